// Forward or deferred shading, as one compile of the still graph decides it (ShadePass::forwardReason()): one rule per
// test, each on a look and a scene, read from the compiled plan (what the shade pass reads) and the graph's facts for
// --stats. No GL: building and compiling the graph needs no context.
#include "graph/GraphCompiler.h"
#include "passes/StillGraph.h"
#include "passes/gbuffer/GBufferPass.h"
#include "passes/shade/ShadePass.h"
#include "scene/mesh/Procedural.h"

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

namespace inkgraph {
namespace {

using Names = std::vector<std::string>;

/** A line pass in small: reads one G-buffer field, so the G-buffer runs anyway. */
class FieldReader final : public Pass {
public:
    FieldReader(std::string name, std::string field) : mName(std::move(name)), mField(std::move(field)) {}
    std::string_view name() const override { return mName; }
    void declare(PassBuilder& builder) const override {
        builder.read(mField);
        builder.write("out", {Format::R8});
    }

private:
    std::string mName, mField;
};

/** What the graph chose for one look. */
struct Choice {
    std::string mode;    ///< "deferred" or "forward"
    std::string reason;  ///< why forward
    Names reads;         ///< the shade pass's reads in the compiled plan
    Names gbufferWrites; ///< the G-buffer's live writes, or none when it is culled
};

class ShadeModeChoice : public ::testing::Test {
protected:
    void SetUp() override {
        scene = makeScene(makeUvSphere({0.0f, 0.0f, 0.0f}, 1.0f, 32, 16));
        scene.meshes[0].name = "sphere";
        scene.meshes[0].material.name = "paint";
    }

    /** Builds the still graph of `look` over `scene` (the eye 5 radii away: comic's constant view vector applies) and
     *  compiles it for the final picture. */
    /** Frames `scene` from 5 radii away at 64x64 and makes its GpuScene; returns its bounding sphere. */
    BoundingSphere frameScene() {
        CameraRequest request;
        request.eye = glm::dvec3(0.0, 0.0, 5.0);
        request.target = glm::dvec3(0.0);
        request.width = 64;
        request.height = 64;
        frame.camera = resolveCamera(request, scene);
        const BoundingSphere sphere = computeBoundingSphere(scene);
        frame.worldOrigin = sphere.center;
        gpuScene = std::make_unique<GpuScene>(scene, frame.worldOrigin);
        return sphere;
    }

    Choice choose(const Look& look, std::vector<std::optional<ShadeMap>> meshShadeMaps = {}) {
        const BoundingSphere sphere = frameScene();
        StillGraphSetup setup{look, shaders, scene, sphere, *gpuScene, frame, std::nullopt};
        setup.meshShadeMaps = std::move(meshShadeMaps);
        const StillGraph graph = buildStillGraph(setup);
        const Plan plan = graph.compilePlan({graph.finalResource});
        Choice choice{graph.shadingModeIn(plan), graph.shadingForwardReasonIn(plan), {}, {}};
        if (const PlannedPass* shade = plan.findPass("shade")) choice.reads = shade->reads;
        if (const PlannedPass* gbuffer = plan.findPass("gbuffer")) choice.gbufferWrites = gbuffer->liveWrites;
        return choice;
    }

    static Look lookOf(ShadingModel model, Names lines = {"contour"}) {
        Look look;
        look.shading = model;
        look.lines = std::move(lines);
        return look;
    }

    Scene scene;
    FrameParams frame;
    ShaderLibrary shaders;
    std::unique_ptr<GpuScene> gpuScene;
};

TEST_F(ShadeModeChoice, ForwardWhenNoDrawnLineReadsTheGBuffer) {
    for (const Names& lines : {Names{}, Names{"silhouette"}, Names{"outline", "crease"}}) {
        const Choice choice = choose(lookOf(ShadingModel::Cel, lines));
        EXPECT_EQ(choice.mode, "forward");
        EXPECT_EQ(choice.reason, "no line type reads the G-buffer");
        EXPECT_TRUE(choice.reads.empty());
        EXPECT_TRUE(choice.gbufferWrites.empty()) << "shading alone must not make the G-buffer run";
    }
}

TEST_F(ShadeModeChoice, DeferredReadsTheNormalAndTheViewOnlyForSpecularModelsWithTheExactViewVector) {
    // One untextured material: the base colour is a uniform, so the G-buffer adds only the normal (and the view);
    // its z-buffer, written anyway, tells the shading which pixels to skip.
    const std::vector<std::pair<ShadingModel, Names>> cases = {
        {ShadingModel::Lambert, {"gbuffer.normal", "gbuffer.zBuffer"}},
        {ShadingModel::Cel, {"gbuffer.normal", "gbuffer.zBuffer"}},
        {ShadingModel::Phong, {"gbuffer.normal", "gbuffer.view", "gbuffer.zBuffer"}},
        {ShadingModel::Comic, {"gbuffer.normal", "gbuffer.view", "gbuffer.zBuffer"}},
    };
    for (const auto& [model, reads] : cases) {
        const Choice choice = choose(lookOf(model, {"silhouette", "contour", "suggestive"}));
        EXPECT_EQ(choice.mode, "deferred") << traitsOf(model).name << ": " << choice.reason;
        EXPECT_TRUE(choice.reason.empty());
        EXPECT_EQ(choice.reads, reads) << traitsOf(model).name;
        for (const std::string& read : reads)
            EXPECT_NE(std::find(choice.gbufferWrites.begin(), choice.gbufferWrites.end(), read),
                      choice.gbufferWrites.end());
    }
    Look constant = lookOf(ShadingModel::Comic);
    constant.viewVector = ViewVectorMode::Constant;
    EXPECT_EQ(choose(constant).reads, (Names{"gbuffer.normal", "gbuffer.zBuffer"}))
        << "comic's constant view vector is a uniform";
}

TEST_F(ShadeModeChoice, DeferredReadsTheBaseColourWhenItVariesOverTheScene) {
    scene.meshes[0].colors.assign(scene.meshes[0].positions.size(), glm::vec4(1.0f, 0.5f, 0.25f, 1.0f));
    EXPECT_EQ(choose(lookOf(ShadingModel::Cel)).reads,
              (Names{"gbuffer.normal", "gbuffer.baseColor", "gbuffer.zBuffer"}));

    SetUp();
    scene.images.push_back({"checker.png", "checker.png", "image/png", nullptr});
    scene.meshes[0].material.baseColorTexture.image = 0;
    EXPECT_EQ(choose(lookOf(ShadingModel::Lambert)).reads,
              (Names{"gbuffer.normal", "gbuffer.baseColor", "gbuffer.zBuffer"}));

    SetUp();
    Mesh second = makeUvSphere({3.0f, 0.0f, 0.0f}, 1.0f, 16, 8);
    second.material.baseColorFactor = glm::vec4(0.2f, 0.4f, 0.8f, 1.0f);
    scene.meshes.push_back(second);
    EXPECT_EQ(choose(lookOf(ShadingModel::Cel)).reads,
              (Names{"gbuffer.normal", "gbuffer.baseColor", "gbuffer.zBuffer"}));
}

TEST_F(ShadeModeChoice, ModelsThatNeedMoreThanThePixelStayForward) {
    for (const ShadingModel model : {ShadingModel::Flat, ShadingModel::Gouraud, ShadingModel::MToon}) {
        const Choice choice = choose(lookOf(model));
        EXPECT_EQ(choice.mode, "forward");
        EXPECT_EQ(choice.reason, "'" + std::string(traitsOf(model).name) +
                                     "' shades from more than the pixel's normal, view and base colour");
        EXPECT_TRUE(choice.reads.empty());
    }
    Look orientation = lookOf(ShadingModel::Comic);
    orientation.viewVector = ViewVectorMode::Constant;
    orientation.faceOrientation = FaceOrientationMethod::AfterVertices;
    EXPECT_EQ(choose(orientation).reason, "'comic' draws the front sets of the CPU face orientation 'after-vertices'");
}

TEST_F(ShadeModeChoice, GBuffersThatWouldShadeOtherNormalsKeepItForward) {
    Look supersampled = lookOf(ShadingModel::Cel);
    supersampled.supersample = 2;
    EXPECT_EQ(choose(supersampled).reason, "the G-buffer is supersampled (2x the frame)");
    Look half = lookOf(ShadingModel::Cel);
    half.gbufferPrecision = GBufferPrecision::Float16;
    EXPECT_EQ(choose(half).reason, "the G-buffer stores float16 normals");
}

TEST_F(ShadeModeChoice, MultisampledShadingIsForwardAndItsOutlineLayerHasItsSamples) {
    // Deferred would shade the single-sample G-buffer: with --msaa the pass draws the meshes itself, into a target it
    // declares as working memory (colour and depth, 8 bytes a sample).
    Look look = lookOf(ShadingModel::Cel);
    EXPECT_EQ(choose(look).mode, "deferred");
    look.msaa = 4;
    const Choice choice = choose(look);
    EXPECT_EQ(choice.mode, "forward");
    EXPECT_EQ(choice.reason, "the shading is multisampled (--msaa 4) and the G-buffer holds one sample per pixel");
    EXPECT_TRUE(choice.reads.empty());

    MToonMaterial mtoon;
    mtoon.outlineWidthMode = MToonMaterial::OutlineWidthMode::WorldCoordinates;
    mtoon.outlineWidthFactor = 0.01f;
    scene.meshes[0].material.mtoon = mtoon;
    look.shading = ShadingModel::MToon;
    const BoundingSphere sphere = frameScene();
    StillGraphSetup setup{look, shaders, scene, sphere, *gpuScene, frame, std::nullopt};
    const StillGraph graph = buildStillGraph(setup);
    const Plan plan = graph.compilePlan({graph.finalResource});
    for (const char* layer : {"mtoon-outline.color", "mtoon-outline.depth"}) {
        ASSERT_NE(plan.findResource(layer), nullptr) << layer;
        EXPECT_EQ(plan.findResource(layer)->desc.samples, 4) << layer;
    }
    EXPECT_EQ(plan.findResource("shade.color")->desc.samples, 1); // resolved for the composite
    const PlannedPass* shade = plan.findPass("shade");
    ASSERT_NE(shade, nullptr);
    ASSERT_EQ(shade->scratch.size(), 1u);
    EXPECT_EQ(shade->scratch[0].bytesPerPixel, 32u);
    EXPECT_NE(plan.describe().find("mtoon-outline.color(rgba8 msaa4)"), std::string::npos) << plan.describe();
}

TEST_F(ShadeModeChoice, MaterialsTheGBufferDoesNotHoldKeepItForward) {
    scene.meshes[0].material.alphaMode = AlphaMode::Blend;
    EXPECT_EQ(choose(lookOf(ShadingModel::Cel)).reason, "material 'paint' of mesh 'sphere' blends");
    SetUp();
    scene.meshes[0].material.emissiveFactor = glm::vec3(0.1f, 0.0f, 0.0f);
    EXPECT_EQ(choose(lookOf(ShadingModel::Cel)).reason, "material 'paint' of mesh 'sphere' is emissive");
    SetUp();
    scene.meshes[0].material.unlit = true;
    EXPECT_EQ(choose(lookOf(ShadingModel::Cel)).reason, "material 'paint' of mesh 'sphere' is unlit");
    SetUp();
    scene.meshes[0].material.alphaMode = AlphaMode::Mask; // cut out alike in the G-buffer and forward
    EXPECT_EQ(choose(lookOf(ShadingModel::Cel)).mode, "deferred");
}

TEST_F(ShadeModeChoice, OneShadeMapPerPixelOrForward) {
    scene.meshes.push_back(makeUvSphere({3.0f, 0.0f, 0.0f}, 1.0f, 16, 8));
    // A mesh's own map equal to the default one is the default one.
    EXPECT_EQ(choose(lookOf(ShadingModel::Cel), {std::nullopt, makeBandShadeMap(5)}).mode, "deferred");
    EXPECT_EQ(choose(lookOf(ShadingModel::Cel), {std::nullopt, makeBandShadeMap(3)}).reason,
              "the meshes use 2 different shade maps");
    // Every mesh with the same map of its own: one map.
    EXPECT_EQ(choose(lookOf(ShadingModel::Cel), {makeBandShadeMap(3), makeBandShadeMap(3)}).mode, "deferred");
}

TEST_F(ShadeModeChoice, ForwardWhenTheShadingFieldsWouldMakeTheGBufferDrawTwice) {
    CameraRequest request;
    request.width = 64;
    request.height = 64;
    frame.camera = resolveCamera(request, scene);
    GpuScene meshes(scene, glm::dvec3(0.0));
    GBufferPass gbuffer("gbuffer", shaders, meshes, frame);
    ShadeSettings settings;
    settings.model = ShadingModel::Lambert;
    settings.deferred = {"gbuffer", gbuffer.supersample(), gbuffer.precision()};
    ShadePass shade("shade", shaders, meshes, frame, settings, std::nullopt);
    // Eight fields without the normal: the ninth would need a second draw of the meshes.
    const Names eight = {"view", "wVec", "nDotV", "depth", "coverage", "baseColor", "radial", "materialId"};
    EXPECT_EQ(shade.forwardReason(eight), "the G-buffer would draw the meshes a second time for 9 fields");
    // Seven and the normal still fit one draw.
    EXPECT_TRUE(shade.forwardReason(Names(eight.begin(), eight.end() - 1)).empty());
    // Deferred reads exactly what it declares: a plan whose lines read seven fields has it read the normal alone.
    std::vector<std::unique_ptr<Pass>> readers;
    for (const std::string& field : Names(eight.begin(), eight.end() - 1))
        readers.push_back(std::make_unique<FieldReader>("read-" + field, "gbuffer." + field));
    std::vector<const Pass*> passes = {&gbuffer, &shade};
    Names requested = {"shade.color"};
    for (const auto& reader : readers) {
        passes.push_back(reader.get());
        requested.push_back(std::string(reader->name()) + ".out");
    }
    const Plan plan = compile(passes, requested, requested);
    EXPECT_EQ(shade.modeIn(plan), ShadeMode::Deferred);
    EXPECT_EQ(plan.findPass("shade")->reads, (Names{"gbuffer.normal", "gbuffer.zBuffer"}));
}

TEST_F(ShadeModeChoice, TheMToonOutlineLayerIsReadOnlyWhenAMaterialAsksForAnOutline) {
    // Registered whenever the look is mtoon; culled, and said so, when no material asks for an outline.
    const auto compileLook = [&](const Look& look) {
        const BoundingSphere sphere = frameScene();
        StillGraphSetup setup{look, shaders, scene, sphere, *gpuScene, frame, std::nullopt};
        const StillGraph graph = buildStillGraph(setup);
        return std::make_pair(graph.findPass("mtoon-outline") != nullptr, compile(graph.view(), {graph.finalResource}));
    };
    const auto culledReason = [](const Plan& plan) -> std::string {
        for (const CulledPass& pass : plan.culled)
            if (pass.name == "mtoon-outline") return pass.reason;
        return "";
    };

    // Not mtoon: not registered.
    EXPECT_FALSE(compileLook(lookOf(ShadingModel::Cel, {})).first);

    // MToon without an outline (width mode none, and a width of 0): registered, unread, culled.
    MToonMaterial mtoon;
    scene.meshes[0].material.mtoon = mtoon;
    auto [registered, plan] = compileLook(lookOf(ShadingModel::MToon, {}));
    EXPECT_TRUE(registered);
    EXPECT_EQ(plan.findPass("mtoon-outline"), nullptr);
    EXPECT_NE(culledReason(plan).find("mtoon-outline.color"), std::string::npos) << culledReason(plan);
    ASSERT_NE(plan.findPass("shade"), nullptr);
    EXPECT_TRUE(plan.findPass("shade")->reads.empty());
    mtoon.outlineWidthMode = MToonMaterial::OutlineWidthMode::WorldCoordinates;
    scene.meshes[0].material.mtoon = mtoon; // a width of 0 draws nothing
    EXPECT_EQ(compileLook(lookOf(ShadingModel::MToon, {})).second.findPass("mtoon-outline"), nullptr);

    // With an outline: the shade pass reads the layer's colour and depth, after the layer is drawn.
    mtoon.outlineWidthFactor = 0.01f;
    scene.meshes[0].material.mtoon = mtoon;
    plan = compileLook(lookOf(ShadingModel::MToon, {})).second;
    const PlannedPass* outline = plan.findPass("mtoon-outline");
    ASSERT_NE(outline, nullptr);
    EXPECT_EQ(outline->liveWrites, (Names{"mtoon-outline.color", "mtoon-outline.depth"}));
    EXPECT_EQ(plan.findPass("shade")->reads, (Names{"mtoon-outline.color", "mtoon-outline.depth"}));
    EXPECT_TRUE(culledReason(plan).empty());
}

TEST(ShadingModelTraits, TheShadePassWorkOfAModelHasTheTraitsItBuildsOn) {
    // ShadePass asks the traits, never the model, for the work beyond a shader branch; each of those traits only
    // makes sense with the traits that feed it.
    for (const ShadingModelTraits& model : shadingModels()) {
        // The constant view vector and the CPU face-orientation sets come from --view-vector and --face-orientation.
        if (model.constantView || model.orientationSets) {
            EXPECT_TRUE(model.faceOrientation) << model.name;
        }
        // Row bands are rows of a 2-D map's specular axis.
        if (model.specularRowBands) {
            EXPECT_TRUE(model.specular && model.shadeMap && !model.oneDimensionalMap) << model.name;
        }
        // The materials' outlines go into forward shading: a model that may shade deferred would lose them.
        if (model.materialOutlines) {
            EXPECT_FALSE(model.perPixel) << model.name;
        }
    }
    EXPECT_EQ(shadingModelsWith(&ShadingModelTraits::constantView), "comic");
    EXPECT_EQ(shadingModelsWith(&ShadingModelTraits::orientationSets), "comic");
    EXPECT_EQ(shadingModelsWith(&ShadingModelTraits::specularRowBands), "comic");
    EXPECT_EQ(shadingModelsWith(&ShadingModelTraits::materialOutlines), "mtoon and auto");
    EXPECT_EQ(shadingModelsWith(&ShadingModelTraits::ambient), "flat, gouraud, lambert, phong, mtoon and auto");
}

} // namespace
} // namespace inkgraph
