// A program that draws with GL of its own keeps its EGL context across the library's calls: a render and a renderer's
// end made the renderer's context current on the caller's thread and left it with none (a viewer embedding inkgraph
// lost its context, silently). The caller's context here is an OpenGL ES one on the surfaceless platform, so the bound
// client API is checked too. Needs EGL (llvmpipe in CI).
#include <inkgraph/inkgraph.h>

#include <epoxy/egl.h>
#include <gtest/gtest.h>

#include <string>

namespace ig = inkgraph::api;

namespace inkgraph::test::api_callers_context_gl_test {
namespace {

/** An OpenGL ES context of the caller's own, current on this thread without a surface. */
class CallersOwnContext : public ::testing::Test {
protected:
    void SetUp() override {
        display = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        ASSERT_NE(display, EGL_NO_DISPLAY);
        ASSERT_TRUE(eglInitialize(display, nullptr, nullptr));
        ASSERT_TRUE(eglBindAPI(EGL_OPENGL_ES_API));
        const EGLint configAttributes[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_ES2_BIT, EGL_SURFACE_TYPE, 0, EGL_NONE};
        EGLConfig config = nullptr;
        EGLint configCount = 0;
        ASSERT_TRUE(eglChooseConfig(display, configAttributes, &config, 1, &configCount));
        ASSERT_EQ(configCount, 1);
        const EGLint contextAttributes[] = {EGL_CONTEXT_CLIENT_VERSION, 2, EGL_NONE};
        context = eglCreateContext(display, config, EGL_NO_CONTEXT, contextAttributes);
        ASSERT_NE(context, EGL_NO_CONTEXT);
        ASSERT_TRUE(eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context));
    }
    void TearDown() override {
        if (context != EGL_NO_CONTEXT) {
            eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
            eglDestroyContext(display, context);
        }
    }
    void expectTheCallersContext(const std::string& after) const {
        EXPECT_EQ(eglGetCurrentContext(), context) << after;
        EXPECT_EQ(eglGetCurrentDisplay(), display) << after;
        EXPECT_EQ(eglQueryAPI(), EGLenum(EGL_OPENGL_ES_API)) << after;
    }

    EGLDisplay display = EGL_NO_DISPLAY;
    EGLContext context = EGL_NO_CONTEXT;
};

TEST_F(CallersOwnContext, StaysCurrentAcrossRendersAndTheRenderersEnd) {
    const ig::Scene scene = ig::Scene::load(std::string(INKGRAPH_SOURCE_ROOT) + "/models/suzanne_npm_4k.obj");
    ig::Frame frame;
    frame.width = 32;
    frame.height = 32;
    {
        ig::Renderer renderer;
        const ig::Still first = renderer.render(scene, ig::Look(), frame); // makes the renderer's context
        expectTheCallersContext("the first render");
        const ig::Still second = renderer.render(scene, ig::Look(), frame);
        expectTheCallersContext("a second render");
        EXPECT_EQ(first.picture().byteCount(), second.picture().byteCount());
        // A render that fails lets go too.
        frame.width = 0;
        EXPECT_THROW(renderer.render(scene, ig::Look(), frame), ig::Error);
        expectTheCallersContext("a refused render");
    }
    expectTheCallersContext("the renderer's end");
}

} // namespace
} // namespace inkgraph::test::api_callers_context_gl_test
