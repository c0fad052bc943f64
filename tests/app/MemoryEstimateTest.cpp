// The memory estimate's model share (render/MemoryBudget.h): the meshes cost the same in every look, and what the
// passes derive from them (edge adjacency, curvature, ...) is charged only when a pass of the plan imports it, once
// however many import it. No GL: the plan is built by hand. tests/app/MemoryBudgetGLTest.cpp holds the estimate
// against measured peaks.
#include "graph/Plan.h"
#include "passes/GpuScene.h"
#include "render/MemoryBudget.h"
#include "render/StillRenderer.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace inkgraph {
namespace {

/** A plan of passes that import `importsPerPass` and touch no resource: its estimate is the process and the model. */
Plan planImporting(const std::vector<std::vector<std::string>>& importsPerPass) {
    Plan plan;
    for (std::size_t index = 0; index < importsPerPass.size(); ++index) {
        PlannedPass pass;
        pass.name = "pass" + std::to_string(index);
        pass.imports = importsPerPass[index];
        plan.passes.push_back(pass);
    }
    return plan;
}

StillRequest smallStill() {
    StillRequest request;
    request.camera.width = 64;
    request.camera.height = 64;
    return request;
}

TEST(MemoryEstimate, TheMeshesCostTheSameInEveryPlanAndGrowWithTheirCounts) {
    const SceneSize scene{100000, 200000, 0};
    const MemoryEstimate bare = estimateRunMemory(planImporting({}), smallStill(), scene);
    const MemoryEstimate drawing =
        estimateRunMemory(planImporting({{SceneImport::kMeshes}, {SceneImport::kMeshes}}), smallStill(), scene);
    EXPECT_EQ(drawing.scene, bare.scene) << "the meshes are in the model's share already";
    EXPECT_EQ(bare.derived, 0u);
    EXPECT_GT(bare.scene, std::size_t(200000) * 64) << "at least what the loader's own bound counts per triangle";

    // In proportion to the counts, but for what llvmpipe bins, which stops growing when its scenes are full.
    const auto sceneShare = [](std::size_t triangles) {
        return estimateRunMemory(planImporting({}), smallStill(), {triangles / 2, triangles, 0}).scene;
    };
    EXPECT_EQ(sceneShare(20000), 2 * sceneShare(10000));
    EXPECT_LT(sceneShare(20000000), 2 * sceneShare(10000000));
    EXPECT_EQ(sceneShare(30000000) - sceneShare(20000000), sceneShare(20000000) - sceneShare(10000000));
    EXPECT_EQ(estimateRunMemory(planImporting({}), smallStill(), {}).scene, 0u) << "a scene not known yet adds nothing";
}

TEST(MemoryEstimate, WhatThePassesDeriveIsChargedOnlyWhenImportedAndOnce) {
    const std::size_t triangles = 200000;
    const SceneSize scene{100000, triangles, 0};
    const MemoryEstimate bare = estimateRunMemory(planImporting({{SceneImport::kMeshes}}), smallStill(), scene);
    // Two edge line types (crease, outline) share one adjacency; the object-space suggestive contours add curvature.
    const MemoryEstimate lines = estimateRunMemory(planImporting({{SceneImport::kMeshes, SceneImport::kEdgeAdjacency},
                                                                  {SceneImport::kEdgeAdjacency},
                                                                  {SceneImport::kCurvature}}),
                                                   smallStill(), scene);
    const std::size_t expected = triangles * (SceneImport::bytesPerTriangle(SceneImport::kEdgeAdjacency) +
                                              SceneImport::bytesPerTriangle(SceneImport::kCurvature));
    EXPECT_EQ(lines.derived, expected);
    EXPECT_EQ(lines.scene, bare.scene + expected);
    EXPECT_EQ(lines.total(), bare.total() + expected);
    // Curvature is what the measurements found the largest (docs/batch.md): it costs more than the adjacency.
    EXPECT_GT(SceneImport::bytesPerTriangle(SceneImport::kCurvature),
              SceneImport::bytesPerTriangle(SceneImport::kEdgeAdjacency));
}

TEST(MemoryEstimate, ATargetAPassKeepsIsCountedWithTheTexturesAndWorkingMemoryAtItsMoment) {
    // One pass keeps a multisampled colour and depth (8 bytes a sample, 4 samples: ShadePass with --msaa 4), another
    // declares working memory of the same size: only the kept one is a GL target, padded as the driver pads.
    const auto planWith = [](bool kept) {
        Plan plan = planImporting({{}});
        plan.passes[0].scratch.push_back({32, 1, 1, kept});
        return plan;
    };
    StillRequest request = smallStill();
    request.camera.width = 100; // padded to 128
    request.camera.height = 64;
    const MemoryEstimate none = estimateRunMemory(planImporting({{}}), request, {});
    const MemoryEstimate kept = estimateRunMemory(planWith(true), request, {});
    const MemoryEstimate working = estimateRunMemory(planWith(false), request, {});
    EXPECT_EQ(kept.glTargets, none.glTargets + std::size_t(32) * 128 * 64);
    EXPECT_EQ(kept.cpuImages, none.cpuImages);
    EXPECT_EQ(working.glTargets, none.glTargets);
    EXPECT_EQ(working.cpuImages, none.cpuImages + std::size_t(32) * 100 * 64);
}

TEST(MemoryEstimate, EveryImportHasACostAndAnUnknownOneIsAnError) {
    for (const char* import : {SceneImport::kHulls, SceneImport::kEdgeAdjacency, SceneImport::kFaceOrientation,
                               SceneImport::kCurvature, SceneImport::kSurfacePatches, SceneImport::kIntersections})
        EXPECT_GT(SceneImport::bytesPerTriangle(import), 0u) << import;
    EXPECT_EQ(SceneImport::bytesPerTriangle(SceneImport::kMeshes), 0u);
    try {
        SceneImport::bytesPerTriangle("scene.nothing");
        FAIL() << "no error";
    } catch (const std::logic_error& error) {
        EXPECT_NE(std::string(error.what()).find("'scene.nothing'"), std::string::npos) << error.what();
    }
}

} // namespace
} // namespace inkgraph
