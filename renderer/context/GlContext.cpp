#include "renderer/context/GlContext.h"

// GlFunctions.h first: it stands in for GL/gl.h, which osmesa.h would otherwise include.
#include "renderer/gl/GlFunctions.h"

#ifndef GLAPIENTRY
#define GLAPIENTRY APIENTRY
#endif
#include <GL/osmesa.h>
#include <GLFW/glfw3.h>
#define EGL_NO_X11
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <dlfcn.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
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

/// EGL without a window: a GPU's driver where one is installed (NVIDIA's through glvnd, say),
/// for headless renders and benches on real hardware. libEGL is opened at run time, so building
/// and running Candela never needs it unless CANDELA_GL=egl asks for it.
class EglContext final : public GlContext {
  public:
    EglContext() {
        mLibrary = dlopen("libEGL.so.1", RTLD_NOW | RTLD_LOCAL);
        if (!mLibrary)
            throw RuntimeError(
                "EGL: cannot open libEGL.so.1 (CANDELA_GL=egl needs libegl1 and a "
                "GL driver for it)");
        getProc = reinterpret_cast<PFNEGLGETPROCADDRESSPROC>(dlsym(mLibrary, "eglGetProcAddress"));
        if (!getProc) fail("libEGL.so.1 has no eglGetProcAddress");
        load(initialize, "eglInitialize");
        load(terminate, "eglTerminate");
        load(bindApi, "eglBindAPI");
        load(chooseConfig, "eglChooseConfig");
        load(createContext, "eglCreateContext");
        load(destroyContext, "eglDestroyContext");
        load(makeCurrentFn, "eglMakeCurrent");
        load(getError, "eglGetError");
        openDisplay();
        if (!bindApi(EGL_OPENGL_API)) fail("eglBindAPI(EGL_OPENGL_API) failed");
        const EGLint configAttribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
        EGLConfig config = nullptr;
        EGLint count = 0;
        // Mesa's devices offer no configs; a context without one (EGL_KHR_no_config_context)
        // draws into framebuffer objects all the same.
        if (!chooseConfig(mDisplay, configAttribs, &config, 1, &count) || count < 1)
            config = EGL_NO_CONFIG_KHR;
        const EGLint contextAttribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                         4,
                                         EGL_CONTEXT_MINOR_VERSION,
                                         5,
                                         EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                         EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                         EGL_NONE};
        mContext = createContext(mDisplay, config, EGL_NO_CONTEXT, contextAttribs);
        if (mContext == EGL_NO_CONTEXT) fail("could not create a GL 4.5 core context");
        makeCurrent();
        finishSetup([](const char* name) { return reinterpret_cast<void*>(getProc(name)); }, "EGL");
    }
    ~EglContext() override {
        if (mDisplay != EGL_NO_DISPLAY) {
            makeCurrentFn(mDisplay, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
            if (mContext != EGL_NO_CONTEXT) destroyContext(mDisplay, mContext);
            terminate(mDisplay);
        }
        // libEGL stays loaded: drivers register exit handlers that must still find their code.
    }
    void makeCurrent() override {
        // Surfaceless (EGL_KHR_surfaceless_context): Candela draws into its own framebuffers.
        if (!makeCurrentFn(mDisplay, EGL_NO_SURFACE, EGL_NO_SURFACE, mContext))
            fail("eglMakeCurrent without a surface failed");
    }

  private:
    template <typename Fn>
    void load(Fn& fn, const char* name) {
        fn = reinterpret_cast<Fn>(getProc(name));
        if (!fn) fail(std::string("libEGL.so.1 has no ") + name);
    }
    [[noreturn]] void fail(const std::string& what) const {
        char code[32] = "";
        if (getError) std::snprintf(code, sizeof code, " (EGL error 0x%x)", getError());
        throw RuntimeError("EGL: " + what + code);
    }
    /// The first device (EGL_EXT_platform_device) whose display initialises; else the default
    /// display.
    void openDisplay() {
        auto queryDevices =
            reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(getProc("eglQueryDevicesEXT"));
        auto platformDisplay =
            reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(getProc("eglGetPlatformDisplayEXT"));
        EGLint major = 0, minor = 0;
        if (queryDevices && platformDisplay) {
            EGLDeviceEXT devices[16];
            EGLint count = 0;
            if (queryDevices(16, devices, &count)) {
                for (EGLint i = 0; i < count; ++i) {
                    EGLDisplay d = platformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
                    if (d != EGL_NO_DISPLAY && initialize(d, &major, &minor)) {
                        mDisplay = d;
                        return;
                    }
                }
            }
        }
        auto getDisplay = reinterpret_cast<PFNEGLGETDISPLAYPROC>(getProc("eglGetDisplay"));
        if (getDisplay) {
            EGLDisplay d = getDisplay(EGL_DEFAULT_DISPLAY);
            if (d != EGL_NO_DISPLAY && initialize(d, &major, &minor)) {
                mDisplay = d;
                return;
            }
        }
        fail("no display initialises (no EGL device, and no default display)");
    }

    void* mLibrary = nullptr;
    EGLDisplay mDisplay = EGL_NO_DISPLAY;
    EGLContext mContext = EGL_NO_CONTEXT;
    PFNEGLINITIALIZEPROC initialize = nullptr;
    PFNEGLTERMINATEPROC terminate = nullptr;
    PFNEGLBINDAPIPROC bindApi = nullptr;
    PFNEGLCHOOSECONFIGPROC chooseConfig = nullptr;
    PFNEGLCREATECONTEXTPROC createContext = nullptr;
    PFNEGLDESTROYCONTEXTPROC destroyContext = nullptr;
    PFNEGLMAKECURRENTPROC makeCurrentFn = nullptr;
    PFNEGLGETERRORPROC getError = nullptr;

    /// eglGetProcAddress, static for finishSetup's plain function pointer (libEGL's one entry
    /// point, the same for every context).
    static inline PFNEGLGETPROCADDRESSPROC getProc = nullptr;
};

}  // namespace

std::unique_ptr<GlContext> createOffscreenContext() {
    const char* which = std::getenv("CANDELA_GL");
    if (!which || !*which || std::strcmp(which, "osmesa") == 0)
        return std::make_unique<OsMesaContext>();
    if (std::strcmp(which, "egl") == 0) return std::make_unique<EglContext>();
    throw RuntimeError(std::string("CANDELA_GL=") + which +
                       ": unknown offscreen context (use osmesa or egl)");
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
