// Deferred shading gives the forward picture: the same still graph built twice over one scene, once as built (the
// lines read the G-buffer, so shading is deferred) and once with the shade pass told that no line reads it (forward),
// and the two shade.color images compared. Spheres with one base colour (a uniform in deferred shading, so the
// same numbers: llvmpipe gives 0 codes of difference), with vertex colours (the G-buffer's sRGB8 copy of the base
// colour), the bunny, and the textured fox. Needs a GL context (llvmpipe in CI).
#include "graph/GraphCompiler.h"
#include "passes/StillGraph.h"
#include "passes/gbuffer/GBufferPass.h"
#include "passes/shade/ShadePass.h"
#include "scene/mesh/Procedural.h"
#include "tests/support/GlTestContext.h"
#include "tests/support/ImageCompare.h"
#include "tests/support/PassHarness.h"

#include <gtest/gtest.h>

#include <string>

namespace inkgraph::deferred_shading_gl_test {
namespace {

constexpr int kSize = 256;

// Both modes compute the normal and view vector by the same expressions from the same interpolated attributes, and
// the base colour either as the same uniform or from the G-buffer's sRGB8 copy, which is off by at most half a code
// before shading; a shading factor <= 1 does not enlarge that, so with the output's own rounding every channel may
// differ by 1 code. Coverage is the same rasterisation (the G-buffer's, and the forward pass's with the same vertex
// transform). A pixel whose normal lands exactly on a band border may take the other band if a driver contracts the
// two programs' arithmetic differently: 1e-4 of the pixels (6 of 256 x 256) may do so.
const test::ImageTolerance kSamePicture{1.0, 0.5, 1e-4};

class DeferredShading : public ::testing::Test, protected test::PassHarness {
protected:
    void SetUp() override { test::sharedGlContext(); }

    /** shade.color of `look` over `scene`, auto-framed: deferred as the graph chooses it, and forced forward. */
    void expectSamePicture(const Look& look, const std::string& name, const CameraRequest& camera = {}) {
        CameraRequest request = camera;
        request.width = kSize;
        request.height = kSize;
        frame.camera = resolveCamera(request, scene);
        const BoundingSphere sphere = computeBoundingSphere(scene);
        frame.worldOrigin = sphere.center;
        frame.towardLightWorld = glm::normalize(glm::dvec3(-0.4, 0.5, 0.77));
        // As the renderer does: deferred shading keeps to the scene's bounds, so the coverage check below also finds
        // any covered pixel the bounds would cut off.
        frame.boundScene(scene);
        const PixelRect bounds = frame.scenePixels(kSize, kSize);
        EXPECT_LT(bounds.width * bounds.height, kSize * kSize) << name << ": the bounds should leave some of the frame";
        gpuScene = std::make_unique<GpuScene>(scene, frame.worldOrigin);

        StillGraph deferred = buildStillGraph({look, shaders, scene, sphere, *gpuScene, frame, std::nullopt});
        const Plan decided = deferred.compilePlan({deferred.finalResource});
        ASSERT_EQ(deferred.shadingModeIn(decided), "deferred")
            << name << ": " << deferred.shadingForwardReasonIn(decided);
        StillGraphSetup forwardSetup{look, shaders, scene, sphere, *gpuScene, frame, std::nullopt};
        forwardSetup.allowDeferredShading = false;
        StillGraph forward = buildStillGraph(forwardSetup);
        ASSERT_EQ(forward.shadingModeIn(forward.compilePlan({forward.finalResource})), "forward");

        const cv::Mat deferredColor = shadeColor(deferred);
        const cv::Mat forwardColor = shadeColor(forward);
        EXPECT_TRUE(
            test::imagesNear(deferredColor, forwardColor, kSamePicture, "DeferredShading." + name, "shade.color"));
        // Transparent black off the model in both: the paper shows through the same pixels.
        int covered = 0;
        for (int row = 0; row < kSize; ++row)
            for (int column = 0; column < kSize; ++column) {
                const bool deferredCovers = deferredColor.at<cv::Vec4b>(row, column)[3] != 0;
                covered += deferredCovers;
                EXPECT_EQ(deferredCovers, forwardColor.at<cv::Vec4b>(row, column)[3] != 0)
                    << name << ": coverage differs at (" << column << ", " << row << ")";
            }
        EXPECT_GT(covered, kSize * kSize / 20) << name << ": the model should cover part of the picture";
    }

    cv::Mat shadeColor(const StillGraph& graph) {
        // The still's decision, for the final picture, then the shading kept.
        const Plan plan = graph.compilePlan({graph.finalResource, "shade.color"});
        executor.run(plan, graph.mutableView(), {kSize, kSize, false});
        cv::Mat color = executor.store().image("shade.color").clone();
        executor.store().clear();
        return color;
    }

    static Look comicStill(ShadingModel model) {
        Look look;
        look.shading = model;
        look.lines = {"silhouette", "contour", "suggestive"};
        return look;
    }
};

const ShadingModel kDeferredModels[] = {ShadingModel::Cel, ShadingModel::Lambert, ShadingModel::Phong,
                                        ShadingModel::Comic};

TEST_F(DeferredShading, SphereOfOneColourMatchesForward) {
    scene = makeScene(makeUvSphere({0.0f, 0.0f, 0.0f}, 1.0f, 96, 48));
    for (const ShadingModel model : kDeferredModels)
        expectSamePicture(comicStill(model), std::string("sphere_") + traitsOf(model).name);
    Look constant = comicStill(ShadingModel::Comic);
    constant.viewVector = ViewVectorMode::Constant;
    expectSamePicture(constant, "sphere_comic_constant_view");
}

TEST_F(DeferredShading, SphereWithVertexColoursMatchesForward) {
    // Colours that vary over the surface: deferred shading reads them from the G-buffer's baseColor.
    Mesh sphere = makeUvSphere({0.0f, 0.0f, 0.0f}, 1.0f, 96, 48);
    for (const glm::vec3& position : sphere.positions) sphere.colors.push_back(glm::vec4(0.5f + 0.5f * position, 1.0f));
    scene = makeScene(sphere);
    for (const ShadingModel model : kDeferredModels)
        expectSamePicture(comicStill(model), std::string("coloured_sphere_") + traitsOf(model).name);
}

TEST_F(DeferredShading, BunnyMatchesForward) {
    scene = loadScene((test::sourceRoot() / "models" / "bunny_c3d_70k.obj").string());
    for (const ShadingModel model : kDeferredModels)
        expectSamePicture(comicStill(model), std::string("bunny_") + traitsOf(model).name);
}

TEST_F(DeferredShading, TexturedFoxMatchesForward) {
    scene = loadScene((test::sourceRoot() / "models" / "characters" / "fox.glb").string());
    for (const ShadingModel model : {ShadingModel::Cel, ShadingModel::Phong})
        expectSamePicture(comicStill(model), std::string("fox_") + traitsOf(model).name);
}

TEST_F(DeferredShading, KeptToTheSceneBoundsItShadesEveryPixelForwardShadingCovers) {
    // The bunny seen close from an eye off the axis, looking below and left of it: the model runs off the frame's top,
    // left and right edges, so the bounds are clamped there and tight only below, and every pixel the forward pass
    // covers must still be shaded (expectSamePicture's coverage check).
    scene = loadScene((test::sourceRoot() / "models" / "bunny_c3d_70k.obj").string());
    const BoundingSphere sphere = computeBoundingSphere(scene);
    CameraRequest close;
    close.eye = sphere.center + glm::dvec3(0.3, 0.2, 2.2) * sphere.radius;
    close.target = sphere.center + glm::dvec3(-0.25, -0.2, 0.0) * sphere.radius;
    expectSamePicture(comicStill(ShadingModel::Cel), "bunny_close_off_axis", close);
    const PixelRect bounds = frame.scenePixels(kSize, kSize);
    EXPECT_EQ(bounds.width, kSize) << "the bunny runs off both sides";
    EXPECT_EQ(bounds.y + bounds.height, kSize) << "and off the top";
    EXPECT_GT(bounds.y, kSize / 2) << "and stays in the top half";
}

} // namespace
} // namespace inkgraph::deferred_shading_gl_test
