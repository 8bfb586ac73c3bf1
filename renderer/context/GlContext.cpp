#include "renderer/context/GlContext.h"

// GlFunctions.h first: it stands in for GL/gl.h, which osmesa.h would otherwise include.
#include "renderer/gl/GlFunctions.h"

#ifndef GLAPIENTRY
#define GLAPIENTRY APIENTRY
#endif
#include <GL/osmesa.h>
#include <GLFW/glfw3.h>

#include <cstdio>
#include <cstdlib>
#include <vector>

#include "util/Error.h"

namespace candela {

static GlDebugHandler gDebugHandler = nullptr;

void setGlDebugHandler(GlDebugHandler handler) {
    gDebugHandler = handler;
}

static void APIENTRY debugCallback(GLenum, GLenum type, GLuint, GLenum severity, GLsizei,
                                   const GLchar* message, const void*) {
    if (severity == GL_DEBUG_SEVERITY_NOTIFICATION) return;
    bool error = type == GL_DEBUG_TYPE_ERROR;
    if (gDebugHandler)
        gDebugHandler(error, message);
    else
        std::fprintf(stderr, "GL %s: %s\n", error ? "error" : "debug", message);
}

/// Loads the GL functions and installs the KHR_debug callback: in debug builds, and wherever a
/// handler is set (setGlDebugHandler).
static void finishSetup(gl::ProcAddressFn getProc, const char* what) {
    int missing = gl::loadFunctions(getProc);
    if (!glGetString || !glCreateBuffers)
        throw RuntimeError(std::string(what) + ": GL 4.5 entry points missing (" +
                           std::to_string(missing) + " unresolved)");
#ifdef NDEBUG
    if (!gDebugHandler) return;
#endif
    glEnable(GL_DEBUG_OUTPUT);
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    glDebugMessageCallback(debugCallback, nullptr);
}

std::string GlContext::description() const {
    auto str = [](GLenum e) {
        const GLubyte* s = glGetString(e);
        return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("?");
    };
    return str(GL_RENDERER) + " / " + str(GL_VERSION);
}

namespace {

class OsMesaContext final : public GlContext {
  public:
    OsMesaContext() {
        const int attribs[] = {OSMESA_FORMAT,
                               OSMESA_RGBA,
                               OSMESA_DEPTH_BITS,
                               24,
                               OSMESA_PROFILE,
                               OSMESA_CORE_PROFILE,
                               OSMESA_CONTEXT_MAJOR_VERSION,
                               4,
                               OSMESA_CONTEXT_MINOR_VERSION,
                               5,
                               0};
        mContext = OSMesaCreateContextAttribs(attribs, nullptr);
        if (!mContext)
            throw RuntimeError(
                "OSMesa: could not create a GL 4.5 core context (is libosmesa6 installed?)");
        makeCurrent();
        finishSetup(
            [](const char* name) { return reinterpret_cast<void*>(OSMesaGetProcAddress(name)); },
            "OSMesa");
    }
    ~OsMesaContext() override { OSMesaDestroyContext(mContext); }
    void makeCurrent() override {
        // Candela renders into its own framebuffers; the default one is a 1x1 placeholder.
        if (!OSMesaMakeCurrent(mContext, mPixels.data(), GL_UNSIGNED_BYTE, 1, 1))
            throw RuntimeError("OSMesa: OSMesaMakeCurrent failed");
    }

  private:
    OSMesaContext mContext = nullptr;
    std::vector<unsigned char> mPixels = std::vector<unsigned char>(4 * 4);
};

}  // namespace

std::unique_ptr<GlContext> createOffscreenContext() {
    return std::make_unique<OsMesaContext>();
}

bool displayAvailable() {
    const char* x = std::getenv("DISPLAY");
    const char* w = std::getenv("WAYLAND_DISPLAY");
    return (x && *x) || (w && *w);
}

WindowContext::WindowContext(int width, int height, const std::string& title) {
    glfwSetErrorCallback(
        [](int code, const char* msg) { std::fprintf(stderr, "GLFW error %d: %s\n", code, msg); });
    if (!glfwInit()) throw RuntimeError("GLFW: initialisation failed (no display?)");
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    mWindow = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
    if (!mWindow) {
        glfwTerminate();
        throw RuntimeError("GLFW: could not open a window with a GL 4.5 core context");
    }
    makeCurrent();
    glfwSwapInterval(0);
    finishSetup([](const char* name) { return reinterpret_cast<void*>(glfwGetProcAddress(name)); },
                "GLFW");
}

WindowContext::~WindowContext() {
    if (mWindow) glfwDestroyWindow(mWindow);
    glfwTerminate();
}

void WindowContext::makeCurrent() {
    glfwMakeContextCurrent(mWindow);
}

}  // namespace candela
