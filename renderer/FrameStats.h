#pragma once
#include <string>
#include <vector>

namespace candela {

struct PassTiming {
    std::string name;
    /// GPU time from a GL_TIME_ELAPSED query, milliseconds; on a software rasterizer (llvmpipe)
    /// the wall time between glFinish calls around the pass (see Renderer.cpp, timed()).
    double gpuMs = 0.0;
};

/// What the last frame did: exactly the passes that ran, with their GPU times.
struct FrameStats {
    std::vector<PassTiming> passes;
    int accumulatedFrames = 0;      ///< Frames in the current accumulation.
    int samplesPerPixel = 0;        ///< Light samples per pixel per luminaire accumulated so far.
    bool converged = false;         ///< Nothing left to refine: later frames run no pass.
    double totalGpuMs() const {
        double t = 0.0;
        for (const auto& p : passes) t += p.gpuMs;
        return t;
    }
};

}  // namespace candela
