#pragma once
// A current OpenGL 4.5 core context with its functions loaded. The renderer draws into its own
// framebuffers and cannot tell a window context from an offscreen one.

#include <memory>
#include <string>

struct GLFWwindow;

namespace candela {

class GlContext {
  public:
    virtual ~GlContext() = default;
    virtual void makeCurrent() = 0;
    /// "GL_RENDERER / GL_VERSION" of the context, for logs and bench results.
    std::string description() const;
};

/// KHR_debug: where GL's messages go. Without a handler, debug builds print errors and warnings
/// to stderr and release builds install no callback. With one, every context made after it
/// reports every message to it, synchronously (inside the GL call that caused it), in any build:
/// the GL tests set one that fails the running test on a GL error.
using GlDebugHandler = void (*)(bool error, const char* message);
void setGlDebugHandler(GlDebugHandler handler);

/// Offscreen context for tests, headless renders and benchmarks, chosen by the environment's
/// CANDELA_GL: `osmesa` (the default: Mesa's llvmpipe, what tests and CI run on) or `egl` (a
/// surfaceless EGL context on the first EGL device, a GPU's driver where one is installed; libEGL
/// is loaded at run time). Anything else is refused. `render --stats` prints which ran.
std::unique_ptr<GlContext> createOffscreenContext();

/// A GLFW window with a GL 4.5 core context, for the editor.
class WindowContext : public GlContext {
  public:
    WindowContext(int width, int height, const std::string& title);
    ~WindowContext() override;
    void makeCurrent() override;
    GLFWwindow* window() const { return mWindow; }

  private:
    GLFWwindow* mWindow = nullptr;
};

/// True when a display is available for a window (X11 or Wayland).
bool displayAvailable();

}  // namespace candela
