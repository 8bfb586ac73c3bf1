#include "util/Activity.h"

#include <exception>
#include <utility>

namespace candela {

namespace {
/// Set by the innermost ScopedActivity an exception unwinds through; kept until taken.
thread_local std::string gFailed;
thread_local bool gFailedSet = false;
}  // namespace

ScopedActivity::ScopedActivity(std::string what)
    : mWhat(std::move(what)), mExceptions(std::uncaught_exceptions()) {
    // A new activity starts after any earlier failure was handled.
    if (mExceptions == 0) gFailedSet = false;
}

ScopedActivity::~ScopedActivity() {
    if (std::uncaught_exceptions() > mExceptions && !gFailedSet) {
        // Destructors must not throw: a failure to copy the text (memory is short) loses it.
        try {
            gFailed = mWhat;
            gFailedSet = true;
        } catch (...) {
        }
    }
}

std::string takeFailedActivity() {
    std::string what = gFailedSet ? gFailed : std::string();
    gFailedSet = false;
    return what;
}

}  // namespace candela
