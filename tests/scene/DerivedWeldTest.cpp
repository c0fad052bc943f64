// One position weld for every datum derived from a loaded mesh (issue 20): the loader records when its weld was by
// position alone (Mesh::positionsWeldedAt) and when the normals are the smooth ones (Mesh::normalsAreSmooth);
// weldMeshPositions() then skips the weld, and the hull normals, edge adjacency and curvature built on the shared map
// equal those built from a weld distance.
#include "scene/mesh/EdgeAdjacency.h"
#include "scene/mesh/MeshCurvature.h"
#include "scene/mesh/MeshOps.h"
#include "scene/mesh/Procedural.h"
#include "scene/Scene.h"

#include "SceneTestSupport.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace inkgraph {
namespace {

using test::TempFile;

std::string modelPath(const std::string& name) { return std::string(INKGRAPH_SOURCE_ROOT) + "/models/" + name; }

/** GpuScene's distance: the loader's default tolerance times the scene's diagonal. */
double derivedDistance(const Scene& scene) {
    BoundingBox box;
    for (const Mesh& mesh : scene.meshes)
        for (const glm::vec3& p : mesh.positions) box.add(glm::dvec3(p));
    return LoadOptions{}.weldTolerance * box.diagonal();
}

void expectSameAdjacency(const EdgeAdjacency& a, const EdgeAdjacency& b) {
    ASSERT_EQ(a.edges.size(), b.edges.size());
    for (std::size_t i = 0; i < a.edges.size(); ++i) {
        const MeshEdge &x = a.edges[i], &y = b.edges[i];
        ASSERT_TRUE(x.vertices == y.vertices && x.welded == y.welded && x.kind == y.kind &&
                    x.inconsistentOrientation == y.inconsistentOrientation && x.normalAngle == y.normalAngle &&
                    x.firstFaceUse == y.firstFaceUse && x.faceCount == y.faceCount)
            << "edge " << i;
    }
    ASSERT_EQ(a.faceUses.size(), b.faceUses.size());
    for (std::size_t i = 0; i < a.faceUses.size(); ++i)
        ASSERT_TRUE(a.faceUses[i].face == b.faceUses[i].face && a.faceUses[i].againstKey == b.faceUses[i].againstKey)
            << "use " << i;
    EXPECT_EQ(a.faceNormals, b.faceNormals);
    EXPECT_EQ(a.facePlaneOffsets, b.facePlaneOffsets);
    EXPECT_EQ(a.counts.degenerateFaces, b.counts.degenerateFaces);
    EXPECT_EQ(a.counts.inconsistent, b.counts.inconsistent);
}

TEST(DerivedWeld, LoaderRecordsAWeldByPositionAlone) {
    const TempFile bare("bare.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n");
    const Scene plain = loadScene(bare.path());
    ASSERT_TRUE(plain.meshes[0].positionsWeldedAt.has_value());
    EXPECT_EQ(*plain.meshes[0].positionsWeldedAt, LoadOptions{}.weldTolerance * std::sqrt(2.0));
    EXPECT_TRUE(plain.meshes[0].normalsAreSmooth);
    EXPECT_EQ(plain.meshes[0].normals, computeSmoothNormals(plain.meshes[0].positions, plain.meshes[0].triangles));

    // File normals or texture coordinates keep copies of a point apart: the weld was not by position alone.
    const TempFile normals("normals.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\n");
    EXPECT_FALSE(loadScene(normals.path()).meshes[0].positionsWeldedAt.has_value());
    EXPECT_FALSE(loadScene(normals.path()).meshes[0].normalsAreSmooth);
    const TempFile textured("textured.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n");
    EXPECT_FALSE(loadScene(textured.path()).meshes[0].positionsWeldedAt.has_value());
    EXPECT_FALSE(loadScene(textured.path()).meshes[0].normalsAreSmooth);
}

TEST(DerivedWeld, SkippedWeldIsTheWeldOnEveryBundledModel) {
    for (const char* name :
         {"bunny_c3d_70k.obj", "teapot_c3d.obj", "fandisk_c3d.obj", "suzanne_npm_4k.obj", "torusknot_open3d.obj"}) {
        const Scene scene = loadScene(modelPath(name));
        const Mesh& mesh = scene.meshes.at(0);
        ASSERT_TRUE(mesh.positionsWeldedAt.has_value()) << name;
        const double distance = derivedDistance(scene);
        EXPECT_LE(distance, *mesh.positionsWeldedAt) << name;
        for (double scale : {1.0, 0.5, 0.0}) {
            const WeldMap skipped = weldMeshPositions(mesh, distance * scale);
            const WeldMap welded = weldVertices(mesh.positions, {}, distance * scale);
            EXPECT_EQ(skipped.kept, welded.kept) << name << " x " << scale;
            EXPECT_EQ(skipped.outputOf, welded.outputOf) << name << " x " << scale;
        }
        // Beyond the loader's distance it welds for real (the teapot's patches are 1e-3 of its size apart at most).
        const WeldMap loose = weldMeshPositions(mesh, distance * 1e4);
        EXPECT_EQ(loose.outputOf, weldVertices(mesh.positions, {}, distance * 1e4).outputOf) << name;
    }
}

TEST(DerivedWeld, DerivedDataOnTheSharedWeldEqualThoseFromADistance) {
    // The soup of a cube (its 36 corners welded by the loader) and the bunny; the cube once more with hard edges,
    // as a file with per-face normals gives it (the loader does not weld those by position).
    const TempFile cube("cube.obj", []() {
        std::string obj;
        for (const glm::vec3& p : test::cubeTriangleSoup())
            obj += "v " + std::to_string(p.x) + " " + std::to_string(p.y) + " " + std::to_string(p.z) + "\n";
        for (int i = 0; i < 36; i += 3)
            obj += "f " + std::to_string(i + 1) + " " + std::to_string(i + 2) + " " + std::to_string(i + 3) + "\n";
        return obj;
    }());
    std::vector<Scene> scenes;
    scenes.push_back(loadScene(cube.path()));
    scenes.push_back(loadScene(modelPath("bunny_c3d_70k.obj")));
    scenes.push_back(makeScene(makeCube(glm::vec3(0.5f), 1.0f)));
    for (const Scene& scene : scenes) {
        const Mesh& mesh = scene.meshes.at(0);
        const double distance = derivedDistance(scene);
        const WeldMap weld = weldMeshPositions(mesh, distance);
        expectSameAdjacency(buildEdgeAdjacency(mesh.positions, mesh.triangles, weld),
                            buildEdgeAdjacency(mesh.positions, mesh.triangles, distance));
        EXPECT_EQ(computePositionWeldedNormals(mesh.positions, mesh.triangles, weld),
                  computePositionWeldedNormals(mesh.positions, mesh.triangles, distance));
        const MeshCurvature shared = computeMeshCurvature(mesh.positions, mesh.triangles, weld);
        const MeshCurvature own = computeMeshCurvature(mesh.positions, mesh.triangles, distance);
        EXPECT_EQ(shared.weldedOf, own.weldedOf);
        EXPECT_EQ(shared.curvature1, own.curvature1);
        EXPECT_EQ(shared.derivative, own.derivative);
        if (mesh.normalsAreSmooth && weld.kept.size() == mesh.positions.size()) {
            EXPECT_EQ(mesh.normals, computePositionWeldedNormals(mesh.positions, mesh.triangles, weld));
        }
    }
}

TEST(DerivedWeld, RefusesAWeldOfAnotherMesh) {
    const Mesh cube = makeCube(glm::vec3(0.0f), 1.0f);
    const WeldMap other = weldVertices(std::vector<glm::vec3>(3, glm::vec3(0.0f)), {}, 0.0);
    EXPECT_THROW(buildEdgeAdjacency(cube.positions, cube.triangles, other), std::invalid_argument);
    EXPECT_THROW(computePositionWeldedNormals(cube.positions, cube.triangles, other), std::invalid_argument);
    EXPECT_THROW(computeMeshCurvature(cube.positions, cube.triangles, other), std::invalid_argument);
}

} // namespace
} // namespace inkgraph
