// The floor of start-up: a whole process that makes an OpenGL 4.5 core context on EGL's device platform (no surface),
// reads GL_RENDERER, clears one pixel and reads it back, and exits. Nothing of inkgraph is linked: this is what any
// headless GL program pays before its first useful draw, so issue 20 measures a tiny still against it
// (bench/whole-process.sh).
//   inkgraph_egl_probe            prints the renderer; exit 0 when a context was made
#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <cstdio>
#include <cstring>

namespace {

bool hasExtension(const char* list, const char* name) {
    if (list == nullptr) return false;
    const std::size_t length = std::strlen(name);
    for (const char* at = std::strstr(list, name); at != nullptr; at = std::strstr(at + 1, name))
        if ((at == list || at[-1] == ' ') && (at[length] == ' ' || at[length] == '\0')) return true;
    return false;
}

/** The first device (hardware before software, as inkgraph orders them) that gives a 4.5 core context. */
bool makeContext() {
    const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!hasExtension(client, "EGL_EXT_platform_device")) return false;
    EGLDeviceEXT devices[16];
    EGLint count = 0;
    if (!eglQueryDevicesEXT(16, devices, &count)) return false;
    for (int pass = 0; pass < 2; ++pass) {
        for (EGLint i = 0; i < count; ++i) {
            const char* extensions = eglQueryDeviceStringEXT(devices[i], EGL_EXTENSIONS);
            const bool software = hasExtension(extensions, "EGL_MESA_device_software");
            if (software != (pass == 1)) continue;
            EGLDisplay display = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
            EGLint major = 0, minor = 0;
            if (display == EGL_NO_DISPLAY || !eglInitialize(display, &major, &minor)) continue;
            if (!eglBindAPI(EGL_OPENGL_API)) continue;
            const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                         4,
                                         EGL_CONTEXT_MINOR_VERSION,
                                         5,
                                         EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                         EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                         EGL_NONE};
            EGLContext context = eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
            if (context == EGL_NO_CONTEXT) continue;
            if (eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) return true;
        }
    }
    return false;
}

} // namespace

int main() {
    if (!makeContext()) {
        std::fprintf(stderr, "inkgraph_egl_probe: no OpenGL 4.5 core context on EGL's device platform\n");
        return 1;
    }
    // One cleared pixel read back: the driver has really started, not only returned a handle.
    GLuint texture = 0, framebuffer = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &texture);
    glTextureStorage2D(texture, 1, GL_RGBA8, 1, 1);
    glCreateFramebuffers(1, &framebuffer);
    glNamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT0, texture, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    glClearColor(1.0f, 0.5f, 0.25f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    unsigned char pixel[4] = {0, 0, 0, 0};
    glReadPixels(0, 0, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, pixel);
    std::printf("%s: cleared pixel %d,%d,%d\n", reinterpret_cast<const char*>(glGetString(GL_RENDERER)), pixel[0],
                pixel[1], pixel[2]);
    return pixel[0] == 255 ? 0 : 1;
}
