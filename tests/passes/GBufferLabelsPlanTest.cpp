// The G-buffer's label fields (issue 37: meshId, triangleId, barycentric) are computed only on request: the still
// graph's plan for every line type at once binds none of them, and asking for one binds that one. No GL: building and
// compiling the graph needs no context.
#include "graph/GraphCompiler.h"
#include "passes/StillGraph.h"
#include "passes/gbuffer/GBufferPass.h"
#include "passes/lines/LineTypes.h"
#include "scene/mesh/Procedural.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

namespace inkgraph {
namespace {

using Names = std::vector<std::string>;

const Names kLabels = {"gbuffer.meshId", "gbuffer.triangleId", "gbuffer.barycentric"};

class GBufferLabelsPlan : public ::testing::Test {
protected:
    void SetUp() override {
        scene = makeScene(makeUvSphere({0.0f, 0.0f, 0.0f}, 1.0f, 32, 16));
        CameraRequest request;
        request.eye = glm::dvec3(0.0, 0.0, 5.0);
        request.target = glm::dvec3(0.0);
        request.width = 64;
        request.height = 64;
        frame.camera = resolveCamera(request, scene);
        sphere = computeBoundingSphere(scene);
        frame.worldOrigin = sphere.center;
        gpuScene = std::make_unique<GpuScene>(scene, frame.worldOrigin);
    }

    /** The G-buffer's live writes in the plan of `look` for the picture and `extra`; empty when it is culled. */
    Names gbufferWrites(const Look& look, const Names& extra = {}) {
        StillGraphSetup setup{look, shaders, scene, sphere, *gpuScene, frame, std::nullopt};
        const StillGraph graph = buildStillGraph(setup);
        Names requested = {graph.finalResource};
        requested.insert(requested.end(), extra.begin(), extra.end());
        const Plan plan = graph.compilePlan(requested);
        const PlannedPass* gbuffer = plan.findPass(kGBufferPass);
        return gbuffer != nullptr ? gbuffer->liveWrites : Names{};
    }

    static bool containsAny(const Names& names, const Names& wanted) {
        return std::any_of(wanted.begin(), wanted.end(), [&](const std::string& name) {
            return std::find(names.begin(), names.end(), name) != names.end();
        });
    }

    Scene scene;
    FrameParams frame;
    ShaderLibrary shaders;
    BoundingSphere sphere;
    std::unique_ptr<GpuScene> gpuScene;
};

TEST_F(GBufferLabelsPlan, NoLineTypeNorShadingComputesTheLabels) {
    Look every;
    every.shading = ShadingModel::Comic;
    for (const LineType& type : lineTypes()) every.lines.push_back(type.name);
    const Names writes = gbufferWrites(every);
    ASSERT_FALSE(writes.empty()) << "the line types read the G-buffer, so it runs";
    EXPECT_FALSE(containsAny(writes, kLabels)) << "a label computed that nobody asked for";
    EXPECT_FALSE(containsAny(gbufferWrites(Look{}), kLabels)) << "the default look";
}

TEST_F(GBufferLabelsPlan, EachLabelIsComputedWhenAskedForAndAloneOfTheThree) {
    for (const std::string& label : kLabels) {
        const Names writes = gbufferWrites(Look{}, {label});
        EXPECT_NE(std::find(writes.begin(), writes.end(), label), writes.end()) << label;
        Names others;
        for (const std::string& other : kLabels)
            if (other != label) others.push_back(other);
        EXPECT_FALSE(containsAny(writes, others)) << label << " brought another label with it";
    }
}

TEST_F(GBufferLabelsPlan, TheLabelsAreFieldsWithDumpFilesAndStayFloat32AtHalfPrecision) {
    // "gbuffer.*" asks for every field the pass declares (render/StillRenderer.cpp), so it includes them.
    const GBufferPass half("gbuffer", shaders, *gpuScene, frame, 1, GBufferPrecision::Float16);
    Names files;
    for (const GBufferPass::Field& field : GBufferPass::fields()) {
        files.push_back(field.fileName);
        if (std::find(kLabels.begin(), kLabels.end(), std::string("gbuffer.") + field.name) == kLabels.end()) continue;
        EXPECT_EQ(half.formatOf(field), std::string_view(field.name) == "barycentric" ? Format::RGBA32F : Format::R32F)
            << field.name << ": ids must stay exact, weights full precision";
    }
    for (const char* file : {"meshid.exr", "triangleid.exr", "barycentric.exr"})
        EXPECT_NE(std::find(files.begin(), files.end(), file), files.end()) << file;
}

} // namespace
} // namespace inkgraph
