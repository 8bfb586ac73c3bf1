// The GL tests' KHR_debug handler (tests/TestUtil.cpp): a GL error fails the test that caused
// it, in a Release build too. Without this, a wrong GL call would only log, or not even that.

#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>

#include "renderer/gl/GlFunctions.h"
#include "tests/TestUtil.h"

namespace candela {
namespace {

TEST(GlDebug, AGlErrorFailsTheTestThatCausedIt) {
    test::glContext();
    // Binding a buffer name that was never generated is GL_INVALID_OPERATION in a core profile.
    EXPECT_NONFATAL_FAILURE(glBindBuffer(GL_ARRAY_BUFFER, 987654321u), "GL error");
    glBindBuffer(GL_ARRAY_BUFFER, 0);  // a valid call reports nothing
}

}  // namespace
}  // namespace candela
