// The still graph as the registry builds it: the passes in the order the app has always run them (every GL pass
// before the CPU line layers, the shared mesh-edges pass once), and only what the drawn types need kept live.
#include "graph/GraphCompiler.h"
#include "passes/StillGraph.h"
#include "passes/gbuffer/GBufferPass.h"
#include "passes/lines/LineTypes.h"
#include "scene/mesh/Procedural.h"
#include "tests/support/GlTestContext.h"
#include "tests/support/PassHarness.h"
#include "tests/support/TestCamera.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace inkgraph {
namespace {

class StillGraphOrder : public ::testing::Test, protected test::PassHarness {
protected:
    void SetUp() override {
        test::sharedGlContext();
        scene = makeScene(makeCube({0.0f, 0.0f, 0.0f}, 1.0f));
        frame.camera = test::lookingAt(scene, {2.5, 1.8, 2.0}, glm::dvec3(0.0), 35.0, 64, 64);
        gpuScene = std::make_unique<GpuScene>(scene, frame.worldOrigin);
    }

    std::vector<std::string> planOrder(const Look& look) {
        StillGraphSetup setup{look, shaders, scene, computeBoundingSphere(scene), *gpuScene, frame, std::nullopt};
        const StillGraph graph = buildStillGraph(setup);
        std::vector<std::string> names;
        for (const PlannedPass& pass : compile(graph.view(), {graph.finalResource}).passes) names.push_back(pass.name);
        return names;
    }
};

TEST_F(StillGraphOrder, GlPassesComeBeforeTheLineLayersAndSharedPassesAreRegisteredOnce) {
    Look look;
    look.lines = {"crease", "normal-edge", "border", "outline"};
    // GL passes in the order their types first register them: mesh-edges by the hidden types, first in the registry.
    EXPECT_EQ(planOrder(look), (std::vector<std::string>{"gbuffer", "shade", "mesh-edges", "outline", "normal-edge",
                                                         "crease", "border", "strokes", "composite"}));
}

/** The silhouette tests its hull against the G-buffer's z-buffer only where that is free and the same depth: the
 *  G-buffer runs anyway, at the mask's size, with every face of every mesh drawn. */
TEST_F(StillGraphOrder, TheSilhouetteReadsTheGBuffersZBufferOnlyWhenItRunsAnywayWithEveryFace) {
    const auto silhouetteReads = [&](const Look& look) {
        StillGraphSetup setup{look, shaders, scene, computeBoundingSphere(scene), *gpuScene, frame, std::nullopt};
        const StillGraph graph = buildStillGraph(setup);
        const Plan plan = compile(graph.view(), {graph.finalResource});
        const PlannedPass* silhouette = plan.findPass("silhouette");
        return silhouette ? silhouette->reads : std::vector<std::string>{"(not run)"};
    };
    const std::vector<std::string> zBuffer{"gbuffer.zBuffer"};
    Look look;
    look.lines = {"silhouette", "contour"};
    EXPECT_EQ(silhouetteReads(look), zBuffer) << "contours make the G-buffer run";
    look.shading = ShadingModel::Flat;
    EXPECT_EQ(silhouetteReads(look), zBuffer) << "whatever the shading";
    look.shading = ShadingModel::Cel;
    look.lines = {"silhouette"};
    EXPECT_EQ(silhouetteReads(look), std::vector<std::string>{}) << "no line reads the G-buffer: it does not run";
    look.lines = {"silhouette", "contour"};
    look.supersample = 2;
    EXPECT_EQ(silhouetteReads(look), std::vector<std::string>{}) << "a supersampled z-buffer is not the mask's size";
    look.supersample = 1;
    scene.meshes[0].material.doubleSided = false;
    gpuScene = std::make_unique<GpuScene>(scene, frame.worldOrigin);
    EXPECT_EQ(silhouetteReads(look), std::vector<std::string>{}) << "single-sided: the G-buffer culls back faces";
    scene.meshes[0].material.doubleSided = true;
    scene.meshes[0].material.alphaMode = AlphaMode::Mask;
    gpuScene = std::make_unique<GpuScene>(scene, frame.worldOrigin);
    EXPECT_EQ(silhouetteReads(look), std::vector<std::string>{}) << "cut-outs stay the pass's own";
}

/** Without --stats the executor does not wait for each pass (ExecuteOptions::waitForEachPass): the driver may still
 *  be drawing one pass while the next submits, and the picture must be the same to the bit. */
TEST_F(StillGraphOrder, PassesThatDoNotWaitForEachOtherMakeTheSamePicture) {
    Look look;
    look.lines = {"silhouette", "contour", "suggestive", "crease"};
    frame.camera = test::lookingAt(scene, {2.5, 1.8, 2.0}, glm::dvec3(0.0), 35.0, 256, 192);
    StillGraphSetup setup{look, shaders, scene, computeBoundingSphere(scene), *gpuScene, frame, std::nullopt};
    const StillGraph graph = buildStillGraph(setup);
    const Plan plan = compile(graph.view(), {graph.finalResource});
    ExecuteOptions options{256, 192, false};
    executor.run(plan, graph.mutableView(), options);
    const cv::Mat waited = executor.store().image(graph.finalResource).clone();
    options.waitForEachPass = false;
    executor.run(plan, graph.mutableView(), options);
    const cv::Mat overlapped = executor.store().image(graph.finalResource);
    ASSERT_EQ(waited.size(), overlapped.size());
    EXPECT_GT(cv::countNonZero(waited.reshape(1) != 255), 1000) << "the cube and its lines must show";
    EXPECT_EQ(cv::countNonZero(waited.reshape(1) != overlapped.reshape(1)), 0);
}

/** Above 2047 rows the image-space suggestive contours are found on a G-buffer of their own at 1024-2047 rows
 *  (issue 39: which crossings the kernel finds and which short pieces the rules keep change with the sampling): at
 *  2048 x 2048 the kernel's skeleton is, pixel for pixel and point for point, the one a 1024 x 1024 picture finds,
 *  and only the strokes are drawn at the picture's size. */
TEST_F(StillGraphOrder, SuggestiveContoursAt2048RowsAreTheOnesFoundAt1024) {
    scene = makeScene(makeTorus(1.0f, 0.4f, 192, 96));
    gpuScene = std::make_unique<GpuScene>(scene, frame.worldOrigin);
    Look look;
    look.shading = ShadingModel::None;
    look.lines = {"contour", "suggestive"};
    const auto render = [&](int side) {
        frame.camera = test::lookingAt(scene, {0.0, 3.0, 1.8}, glm::dvec3(0.0), 35.0, side, side);
        StillGraphSetup setup{look, shaders, scene, computeBoundingSphere(scene), *gpuScene, frame, std::nullopt};
        const StillGraph graph = buildStillGraph(setup);
        const Plan plan = compile(graph.view(), {graph.finalResource, "suggestive.skeleton", "strokes.suggestive"});
        const PlannedResource* field = plan.findResource("suggestive-field.radial");
        if (side == 2048) {
            EXPECT_NE(field, nullptr) << plan.describe();
            if (field != nullptr) {
                EXPECT_EQ(field->desc.divisor, 2);
            }
            EXPECT_EQ(plan.findResource("suggestive.skeleton")->object.divisor, 2);
            const PlannedPass* fieldPass = plan.findPass("suggestive-field");
            EXPECT_NE(fieldPass, nullptr);
            if (fieldPass != nullptr) {
                EXPECT_EQ(fieldPass->liveWrites,
                          (std::vector<std::string>{"suggestive-field.depth", "suggestive-field.radial"}))
                    << "only what the kernel reads (a torus's surfaces do not meet: no triangle ids)";
            }
        } else {
            EXPECT_EQ(plan.findPass("suggestive-field"), nullptr) << "1024 rows: the picture's own G-buffer";
        }
        executor.run(plan, graph.mutableView(), ExecuteOptions{side, side, false});
        const cv::Mat drawn = executor.store().image("strokes.suggestive").clone();
        EXPECT_EQ(drawn.size(), cv::Size(side, side));
        return std::make_pair(executor.store().object<LineSkeleton>("suggestive.skeleton"), drawn);
    };
    const auto [small, smallLines] = render(1024);
    const auto [large, largeLines] = render(2048);
    ASSERT_EQ(large.mask.size(), cv::Size(1024, 1024));
    EXPECT_GT(cv::countNonZero(small.mask), 200) << "the torus's inner side has suggestive contours";
    EXPECT_EQ(cv::countNonZero(small.mask != large.mask), 0);
    ASSERT_EQ(small.points.size(), large.points.size());
    for (std::size_t index = 0; index < small.points.size(); ++index) {
        EXPECT_EQ(small.points[index].position, large.points[index].position) << index;
        EXPECT_EQ(small.points[index].strength, large.points[index].strength) << index;
    }
    GBufferPass unknown("g", shaders, *gpuScene, frame);
    EXPECT_THROW(unknown.declareOnly({"radial", "radius"}), std::invalid_argument);
    // The strokes are drawn at 2048 x 2048, twice as long and as many pixels wide as the style says (2 at 1024 and
    // at 2048 alike): about twice the ink pixels of 1024, not four times.
    const double inkRatio = double(cv::countNonZero(largeLines)) / double(cv::countNonZero(smallLines));
    EXPECT_GT(inkRatio, 1.6);
    EXPECT_LT(inkRatio, 2.6);
}

TEST_F(StillGraphOrder, EveryRegisteredTypeHasItsLayerOrPassAndTheCompositeReadsThemInRegistryOrder) {
    Look look;
    look.shading = ShadingModel::None;
    for (const LineType& type : lineTypes()) look.lines.push_back(type.name);
    std::reverse(look.lines.begin(), look.lines.end()); // the user's order does not change the composite's
    StillGraphSetup setup{look, shaders, scene, computeBoundingSphere(scene), *gpuScene, frame, std::nullopt};
    const StillGraph graph = buildStillGraph(setup);
    const Plan plan = compile(graph.view(), {graph.finalResource});
    const PlannedPass* composite = plan.findPass("composite");
    ASSERT_NE(composite, nullptr);
    std::vector<std::string> expected;
    for (const LineType& type : lineTypes()) expected.push_back("strokes." + type.name);
    EXPECT_EQ(composite->reads, expected);
    // The stroke stage reads every type's skeleton, or the band a GL pass drew.
    std::vector<std::string> skeletons;
    for (const LineType& type : lineTypes())
        skeletons.push_back(type.name + (type.strokedOnCpu() ? ".skeleton" : ".lines"));
    EXPECT_EQ(plan.findPass("strokes")->reads, skeletons);
    EXPECT_TRUE(plan.culled.empty()) << plan.culled.front().name << ": " << plan.culled.front().reason;
}

} // namespace
} // namespace inkgraph
