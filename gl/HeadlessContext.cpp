#include "gl/HeadlessContext.h"

#include "gl/GlObjects.h"

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <mutex>
#include <sstream>
#include <vector>

#include <unistd.h>

namespace inkgraph {

namespace {

/** The process whose EGL driver is started (its display initialised), 0 when none is: a child forked from it inherits
 *  the driver's state without its threads (llvmpipe's rasterisers), and a context made there would wait for them
 *  forever. */
pid_t gDriverProcess = 0;

/** How many of this process's contexts hold each display they initialised. EGL initialises a display once for the
 *  whole process and eglTerminate() ends it for every context made on it, so the last context to let go terminates
 *  it, not the first (a batch's drawing threads each hold a context: --draw-threads). Guards gDriverProcess too. */
std::mutex gDisplaysMutex;
std::map<EGLDisplay, int> gDisplayHolders;

/** eglInitialize(), counted as one more holder of `display`. */
bool initializeDisplay(EGLDisplay display) {
    const std::lock_guard<std::mutex> lock(gDisplaysMutex);
    EGLint major = 0, minor = 0;
    if (!eglInitialize(display, &major, &minor)) return false;
    gDriverProcess = getpid();
    ++gDisplayHolders[display];
    return true;
}

/** One holder of `display` lets go; the last terminates it, unless `afterUse` in a sanitized build
 *  (INKGRAPH_KEEP_EGL_DISPLAYS: terminating unloads Mesa's driver, whose globals are the only roots of its still-used
 *  caches, and LeakSanitizer would report them as lost from an unmapped library it cannot name; a later context on
 *  the same display initialises it again at no cost). */
void releaseDisplay(EGLDisplay display, [[maybe_unused]] bool afterUse) {
    const std::lock_guard<std::mutex> lock(gDisplaysMutex);
    const auto held = gDisplayHolders.find(display);
    if (held == gDisplayHolders.end() || --held->second > 0) return;
    gDisplayHolders.erase(held);
#ifdef INKGRAPH_KEEP_EGL_DISPLAYS
    if (afterUse) return;
#endif
    eglTerminate(display);
    if (gDisplayHolders.empty()) gDriverProcess = 0;
}

const char* const kInstallHint =
    "Install Mesa's EGL and drivers (apt-get install libegl1 libegl-mesa0 libgl1-mesa-dri) for CPU rendering, or "
    "NVIDIA's driver with its EGL vendor file (10_nvidia.json in /usr/share/glvnd/egl_vendor.d). "
    "Run with EGL_LOG_LEVEL=debug (Mesa) or __EGL_VENDOR_LIBRARY_DEBUG=1 (glvnd) to see more.";

bool hasExtension(const char* extensionList, const char* name) {
    if (extensionList == nullptr) return false;
    const std::size_t length = std::strlen(name);
    for (const char* at = std::strstr(extensionList, name); at != nullptr; at = std::strstr(at + 1, name)) {
        const bool startsWord = at == extensionList || at[-1] == ' ';
        const bool endsWord = at[length] == ' ' || at[length] == '\0';
        if (startsWord && endsWord) return true;
    }
    return false;
}

std::string eglErrorName(EGLint error) {
    switch (error) {
    case EGL_SUCCESS: return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    default: {
        char buffer[32];
        std::snprintf(buffer, sizeof buffer, "0x%04X", static_cast<unsigned>(error));
        return buffer;
    }
    }
}

EglPlatform platformFromEnvironment(EglPlatform requested) {
    const char* value = std::getenv("INKGRAPH_EGL_PLATFORM");
    if (requested != EglPlatform::Any || value == nullptr || *value == '\0') return requested;
    if (std::strcmp(value, "device") == 0) return EglPlatform::Device;
    if (std::strcmp(value, "surfaceless") == 0) return EglPlatform::Surfaceless;
    throw HeadlessContextError(std::string("HeadlessContext(): INKGRAPH_EGL_PLATFORM='") + value +
                               "' is not one of 'device', 'surfaceless'");
}

void GLAPIENTRY printDebugMessage(GLenum, GLenum type, GLuint, GLenum severity, GLsizei, const GLchar* message,
                                  const void*) {
    if (severity == GL_DEBUG_SEVERITY_NOTIFICATION) return;
    std::fprintf(stderr, "inkgraph: GL %s: %s\n", type == GL_DEBUG_TYPE_ERROR ? "error" : "message", message);
}

// One attempt at a display: initialise, pick a config and make a 4.5 core context current without a surface.
struct Attempt {
    EGLDisplay display = EGL_NO_DISPLAY;
    EGLContext context = EGL_NO_CONTEXT;
    std::string failure;
};

Attempt tryDisplay(EGLDisplay display, bool debug) {
    Attempt attempt;
    if (display == EGL_NO_DISPLAY) {
        attempt.failure = "eglGetPlatformDisplayEXT failed (" + eglErrorName(eglGetError()) + ")";
        return attempt;
    }
    if (!initializeDisplay(display)) {
        attempt.failure = "eglInitialize failed (" + eglErrorName(eglGetError()) + ")";
        return attempt;
    }
    const char* displayExtensions = eglQueryString(display, EGL_EXTENSIONS);
    if (!hasExtension(displayExtensions, "EGL_KHR_surfaceless_context")) {
        attempt.failure = "the display lacks EGL_KHR_surfaceless_context";
        releaseDisplay(display, false);
        return attempt;
    }
    if (!eglBindAPI(EGL_OPENGL_API)) {
        attempt.failure = "eglBindAPI(EGL_OPENGL_API) failed: the driver has no desktop OpenGL";
        releaseDisplay(display, false);
        return attempt;
    }
    const EGLint configAttributes[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, 0, EGL_NONE};
    EGLConfig config = nullptr;
    EGLint configCount = 0;
    if (!eglChooseConfig(display, configAttributes, &config, 1, &configCount) || configCount == 0) {
        if (!hasExtension(displayExtensions, "EGL_KHR_no_config_context")) {
            attempt.failure = "no EGL config renders desktop OpenGL";
            releaseDisplay(display, false);
            return attempt;
        }
        config = EGL_NO_CONFIG_KHR;
    }
    // Core 4.5 but not forward-compatible: glLineWidth > 1 stays legal for Lander's outline pass.
    const EGLint contextAttributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                        4,
                                        EGL_CONTEXT_MINOR_VERSION,
                                        5,
                                        EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                        EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                        EGL_CONTEXT_OPENGL_DEBUG,
                                        debug ? EGL_TRUE : EGL_FALSE,
                                        EGL_NONE};
    EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, contextAttributes);
    if (context == EGL_NO_CONTEXT) {
        attempt.failure = "eglCreateContext(OpenGL 4.5 core) failed (" + eglErrorName(eglGetError()) + ")";
        releaseDisplay(display, false);
        return attempt;
    }
    if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
        attempt.failure = "eglMakeCurrent without a surface failed (" + eglErrorName(eglGetError()) + ")";
        eglDestroyContext(display, context);
        releaseDisplay(display, false);
        return attempt;
    }
    attempt.display = display;
    attempt.context = context;
    return attempt;
}

bool isSoftwareDevice(EGLDeviceEXT device) {
    return hasExtension(eglQueryDeviceStringEXT(device, EGL_EXTENSIONS), "EGL_MESA_device_software");
}

} // namespace

std::string forkedDriverRefusal() {
    pid_t driverProcess = 0;
    {
        const std::lock_guard<std::mutex> lock(gDisplaysMutex);
        driverProcess = gDriverProcess;
    }
    if (driverProcess == 0 || driverProcess == getpid()) return {};
    return "this process was forked from process " + std::to_string(driverProcess) +
           " after that one started the EGL driver, whose threads do not exist here; start the driver after the fork "
           "(Python: multiprocessing's 'spawn' or 'forkserver', or close every renderer before forking)";
}

HeadlessContext::HeadlessContext(const HeadlessContextOptions& options) : mProcess(int(getpid())) {
    if (const std::string refusal = forkedDriverRefusal(); !refusal.empty())
        throw HeadlessContextError("HeadlessContext(): " + refusal);
    const EglPlatform platform = platformFromEnvironment(options.platform);
    const char* debugVariable = std::getenv("INKGRAPH_GL_DEBUG");
    const bool debug = options.debugOutput || (debugVariable != nullptr && std::strcmp(debugVariable, "1") == 0);

    // libepoxy aborts the process on the first EGL call when no libEGL can be loaded, so ask it first.
    if (!epoxy_has_egl())
        throw HeadlessContextError(std::string("HeadlessContext(): libEGL.so.1 could not be loaded. ") + kInstallHint);
    const char* clientExtensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!hasExtension(clientExtensions, "EGL_EXT_platform_base"))
        throw HeadlessContextError(
            std::string("HeadlessContext(): the EGL client extensions lack EGL_EXT_platform_base, so no display "
                        "can be made without a window system. ") +
            kInstallHint);

    // libepoxy resolves an EGL entry point on its first call, by the EGL version of the display current then. Resolve
    // eglReleaseThread now, while no display is current: a context destroyed at exit (a static's destructor) after
    // NVIDIA's driver has torn its displays down would otherwise make the first call, and epoxy would find no
    // provider and abort the process. With no context current the call changes nothing that matters here.
    if (eglGetCurrentContext() == EGL_NO_CONTEXT) eglReleaseThread();

    std::vector<std::string> failures;
    Attempt chosen;

    if (platform != EglPlatform::Surfaceless) {
        // EGL_EXT_device_base is enumeration and query in one: NVIDIA's driver (580, through glvnd) names only it.
        const bool enumerates = hasExtension(clientExtensions, "EGL_EXT_device_enumeration") ||
                                hasExtension(clientExtensions, "EGL_EXT_device_base");
        if (!hasExtension(clientExtensions, "EGL_EXT_platform_device") || !enumerates) {
            failures.push_back("device platform: EGL_EXT_platform_device, or EGL_EXT_device_enumeration and "
                               "EGL_EXT_device_base, missing");
        } else {
            EGLDeviceEXT devices[16];
            EGLint deviceCount = 0;
            if (!eglQueryDevicesEXT(16, devices, &deviceCount) || deviceCount == 0) {
                failures.push_back("device platform: no EGL device found");
            }
            // Hardware devices first: Mesa also lists a software device (llvmpipe) on GPU machines.
            std::vector<EGLDeviceEXT> ordered;
            for (EGLint i = 0; i < deviceCount; ++i)
                if (!isSoftwareDevice(devices[i])) ordered.push_back(devices[i]);
            for (EGLint i = 0; i < deviceCount; ++i)
                if (isSoftwareDevice(devices[i])) ordered.push_back(devices[i]);
            for (std::size_t i = 0; i < ordered.size() && chosen.context == EGL_NO_CONTEXT; ++i) {
                EGLDisplay display = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, ordered[i], nullptr);
                Attempt attempt = tryDisplay(display, debug);
                if (attempt.context != EGL_NO_CONTEXT) {
                    chosen = attempt;
                    mPlatform = "device";
                } else {
                    failures.push_back("device platform, device " + std::to_string(i) + ": " + attempt.failure);
                }
            }
        }
    }
    if (chosen.context == EGL_NO_CONTEXT && platform != EglPlatform::Device) {
        if (!hasExtension(clientExtensions, "EGL_MESA_platform_surfaceless")) {
            failures.push_back("surfaceless platform: EGL_MESA_platform_surfaceless missing");
        } else {
            EGLDisplay display = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
            Attempt attempt = tryDisplay(display, debug);
            if (attempt.context != EGL_NO_CONTEXT) {
                chosen = attempt;
                mPlatform = "surfaceless";
            } else {
                failures.push_back("surfaceless platform: " + attempt.failure);
            }
        }
    }
    if (chosen.context == EGL_NO_CONTEXT) {
        std::ostringstream message;
        message << "HeadlessContext(): no OpenGL 4.5 core context could be made without a display. Tried:";
        for (const std::string& failure : failures) message << "\n  - " << failure;
        message << "\n" << kInstallHint;
        throw HeadlessContextError(message.str());
    }
    mDisplay = chosen.display;
    mContext = chosen.context;

    auto glString = [](GLenum name) {
        const auto* text = reinterpret_cast<const char*>(glGetString(name));
        return std::string(text != nullptr ? text : "?");
    };
    mVendor = glString(GL_VENDOR);
    mRenderer = glString(GL_RENDERER);
    mVersion = glString(GL_VERSION);
    if (epoxy_gl_version() < 45) {
        const std::string found = describe();
        releaseEgl();
        throw HeadlessContextError("HeadlessContext(): OpenGL 4.5 is required, the driver gave " + found);
    }
    // Every pass draws with reversed-Z (gl/GlObjects.h), also one run outside GraphExecutor.
    useReversedDepthClipControl();
    glDepthFunc(kDepthNearer);
    if (debug) {
        glEnable(GL_DEBUG_OUTPUT);
        glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
        glDebugMessageCallback(printDebugMessage, nullptr);
    }
}

CallersEglState::CallersEglState()
    : mDisplay(eglGetCurrentDisplay()), mDraw(eglGetCurrentSurface(EGL_DRAW)), mRead(eglGetCurrentSurface(EGL_READ)),
      mContext(eglGetCurrentContext()), mApi(eglQueryAPI()) {}

CallersEglState::~CallersEglState() {
    // No exception leaves a destructor: a context the caller had that cannot be made current again stays released.
    if (mApi != 0 && eglQueryAPI() != EGLenum(mApi)) eglBindAPI(EGLenum(mApi));
    if (mContext != EGL_NO_CONTEXT && eglGetCurrentContext() != mContext)
        eglMakeCurrent(mDisplay, mDraw, mRead, mContext);
}

HeadlessContext::~HeadlessContext() { releaseEgl(); }

void HeadlessContext::releaseEgl() {
    if (mDisplay == nullptr) return;
    // Another context may be current on this thread (several drawing threads' contexts are each destroyed on their
    // own thread, but a caller may do otherwise): only this one is let go here.
    if (eglGetCurrentContext() == mContext) eglMakeCurrent(mDisplay, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (mContext != nullptr) eglDestroyContext(mDisplay, mContext);
    releaseDisplay(mDisplay, true);
    if (eglGetCurrentContext() == EGL_NO_CONTEXT) eglReleaseThread();
    mDisplay = nullptr;
    mContext = nullptr;
}

void HeadlessContext::makeCurrent() {
    if (eglGetCurrentContext() == mContext) return;
    if (!eglMakeCurrent(mDisplay, EGL_NO_SURFACE, EGL_NO_SURFACE, mContext))
        throw HeadlessContextError("HeadlessContext::makeCurrent(): eglMakeCurrent failed (" +
                                   eglErrorName(eglGetError()) + "); is the context current on another thread?");
}

void HeadlessContext::releaseThread() {
    if (eglGetCurrentContext() == mContext) eglMakeCurrent(mDisplay, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
}

std::string HeadlessContext::describe() const {
    return mRenderer + " / " + mVersion + " (" + mVendor + ") via EGL " + mPlatform + " platform";
}

const std::vector<std::string>& softwareRasterizerNames() {
    static const std::vector<std::string> kNames = {"llvmpipe", "softpipe", "swrast", "swiftshader"};
    return kNames;
}

bool isSoftwareRasterizer(std::string_view glRenderer) {
    std::string lower(glRenderer);
    std::transform(lower.begin(), lower.end(), lower.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    for (const std::string& name : softwareRasterizerNames())
        if (lower.find(name) != std::string::npos) return true;
    return false;
}

bool HeadlessContext::isSoftware() const { return isSoftwareRasterizer(mRenderer); }

} // namespace inkgraph
