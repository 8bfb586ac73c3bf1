#pragma once
#include <string>
#include <vector>

namespace candela {

struct PassTiming {
    std::string name;
    /// Milliseconds. On a GPU, from a pooled GL_TIME_ELAPSED query read back without waiting:
    /// the last result for a pass of this name (a frame or more old; 0 before the first). On a
    /// software rasterizer (llvmpipe), this pass's wall time between glFinish calls around it
    /// (renderer/PassTimer.h).
    double gpuMs = 0.0;
};

/// What the last frame did: exactly the passes that ran, with their GPU times.
struct FrameStats {
    std::vector<PassTiming> passes;
    int accumulatedFrames = 0;  ///< Frames in the current accumulation.
    int samplesPerPixel = 0;    ///< Light samples per pixel per luminaire accumulated so far.
    bool converged = false;     ///< Nothing left to refine: later frames run no pass.
    double totalGpuMs() const {
        double t = 0.0;
        for (const auto& p : passes) t += p.gpuMs;
        return t;
    }
};

}  // namespace candela
