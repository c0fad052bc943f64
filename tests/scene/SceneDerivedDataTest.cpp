// What the passes derive from a scene's meshes whatever the view (scene/SceneDerivedData.h): each item derived once,
// the same as deriving it directly, kept while other items are derived, and safe to ask for from several threads.
#include "scene/SceneDerivedData.h"
#include "scene/mesh/MeshOps.h"
#include "scene/mesh/Procedural.h"

#include <gtest/gtest.h>

#include <atomic>
#include <set>
#include <thread>
#include <vector>

namespace inkgraph {
namespace {

Scene sphereAndCube() {
    Scene scene = makeScene(makeUvSphere(glm::vec3(0.0f), 1.0f, 24, 12));
    scene.meshes.push_back(makeCube(glm::vec3(3.0f, 0.0f, 0.0f), 0.5f));
    return scene;
}

TEST(SceneDerivedData, EachItemIsDerivedOnceAndKeptWhileOthersAre) {
    const Scene scene = sphereAndCube();
    SceneDerivedData derived(scene);
    EXPECT_FALSE(derived.positionWeldComputed(0));
    EXPECT_FALSE(derived.edgeAdjacencyComputed());
    EXPECT_FALSE(derived.meshCurvatureComputed());
    EXPECT_FALSE(derived.surfacePatchesComputed());
    EXPECT_FALSE(derived.meshIntersectionsComputed());

    const MeshCurvature& sharp = derived.meshCurvature(0, 0.0);
    const MeshCurvature& smooth = derived.meshCurvature(0, 0.2);
    EXPECT_TRUE(derived.meshCurvatureComputed(0.0));
    EXPECT_TRUE(derived.meshCurvatureComputed(0.2));
    EXPECT_FALSE(derived.meshCurvatureComputed(0.1));
    // Another smoothing is derived beside the first, which stays where it was (a still's reader may hold it).
    EXPECT_EQ(&derived.meshCurvature(0, 0.0), &sharp);
    EXPECT_EQ(&derived.meshCurvature(0, 0.2), &smooth);
    EXPECT_TRUE(derived.positionWeldComputed(0)) << "the curvature is built on the weld";

    const EdgeAdjacency& adjacency = derived.edgeAdjacency(1);
    EXPECT_TRUE(derived.edgeAdjacencyComputed());
    EXPECT_EQ(&derived.edgeAdjacency(1), &adjacency);
    EXPECT_EQ(adjacency.edges.size(), 18u) << "a cube's 12 edges and 6 face diagonals";

    // The same as deriving directly, from the same weld.
    const Mesh& cube = scene.meshes[1];
    const EdgeAdjacency direct = buildEdgeAdjacency(cube.positions, cube.triangles, derived.positionWeld(1));
    EXPECT_EQ(direct.edges.size(), adjacency.edges.size());

    EXPECT_TRUE(derived.surfacesMeet()) << "two meshes";
    EXPECT_EQ(derived.surfacePatches().seamEdges, 12u) << "the cube's hard edges";
    EXPECT_TRUE(derived.surfacePatchesComputed());
    EXPECT_THROW(derived.edgeAdjacency(2), std::out_of_range);
    EXPECT_THROW(derived.meshCurvature(2, 0.0), std::out_of_range);
}

TEST(SceneDerivedData, HullNormalsAreNoneWhereTheMeshsOwnServe) {
    const Scene scene = sphereAndCube();
    SceneDerivedData derived(scene);
    // The sphere's normals are its smooth ones (its seam welded by the loader's rule or not: then they are computed).
    const std::vector<glm::vec3>* sphere = derived.hullNormals(0);
    if (scene.meshes[0].normalsAreSmooth && derived.positionWeld(0).kept.size() == scene.meshes[0].positions.size()) {
        EXPECT_EQ(sphere, nullptr);
    }
    // The cube's split normals would tear the hull open: its hull normals are its corners' averaged ones.
    const std::vector<glm::vec3>* cube = derived.hullNormals(1);
    ASSERT_NE(cube, nullptr);
    ASSERT_EQ(cube->size(), scene.meshes[1].positions.size());
    for (const glm::vec3& normal : *cube) {
        EXPECT_NEAR(glm::length(normal), 1.0f, 1e-5f);
        for (int axis = 0; axis < 3; ++axis) EXPECT_NEAR(std::abs(normal[axis]), 1.0f / std::sqrt(3.0f), 1e-5f);
    }
    EXPECT_EQ(derived.hullNormals(1), cube) << "derived once";
}

TEST(SceneDerivedData, ThreadsAskingAtOnceShareOneDerivation) {
    const Scene scene = makeScene(makeTorus(1.0f, 0.3f, 48, 24));
    SceneDerivedData derived(scene);
    constexpr int kThreads = 6;
    std::vector<const MeshCurvature*> curvature(kThreads);
    std::vector<const SceneDerivedData::SurfacePatches*> patches(kThreads);
    std::atomic<int> ready{0};
    std::vector<std::thread> threads;
    for (int t = 0; t < kThreads; ++t)
        threads.emplace_back([&, t] {
            ready.fetch_add(1);
            while (ready.load() < kThreads) std::this_thread::yield(); // all ask at about the same moment
            curvature[std::size_t(t)] = &derived.meshCurvature(0, t % 2 == 0 ? 0.05 : 0.0);
            patches[std::size_t(t)] = &derived.surfacePatches();
        });
    for (std::thread& thread : threads) thread.join();
    const std::set<const MeshCurvature*> distinctCurvature(curvature.begin(), curvature.end());
    EXPECT_EQ(distinctCurvature.size(), 2u) << "one per smoothing";
    const std::set<const SceneDerivedData::SurfacePatches*> distinctPatches(patches.begin(), patches.end());
    EXPECT_EQ(distinctPatches.size(), 1u);
    EXPECT_EQ(patches[0]->patchOfTriangle.size(), scene.meshes[0].triangles.size() + 1);
}

} // namespace
} // namespace inkgraph
