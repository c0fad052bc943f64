// Crease prominence on the mesh (issue 19, docs/lines.md): crease edges chained through the points they share where
// they run on straightest, and kept by the 3-D length of their chain. Known answers: a cube's 12 edges are 12 chains
// (three meet at right angles at each corner), a box made of small facets has 12 chains each as long as the box edge,
// and small bumps on a face make only short chains, dropped while the box's edges stay.
#include "scene/mesh/EdgeAdjacency.h"
#include "scene/mesh/MeshOps.h"
#include "scene/mesh/Procedural.h"

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

#include <cmath>
#include <map>
#include <set>
#include <stdexcept>
#include <vector>

namespace inkgraph {
namespace {

constexpr double kDegrees = glm::pi<double>() / 180.0;

double weldDistanceOf(const Mesh& mesh) {
    return LoadOptions{}.weldTolerance * computeBoundingBox(mesh.positions).diagonal();
}

/** The box [-1, 1]^3 with each face an n x n grid of quads split into two triangles, its vertices not shared between
 *  faces (as a loader leaves a hard edge: the adjacency welds them). Each point in `bumps` (grid cell corners (i, j)
 *  inside the +z face) is raised by `bumpHeight`: a small pyramid whose facets meet at more than the crease angle. */
Mesh gridBox(int n, const std::set<std::pair<int, int>>& bumps = {}, float bumpHeight = 0.0f) {
    Mesh mesh;
    // Face frames: normal axis and sign, and two in-plane axes whose cross product is the outward normal.
    const glm::vec3 normals[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (const glm::vec3& normal : normals) {
        const glm::vec3 u = std::abs(normal.x) > 0.5f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
        const glm::vec3 v = glm::cross(normal, u);
        const auto first = std::uint32_t(mesh.positions.size());
        for (int j = 0; j <= n; ++j)
            for (int i = 0; i <= n; ++i) {
                const float s = -1.0f + 2.0f * float(i) / float(n), t = -1.0f + 2.0f * float(j) / float(n);
                glm::vec3 p = normal + s * u + t * v;
                if (normal.z > 0.5f && bumps.count({i, j})) p += bumpHeight * normal;
                mesh.positions.push_back(p);
            }
        const auto at = [&](int i, int j) { return first + std::uint32_t(j * (n + 1) + i); };
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                mesh.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
                mesh.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
            }
    }
    return mesh;
}

/** Whether edge `edge` lies on one of the box's 12 edges (two coordinates at +-1). */
bool onBoxEdge(const Mesh& mesh, const MeshEdge& edge) {
    const auto onRim = [](float c) { return std::abs(std::abs(c) - 1.0f) < 1e-5f; };
    for (std::uint32_t vertex : {edge.vertices.x, edge.vertices.y}) {
        const glm::vec3 p = mesh.positions[vertex];
        if (onRim(p.x) + onRim(p.y) + onRim(p.z) < 2) return false;
    }
    return true;
}

std::vector<std::uint32_t> creaseEdgeIndices(const EdgeAdjacency& adjacency, double angle) {
    std::vector<std::uint32_t> edges;
    for (std::size_t index = 0; index < adjacency.edges.size(); ++index)
        if (adjacency.edges[index].kind == EdgeKind::Manifold && adjacency.edges[index].normalAngle > angle)
            edges.push_back(std::uint32_t(index));
    return edges;
}

TEST(CreaseChains, CubeEdgesAreTwelveChainsMeetingAtRightAngles) {
    const Mesh cube = makeCube({0.0f, 0.0f, 0.0f}, 1.0f);
    const EdgeAdjacency adjacency = buildEdgeAdjacency(cube.positions, cube.triangles, weldDistanceOf(cube));
    const std::vector<std::uint32_t> creases = creaseEdgeIndices(adjacency, 30.0 * kDegrees);
    ASSERT_EQ(creases.size(), 12u);
    const EdgeChains chains = chainEdges(adjacency, cube.positions, creases, kCreaseChainMaxTurnRadians);
    EXPECT_EQ(chains.edges, creases);
    // Three edges at right angles at each corner: a turn of 90 degrees, past 60, so no edge runs on into another.
    ASSERT_EQ(chains.chainLength.size(), 12u);
    for (double length : chains.chainLength) EXPECT_NEAR(length, 2.0, 1e-6);
    for (double angle : chains.chainNormalAngle) EXPECT_NEAR(angle, glm::half_pi<double>(), 1e-6);
    // The bounding radius is sqrt(3); an edge is 2 / sqrt(3) = 1.155 of it. Kept at any share up to that.
    const double radius = std::sqrt(3.0);
    for (double share : {0.0, 0.15, 0.3, 1.0, 1.15}) {
        const CreaseSelection kept =
            selectProminentCreaseEdges(adjacency, cube.positions, 30.0 * kDegrees, share * radius);
        EXPECT_EQ(kept.edgesByAngle, 12u) << share;
        EXPECT_EQ(kept.edgesKept, 12u) << share;
        EXPECT_EQ(kept.chainsKept, 12u) << share;
        EXPECT_EQ(kept.indices, selectCreaseEdges(adjacency, 30.0 * kDegrees)) << share;
    }
    const CreaseSelection none = selectProminentCreaseEdges(adjacency, cube.positions, 30.0 * kDegrees, 1.2 * radius);
    EXPECT_EQ(none.edgesByAngle, 12u);
    EXPECT_EQ(none.edgesKept, 0u);
    EXPECT_TRUE(none.indices.empty());
    // With a turn of 90 degrees allowed, edges pair up through the corners (greedy, so some pairs are left over).
    const EdgeChains loose = chainEdges(adjacency, cube.positions, creases, 90.0 * kDegrees);
    EXPECT_LT(loose.chainLength.size(), 12u);
}

TEST(CreaseChains, CollinearShortEdgesMakeOneChainAsLongAsTheirSum) {
    constexpr int kCells = 40;
    const Mesh box = gridBox(kCells);
    const EdgeAdjacency adjacency = buildEdgeAdjacency(box.positions, box.triangles, weldDistanceOf(box));
    EXPECT_EQ(adjacency.counts.boundary, 0u);
    const std::vector<std::uint32_t> creases = creaseEdgeIndices(adjacency, 30.0 * kDegrees);
    ASSERT_EQ(creases.size(), 12u * kCells);
    const EdgeChains chains = chainEdges(adjacency, box.positions, creases, kCreaseChainMaxTurnRadians);
    ASSERT_EQ(chains.chainLength.size(), 12u);
    std::map<std::uint32_t, int> edgesPerChain;
    for (std::uint32_t chain : chains.chainOf) ++edgesPerChain[chain];
    for (const auto& [chain, edges] : edgesPerChain) {
        EXPECT_EQ(edges, kCells) << chain;
        EXPECT_NEAR(chains.chainLength[chain], 2.0, 1e-5) << chain; // 40 edges of 0.05
    }
    // One edge is 0.05 / sqrt(3) = 0.03 of the radius; its chain is 1.155, so it stays at a share of 1.
    const CreaseSelection kept =
        selectProminentCreaseEdges(adjacency, box.positions, 30.0 * kDegrees, 1.0 * std::sqrt(3.0));
    EXPECT_EQ(kept.edgesKept, 12u * kCells);
}

TEST(CreaseChains, BumpsOnAFaceAreDroppedWhileTheBoxEdgesStay) {
    constexpr int kCells = 40;
    // Nine bumps one cell high (45-degree facets), apart from each other and from the face's rim.
    std::set<std::pair<int, int>> bumps;
    for (int i : {8, 20, 32})
        for (int j : {8, 20, 32}) bumps.insert({i, j});
    const Mesh box = gridBox(kCells, bumps, 2.0f / kCells);
    const EdgeAdjacency adjacency = buildEdgeAdjacency(box.positions, box.triangles, weldDistanceOf(box));
    const double creaseAngle = 30.0 * kDegrees;
    const std::vector<std::uint32_t> creases = creaseEdgeIndices(adjacency, creaseAngle);
    std::size_t boxEdges = 0;
    for (std::uint32_t edge : creases) boxEdges += onBoxEdge(box, adjacency.edges[edge]);
    EXPECT_EQ(boxEdges, 12u * kCells);
    ASSERT_GT(creases.size(), boxEdges + 9u * 6u); // each bump adds at least its six spokes

    const double radius = std::sqrt(3.0);
    for (double share : {0.15, 0.2, 0.3}) {
        const CreaseSelection kept = selectProminentCreaseEdges(adjacency, box.positions, creaseAngle, share * radius);
        EXPECT_EQ(kept.edgesByAngle, creases.size()) << share;
        EXPECT_EQ(kept.edgesKept, 12u * kCells) << share;
        EXPECT_EQ(kept.chainsKept, 12u) << share;
        // Exactly the box's edges.
        for (std::size_t index = 0; index < kept.indices.size(); index += 2) {
            MeshEdge edge{};
            edge.vertices = {kept.indices[index], kept.indices[index + 1]};
            EXPECT_TRUE(onBoxEdge(box, edge)) << index;
        }
    }
    // 0 keeps every crease.
    EXPECT_EQ(selectProminentCreaseEdges(adjacency, box.positions, creaseAngle, 0.0).edgesKept, creases.size());
}

TEST(CreaseChains, ChoiceIsViewIndependentAndScalesWithTheModel) {
    // The selection takes no camera or picture size: what a 1024 and a 2048 picture draw is the same edge set. What
    // it depends on is the length in model units, so a model twice as large with twice the length keeps the same.
    std::set<std::pair<int, int>> bumps{{10, 10}, {30, 30}};
    Mesh box = gridBox(40, bumps, 0.05f);
    const EdgeAdjacency adjacency = buildEdgeAdjacency(box.positions, box.triangles, weldDistanceOf(box));
    const CreaseSelection first = selectProminentCreaseEdges(adjacency, box.positions, 30.0 * kDegrees, 0.35);
    const CreaseSelection again = selectProminentCreaseEdges(adjacency, box.positions, 30.0 * kDegrees, 0.35);
    EXPECT_EQ(first.indices, again.indices);
    for (glm::vec3& p : box.positions) p *= 2.0f;
    const EdgeAdjacency doubled = buildEdgeAdjacency(box.positions, box.triangles, weldDistanceOf(box));
    EXPECT_EQ(selectProminentCreaseEdges(doubled, box.positions, 30.0 * kDegrees, 0.7).indices, first.indices);
}

TEST(CreaseChains, BadInputThrowsNamingTheFunction) {
    const Mesh cube = makeCube({0.0f, 0.0f, 0.0f}, 1.0f);
    const EdgeAdjacency adjacency = buildEdgeAdjacency(cube.positions, cube.triangles, weldDistanceOf(cube));
    const std::vector<std::uint32_t> past{std::uint32_t(adjacency.edges.size())};
    try {
        chainEdges(adjacency, cube.positions, past, 1.0);
        FAIL() << "expected std::out_of_range";
    } catch (const std::out_of_range& error) {
        EXPECT_EQ(std::string(error.what()).rfind("chainEdges(): ", 0), 0u) << error.what();
    }
    EXPECT_THROW(chainEdges(adjacency, cube.positions, {}, -0.1), std::invalid_argument);
    EXPECT_THROW(chainEdges(adjacency, cube.positions, {}, 4.0), std::invalid_argument);
    EXPECT_THROW(chainEdges(adjacency, std::span<const glm::vec3>(cube.positions).first(3),
                            std::vector<std::uint32_t>{0u, 1u, 2u, 3u, 4u, 5u}, 1.0),
                 std::out_of_range);
    try {
        selectProminentCreaseEdges(adjacency, cube.positions, 0.5, -1.0);
        FAIL() << "expected std::invalid_argument";
    } catch (const std::invalid_argument& error) {
        EXPECT_EQ(std::string(error.what()).rfind("selectProminentCreaseEdges(): 'minChainLength'", 0), 0u)
            << error.what();
    }
    EXPECT_TRUE(chainEdges(adjacency, cube.positions, {}, 1.0).chainLength.empty());
}

} // namespace
} // namespace inkgraph
