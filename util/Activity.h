#pragma once
// What the program was doing when it failed for want of memory. std::bad_alloc says nothing of
// where it came from; the steps that can take much memory (reading a file, loading a scene,
// building the interreflection's patches) hold a ScopedActivity, and the innermost one an
// exception unwinds through is kept, so that the command's error can name the file or step:
// "out of memory while reading model.bin (glTF buffer)".

#include <string>

namespace candela {

class ScopedActivity {
  public:
    /// `what` completes "while ...": "reading lamp.ies", "computing the interreflected light of
    /// scene.json".
    explicit ScopedActivity(std::string what);
    ~ScopedActivity();
    ScopedActivity(const ScopedActivity&) = delete;
    ScopedActivity& operator=(const ScopedActivity&) = delete;

  private:
    std::string mWhat;
    int mExceptions;
};

/// The innermost activity the last exception unwound through on this thread (empty when none),
/// and forgets it.
std::string takeFailedActivity();

}  // namespace candela
