// buildEdgeAdjacency() (a counting sort of edge uses, issue 20) against the adjacency built the plainest way from its
// definition: a std::map from the welded pair to the faces using it, edges numbered by first use. On meshes with
// borders, non-manifold fins, inconsistent orientation, degenerate and collapsed faces, a fan's hub (a bucket sorted by
// std::stable_sort), a soup welded back together, and the bunny.
#include "scene/mesh/EdgeAdjacency.h"
#include "scene/mesh/MeshOps.h"
#include "scene/mesh/Procedural.h"
#include "scene/Scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <map>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace inkgraph {
namespace {

/** The definition, written out: skipped faces, edges keyed (min, max) welded id in order of first use, the faces of
 *  each in face order, kinds, orientation and angles. */
EdgeAdjacency referenceAdjacency(const std::vector<glm::vec3>& positions, const std::vector<glm::uvec3>& triangles,
                                 double weldDistance) {
    const WeldMap weld = weldVertices(positions, {}, weldDistance);
    const double diagonal = computeBoundingBox(positions).diagonal();
    EdgeAdjacency adjacency;
    adjacency.faceNormals.assign(triangles.size(), glm::vec3(0.0f));
    adjacency.facePlaneOffsets.assign(triangles.size(), 0.0);
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::size_t> edgeOf;
    std::vector<std::vector<EdgeFaceUse>> uses;
    for (std::size_t face = 0; face < triangles.size(); ++face) {
        glm::uvec3 welded;
        for (int corner = 0; corner < 3; ++corner) welded[corner] = weld.outputOf[triangles[face][corner]];
        const glm::dvec3 a(positions[triangles[face].x]);
        const glm::dvec3 cross =
            glm::cross(glm::dvec3(positions[triangles[face].y]) - a, glm::dvec3(positions[triangles[face].z]) - a);
        if (welded.x == welded.y || welded.y == welded.z || welded.x == welded.z ||
            !(glm::length(cross) > 2.0 * 1e-14 * diagonal * diagonal)) {
            ++adjacency.counts.degenerateFaces;
            continue;
        }
        adjacency.faceNormals[face] = glm::vec3(cross / glm::length(cross));
        adjacency.facePlaneOffsets[face] = glm::dot(glm::dvec3(adjacency.faceNormals[face]), a);
        for (int corner = 0; corner < 3; ++corner) {
            const std::uint32_t from = welded[corner], to = welded[(corner + 1) % 3];
            const auto [at, inserted] = edgeOf.try_emplace({std::min(from, to), std::max(from, to)}, uses.size());
            if (inserted) {
                MeshEdge edge{};
                edge.vertices = glm::uvec2(triangles[face][corner], triangles[face][(corner + 1) % 3]);
                edge.welded = glm::uvec2(from, to);
                adjacency.edges.push_back(edge);
                uses.emplace_back();
            }
            uses[at->second].push_back({std::uint32_t(face), from > to});
        }
    }
    for (std::size_t index = 0; index < adjacency.edges.size(); ++index) {
        MeshEdge& edge = adjacency.edges[index];
        edge.firstFaceUse = std::uint32_t(adjacency.faceUses.size());
        edge.faceCount = std::uint32_t(uses[index].size());
        adjacency.faceUses.insert(adjacency.faceUses.end(), uses[index].begin(), uses[index].end());
        edge.kind = edge.faceCount == 1   ? EdgeKind::Boundary
                    : edge.faceCount == 2 ? EdgeKind::Manifold
                                          : EdgeKind::NonManifold;
        adjacency.counts.boundary += edge.kind == EdgeKind::Boundary;
        adjacency.counts.nonManifold += edge.kind == EdgeKind::NonManifold;
        if (edge.kind != EdgeKind::Manifold) continue;
        ++adjacency.counts.manifold;
        edge.inconsistentOrientation = uses[index][0].againstKey == uses[index][1].againstKey;
        adjacency.counts.inconsistent += edge.inconsistentOrientation;
        const glm::dvec3 n1(adjacency.faceNormals[uses[index][0].face]);
        const glm::dvec3 n2 =
            glm::dvec3(adjacency.faceNormals[uses[index][1].face]) * (edge.inconsistentOrientation ? -1.0 : 1.0);
        edge.normalAngle = float(std::atan2(glm::length(glm::cross(n1, n2)), glm::dot(n1, n2)));
    }
    return adjacency;
}

void expectReference(const std::vector<glm::vec3>& positions, const std::vector<glm::uvec3>& triangles,
                     double weldDistance, const std::string& what) {
    const EdgeAdjacency expected = referenceAdjacency(positions, triangles, weldDistance);
    const EdgeAdjacency actual = buildEdgeAdjacency(positions, triangles, weldDistance);
    ASSERT_EQ(actual.edges.size(), expected.edges.size()) << what;
    for (std::size_t i = 0; i < expected.edges.size(); ++i) {
        const MeshEdge &x = actual.edges[i], &y = expected.edges[i];
        ASSERT_TRUE(x.vertices == y.vertices && x.welded == y.welded && x.kind == y.kind &&
                    x.inconsistentOrientation == y.inconsistentOrientation && x.normalAngle == y.normalAngle &&
                    x.firstFaceUse == y.firstFaceUse && x.faceCount == y.faceCount)
            << what << ": edge " << i;
    }
    ASSERT_EQ(actual.faceUses.size(), expected.faceUses.size()) << what;
    for (std::size_t i = 0; i < expected.faceUses.size(); ++i)
        ASSERT_TRUE(actual.faceUses[i].face == expected.faceUses[i].face &&
                    actual.faceUses[i].againstKey == expected.faceUses[i].againstKey)
            << what << ": use " << i;
    EXPECT_EQ(actual.faceNormals, expected.faceNormals) << what;
    EXPECT_EQ(actual.facePlaneOffsets, expected.facePlaneOffsets) << what;
    EXPECT_EQ(actual.counts.boundary, expected.counts.boundary) << what;
    EXPECT_EQ(actual.counts.manifold, expected.counts.manifold) << what;
    EXPECT_EQ(actual.counts.nonManifold, expected.counts.nonManifold) << what;
    EXPECT_EQ(actual.counts.inconsistent, expected.counts.inconsistent) << what;
    EXPECT_EQ(actual.counts.degenerateFaces, expected.counts.degenerateFaces) << what;
}

TEST(EdgeTableReference, OpenSheetWithFinsFlipsAndDegenerateFaces) {
    // A 20 x 20 grid sheet (a border all round), a few faces flipped (inconsistent edges), fins standing on some of its
    // edges (three and four faces on one edge), a face repeating a vertex, a zero-area face, faces listed twice.
    std::vector<glm::vec3> positions;
    std::vector<glm::uvec3> triangles;
    const int n = 20;
    for (int y = 0; y <= n; ++y)
        for (int x = 0; x <= n; ++x) positions.emplace_back(float(x), float(y), 0.1f * float((x * y) % 3));
    const auto at = [&](int x, int y) { return std::uint32_t(y * (n + 1) + x); };
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            triangles.emplace_back(at(x, y), at(x + 1, y), at(x + 1, y + 1));
            if ((x * 7 + y) % 11 == 0)
                triangles.emplace_back(at(x, y), at(x, y + 1), at(x + 1, y + 1)); // flipped
            else
                triangles.emplace_back(at(x, y), at(x + 1, y + 1), at(x, y + 1));
        }
    for (int fin = 0; fin < 30; ++fin) {
        const int x = (fin * 3) % n, y = (fin * 5) % n;
        positions.emplace_back(float(x) + 0.5f, float(y), 2.0f + float(fin % 2));
        triangles.emplace_back(at(x, y), at(x + 1, y), std::uint32_t(positions.size() - 1));
    }
    triangles.emplace_back(at(3, 3), at(3, 3), at(4, 4));
    positions.emplace_back(0.0f, 0.5f, 0.0f); // on the segment from (0, 0) to (0, 1): a zero-area face
    triangles.emplace_back(at(0, 0), std::uint32_t(positions.size() - 1), at(0, 1));
    triangles.push_back(triangles[17]);
    triangles.push_back(triangles[40]);
    expectReference(positions, triangles, 0.0, "sheet");
    expectReference(positions, triangles, 0.6, "sheet, welded at 0.6 (collapses faces)");
}

TEST(EdgeTableReference, FanHubAndShuffledSoup) {
    // A fan of 300 triangles round one hub (its bucket is sorted by std::stable_sort), closed by a cone of another 300.
    std::vector<glm::vec3> positions = {{0, 0, 0}, {0, 0, 1}};
    std::vector<glm::uvec3> triangles;
    const int spokes = 300;
    for (int i = 0; i < spokes; ++i) {
        const double angle = 2.0 * 3.14159265358979323846 * i / spokes;
        positions.emplace_back(float(std::cos(angle)), float(std::sin(angle)), 0.0f);
    }
    for (int i = 0; i < spokes; ++i) {
        const auto a = std::uint32_t(2 + i), b = std::uint32_t(2 + (i + 1) % spokes);
        triangles.emplace_back(0u, b, a);
        triangles.emplace_back(1u, a, b);
    }
    expectReference(positions, triangles, 0.0, "fan and cone");

    // The same as a soup in shuffled face order, welded back by distance.
    std::vector<glm::vec3> soup;
    std::vector<glm::uvec3> soupTriangles;
    std::mt19937 random(5);
    std::shuffle(triangles.begin(), triangles.end(), random);
    for (const glm::uvec3& t : triangles) {
        const auto first = std::uint32_t(soup.size());
        for (int corner = 0; corner < 3; ++corner) soup.push_back(positions[t[corner]]);
        soupTriangles.emplace_back(first, first + 1, first + 2);
    }
    expectReference(soup, soupTriangles, 1e-6, "shuffled soup");
    expectReference(soup, soupTriangles, 0.0, "shuffled soup, unwelded");
}

TEST(EdgeTableReference, BunnyAndSplitCube) {
    const Scene bunny = loadScene(INKGRAPH_SOURCE_ROOT "/models/bunny_c3d_70k.obj");
    const Mesh& mesh = bunny.meshes.at(0);
    const double distance = LoadOptions{}.weldTolerance * computeBoundingBox(mesh.positions).diagonal();
    expectReference(mesh.positions, mesh.triangles, distance, "bunny");
    const Mesh cube = makeCube(glm::vec3(0.0f), 1.0f);
    expectReference(cube.positions, cube.triangles, 1e-6, "split cube");
    expectReference(cube.positions, cube.triangles, 0.0, "split cube, unwelded");
    expectReference({}, {}, 0.0, "empty");
}

} // namespace
} // namespace inkgraph
