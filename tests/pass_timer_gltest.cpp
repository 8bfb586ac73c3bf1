// PassTimer (issue 19, part 4): pooled GL_TIME_ELAPSED queries are reused, read back in a later
// frame without waiting, and every pass that ran is listed in the frame that ran it. llvmpipe
// implements timer queries, so the pooled mode runs here although the renderer uses wall times
// on it.

#include <gtest/gtest.h>

#include <cmath>

#include "renderer/PassTimer.h"
#include "renderer/gl/GlObjects.h"
#include "tests/TestUtil.h"

namespace candela {
namespace {

/// A pass with some GPU work: clears a 256 x 256 framebuffer a few times.
struct ClearPass {
    gl::Texture2D colour{256, 256, GL_RGBA8};
    gl::Framebuffer fbo{{&colour}, nullptr};
    void run() {
        glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
        glViewport(0, 0, 256, 256);
        for (int i = 0; i < 4; ++i) {
            glClearColor(0.1f * float(i), 0.2f, 0.3f, 1.0f);
            glClear(GL_COLOR_BUFFER_BIT);
        }
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
    }
};

TEST(PassTimer, PooledQueriesAreReusedAndReadAFrameLater) {
    test::glContext();
    ClearPass work;
    PassTimer timer(PassTimer::Pooled);
    const char* names[] = {"gbuffer", "shade:a", "resolve"};
    for (int frame = 0; frame < 40; ++frame) {
        timer.collect();
        FrameStats stats;
        for (const char* name : names) timer.timed(stats, name, [&] { work.run(); });
        // Every pass that ran is listed, in order, with a finite, non-negative time.
        ASSERT_EQ(stats.passes.size(), 3u);
        for (size_t i = 0; i < 3; ++i) {
            EXPECT_EQ(stats.passes[i].name, names[i]);
            EXPECT_TRUE(std::isfinite(stats.passes[i].gpuMs) && stats.passes[i].gpuMs >= 0.0);
        }
        // Before any collect() has read a result, the first frame's times are 0 and none is known.
        if (frame == 0) {
            for (const char* name : names) EXPECT_LT(timer.lastMs(name), 0.0) << name;
        }
        glFinish();  // the GPU has finished the frame: the next collect() reads all three
    }
    timer.collect();
    // Read back: every pass has a time, and nothing is left pending once the GPU is idle.
    for (const char* name : names) EXPECT_GE(timer.lastMs(name), 0.0) << name;
    EXPECT_EQ(timer.queriesPending(), 0u);
    // Reused: with each frame's results read at the next frame's start, the pool holds at most
    // two frames of queries (the frame in flight and the one being collected), not 40.
    EXPECT_LE(timer.queriesMade(), 6u);
}

TEST(PassTimer, WaitedAndWallTimesAreEachFramesOwn) {
    test::glContext();
    ClearPass work;
    for (PassTimer::Mode mode : {PassTimer::Waited, PassTimer::Wall}) {
        PassTimer timer(mode);
        FrameStats stats;
        timer.timed(stats, "shade:a", [&] { work.run(); });
        ASSERT_EQ(stats.passes.size(), 1u);
        EXPECT_TRUE(std::isfinite(stats.passes[0].gpuMs) && stats.passes[0].gpuMs >= 0.0);
        EXPECT_EQ(timer.queriesPending(), 0u);  // nothing left for a later frame
    }
}

}  // namespace
}  // namespace candela
