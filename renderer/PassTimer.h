#pragma once
// Times the passes of a frame for the frame statistics (FrameStats), whichever object runs them.

#include <deque>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "renderer/FrameStats.h"
#include "renderer/gl/GlObjects.h"

namespace candela {

/// True on Mesa's software rasterizer, whose GL_TIME_ELAPSED queries end before its rasterizer
/// threads have run the pass's fragment shaders whenever those sample textures (measured: the
/// restricted-cdf pass at 960x540 reads 26 ms from its query and takes 1.6 s to glFinish).
bool softwareRasterizer();

class PassTimer {
  public:
    enum Mode {
        Wall,    ///< The wall time between a glFinish before the pass and one after it.
        Waited,  ///< A GPU timer query, waited for: exact, but the CPU stalls until the GPU is
                 ///< done.
        Pooled,  ///< GPU timer queries from a pool, read back a frame or more later, never waiting.
    };
    /// On a software rasterizer always Wall (the CPU is the GPU); on a GPU, Pooled, or Waited
    /// where each frame's own times matter more than a stall (benches, the comparison).
    static Mode defaultMode(bool exact) {
        return softwareRasterizer() ? Wall : exact ? Waited : Pooled;
    }
    explicit PassTimer(Mode mode) : mMode(mode) {}
    void setMode(Mode mode) { mMode = mode; }
    Mode mode() const { return mMode; }

    /// Runs fn and records it as pass `name` in stats. Wall, Waited: with its time. Pooled:
    /// with the last time read for a pass of that name (0 before the first), since the query
    /// issued now is read at a later frame's collect(), once the GPU has its result.
    void timed(FrameStats& stats, const std::string& name, const std::function<void()>& fn);
    /// At the start of a frame: reads the queries whose results are there, in the order they
    /// were issued, without waiting, and returns them to the pool.
    void collect();

    size_t queriesMade() const { return mMade; }  ///< Pool size: queries ever created.
    size_t queriesPending() const { return mPending.size(); }
    /// The last GPU time read for pass `name`, milliseconds; negative when none yet.
    double lastMs(const std::string& name) const;

  private:
    struct Pending {
        gl::TimerQuery query;
        std::string name;
    };
    Mode mMode;
    std::vector<gl::TimerQuery> mFree;
    std::deque<Pending> mPending;
    std::map<std::string, double> mLast;
    size_t mMade = 0;
};

}  // namespace candela
