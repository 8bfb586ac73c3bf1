#include "renderer/PassTimer.h"

#include <chrono>
#include <cstring>

namespace candela {

bool softwareRasterizer() {
    static const bool software = [] {
        const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
        return renderer && (std::strstr(renderer, "llvmpipe") || std::strstr(renderer, "softpipe"));
    }();
    return software;
}

void PassTimer::timed(FrameStats& stats, const std::string& name, const std::function<void()>& fn) {
    if (mMode == Wall) {
        glFinish();
        auto start = std::chrono::steady_clock::now();
        fn();
        glFinish();
        stats.passes.push_back({name, std::chrono::duration<double, std::milli>(
                                          std::chrono::steady_clock::now() - start)
                                          .count()});
        return;
    }
    if (mMode == Waited) {
        gl::TimerQuery query;
        query.begin();
        fn();
        query.end();
        stats.passes.push_back({name, query.milliseconds()});
        return;
    }
    if (mFree.empty()) {
        mFree.emplace_back();
        ++mMade;
    }
    Pending p{std::move(mFree.back()), name};
    mFree.pop_back();
    p.query.begin();
    fn();
    p.query.end();
    mPending.push_back(std::move(p));
    double last = lastMs(name);
    stats.passes.push_back({name, last < 0.0 ? 0.0 : last});
}

void PassTimer::collect() {
    // Queries finish in the order they were issued: stop at the first without its result.
    while (!mPending.empty() && mPending.front().query.available()) {
        Pending& p = mPending.front();
        mLast[p.name] = p.query.milliseconds();
        mFree.push_back(std::move(p.query));
        mPending.pop_front();
    }
}

double PassTimer::lastMs(const std::string& name) const {
    auto found = mLast.find(name);
    return found == mLast.end() ? -1.0 : found->second;
}

}  // namespace candela
