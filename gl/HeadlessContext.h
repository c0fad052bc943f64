#pragma once
/** @file An OpenGL 4.5 core context with no window and no X server, through EGL.
 *  Tries the EGL device platform first (what NVIDIA machines use; hardware devices before Mesa's software device),
 *  then Mesa's surfaceless platform. The context is not forward-compatible, so wide lines stay available. */

#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace inkgraph {

/** True for the GL_RENDERER strings of rasterizers that run on the CPU (Mesa's llvmpipe, softpipe and swrast, Google's
 *  SwiftShader; case-insensitive), whose "GPU" work competes with ours for the same cores. */
bool isSoftwareRasterizer(std::string_view glRenderer);

/** The renderer names isSoftwareRasterizer() knows (matched case-blind within GL_RENDERER): "llvmpipe", ... */
const std::vector<std::string>& softwareRasterizerNames();

/** Why no context can be made in this process, or nothing: it was forked from the process that started the EGL
 *  driver, whose threads (llvmpipe's rasterisers) do not exist here, so a context would wait for them forever.
 *  HeadlessContext() refuses with it after its own name; the library's Renderer::render() before making one, after
 *  its. */
std::string forkedDriverRefusal();

/** No display or context could be made. The message names what is missing and how to see more. */
class HeadlessContextError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

enum class EglPlatform { Any, Device, Surfaceless };

struct HeadlessContextOptions {
    EglPlatform platform = EglPlatform::Any; ///< INKGRAPH_EGL_PLATFORM=device|surfaceless overrides Any
    bool debugOutput = false;                ///< KHR_debug messages to stderr (INKGRAPH_GL_DEBUG=1 also enables)
};

/** While it lives, a library call may make its own context current on this thread: at its end, the thread's EGL
 *  state as the caller had it is put back (the context, its display and surfaces, and the bound client API), so a
 *  program that draws with GL of its own keeps its context across a render. The command line has none to keep. */
class CallersEglState {
public:
    CallersEglState();
    ~CallersEglState();
    CallersEglState(const CallersEglState&) = delete;
    CallersEglState& operator=(const CallersEglState&) = delete;

private:
    void* mDisplay = nullptr;
    void* mDraw = nullptr;
    void* mRead = nullptr;
    void* mContext = nullptr;
    unsigned mApi = 0;
};

/** Owns an EGL context and a hold on its display; make it the first member of an app or fixture so it outlives every
 *  GL object. Several may live at once, each current on its own thread: EGL shares a display across the process, so
 *  the last context made on it terminates it. */
class HeadlessContext {
public:
    /** Creates the context and makes it current on this thread. Throws HeadlessContextError. */
    explicit HeadlessContext(const HeadlessContextOptions& options = {});
    ~HeadlessContext();
    HeadlessContext(const HeadlessContext&) = delete;
    HeadlessContext& operator=(const HeadlessContext&) = delete;

    /** "device" or "surfaceless" */
    const std::string& platform() const { return mPlatform; }
    /** GL_VENDOR, GL_RENDERER, GL_VERSION of the current context. */
    const std::string& vendor() const { return mVendor; }
    const std::string& renderer() const { return mRenderer; }
    /** isSoftwareRasterizer() of this context's renderer. */
    bool isSoftware() const;
    const std::string& version() const { return mVersion; }
    /** e.g. "llvmpipe (LLVM 15.0.6, 256 bits) / 4.5 (Core Profile) Mesa 22.3.6 via EGL device platform" */
    std::string describe() const;

    /** Makes the context current on the calling thread; it must not be current on another one (releaseThread() there
     *  first). Throws HeadlessContextError. */
    void makeCurrent();
    /** Leaves the calling thread without a context, so another thread may make this one current. */
    void releaseThread();
    /** The process that made the context. A forked child inherits the driver's state but none of its threads, so
     *  nothing there may call into it: not even to free it. */
    int owningProcess() const { return mProcess; }

private:
    void releaseEgl();

    void* mDisplay = nullptr;
    void* mContext = nullptr;
    int mProcess = 0;
    std::string mPlatform;
    std::string mVendor;
    std::string mRenderer;
    std::string mVersion;
};

} // namespace inkgraph
