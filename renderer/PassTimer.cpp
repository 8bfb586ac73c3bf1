#include "renderer/PassTimer.h"

#include <chrono>
#include <cstring>

#include "renderer/gl/GlObjects.h"

namespace candela {

bool softwareRasterizer() {
    static const bool software = [] {
        const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
        return renderer && (std::strstr(renderer, "llvmpipe") || std::strstr(renderer, "softpipe"));
    }();
    return software;
}

void timed(FrameStats& stats, const std::string& name, const std::function<void()>& fn) {
    if (softwareRasterizer()) {
        glFinish();
        auto start = std::chrono::steady_clock::now();
        fn();
        glFinish();
        stats.passes.push_back(
            {name, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count()});
        return;
    }
    gl::TimerQuery query;
    query.begin();
    fn();
    query.end();
    stats.passes.push_back({name, query.milliseconds()});
}

}  // namespace candela
