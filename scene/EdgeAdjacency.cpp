#include "scene/EdgeAdjacency.h"

#include "scene/MeshOps.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace inkgraph {
namespace {

/** Relative area at or below which a face counts as degenerate (times the squared bounding-box diagonal): the
 *  loaders' rule (MeshOps finalizeMesh), so a loaded mesh loses nothing more here. */
constexpr double kDegenerateAreaRelative = 1e-14;

std::uint64_t edgeKey(std::uint32_t a, std::uint32_t b) {
    const std::uint32_t low = a < b ? a : b;
    const std::uint32_t high = a < b ? b : a;
    return (std::uint64_t(low) << 32) | high;
}

/** Open-addressing hash map from an edge key to its index in the edge list, linear probing, kept at most half full
 *  (it doubles past that). Key and index share a slot, so a probe costs one cache miss: on large meshes the lookups
 *  are random accesses into a table far bigger than the cache, and std::unordered_map's node per edge cost more. No
 *  key equals kEmptyKey: it would need min == max. */
class EdgeIndexTable {
public:
    explicit EdgeIndexTable(std::size_t expectedEdges) {
        allocate(std::bit_ceil(std::max<std::size_t>(16, 2 * expectedEdges)));
    }

    /** The index stored for `key`, storing `indexIfNew` first when the key is new; `second` tells which. */
    std::pair<std::uint32_t, bool> findOrInsert(std::uint64_t key, std::uint32_t indexIfNew) {
        if (2 * (mCount + 1) > mSlots.size()) grow();
        for (std::size_t index = mix(key) & mMask;; index = (index + 1) & mMask) {
            Slot& slot = mSlots[index];
            if (slot.key == key) return {slot.edge, false};
            if (slot.key == kEmptyKey) {
                slot = {key, indexIfNew};
                ++mCount;
                return {indexIfNew, true};
            }
        }
    }

private:
    static constexpr std::uint64_t kEmptyKey = ~std::uint64_t(0);

    struct Slot {
        std::uint64_t key = kEmptyKey;
        std::uint32_t edge = 0;
    };

    // The splitmix64 finaliser: neighbouring vertex ids (the common case) spread over the whole table, so a vertex
    // shared by many faces (a fan's hub) makes no long probe runs.
    static std::uint64_t mix(std::uint64_t key) {
        key ^= key >> 30;
        key *= 0xBF58476D1CE4E5B9ull;
        key ^= key >> 27;
        key *= 0x94D049BB133111EBull;
        return key ^ (key >> 31);
    }

    void allocate(std::size_t capacity) {
        mSlots.assign(capacity, Slot{});
        mMask = capacity - 1;
        mCount = 0;
    }

    void grow() {
        std::vector<Slot> old = std::move(mSlots);
        allocate(2 * old.size());
        for (const Slot& slot : old)
            if (slot.key != kEmptyKey) findOrInsert(slot.key, slot.edge);
    }

    std::vector<Slot> mSlots;
    std::size_t mMask = 0;
    std::size_t mCount = 0;
};

/** One face's use of an edge before grouping: which edge (index into the edge list), which face, which way. */
struct PendingUse {
    std::uint32_t edge;
    EdgeFaceUse use;
};

} // namespace

EdgeAdjacency buildEdgeAdjacency(std::span<const glm::vec3> positions, std::span<const glm::uvec3> triangles,
                                 double weldDistance) {
    if (!std::isfinite(weldDistance) || weldDistance < 0.0)
        throw std::invalid_argument("buildEdgeAdjacency(): 'weldDistance' must be finite and >= 0, got " +
                                    std::to_string(weldDistance));
    return buildEdgeAdjacency(positions, triangles, weldVertices(positions, {}, weldDistance));
}

EdgeAdjacency buildEdgeAdjacency(std::span<const glm::vec3> positions, std::span<const glm::uvec3> triangles,
                                 const WeldMap& weld) {
    if (weld.outputOf.size() != positions.size())
        throw std::invalid_argument("buildEdgeAdjacency(): the weld maps " + std::to_string(weld.outputOf.size()) +
                                    " vertices, not the " + std::to_string(positions.size()) + " 'positions'");
    const auto vertexCount = std::uint32_t(positions.size());
    for (std::size_t face = 0; face < triangles.size(); ++face)
        if (glm::any(glm::greaterThanEqual(triangles[face], glm::uvec3(vertexCount))))
            throw std::out_of_range("buildEdgeAdjacency(): triangle " + std::to_string(face) +
                                    " names a vertex past the " + std::to_string(positions.size()) + " positions");

    const double diagonal = computeBoundingBox(positions).diagonal();
    // |cross| is twice the area.
    const double minCrossLength = 2.0 * kDegenerateAreaRelative * diagonal * diagonal;

    EdgeAdjacency adjacency;
    adjacency.faceNormals.assign(triangles.size(), glm::vec3(0.0f));
    adjacency.facePlaneOffsets.assign(triangles.size(), 0.0);

    EdgeIndexTable edgeOfKey(triangles.size() * 3 / 2); // welded key -> index into adjacency.edges; a closed mesh
                                                        // has 1.5 edges per face
    std::vector<PendingUse> pending;
    pending.reserve(triangles.size() * 3);

    for (std::size_t faceIndex = 0; faceIndex < triangles.size(); ++faceIndex) {
        const glm::uvec3& triangle = triangles[faceIndex];
        const glm::uvec3 welded(weld.outputOf[triangle.x], weld.outputOf[triangle.y], weld.outputOf[triangle.z]);
        const glm::dvec3 a(positions[triangle.x]);
        const glm::dvec3 cross =
            glm::cross(glm::dvec3(positions[triangle.y]) - a, glm::dvec3(positions[triangle.z]) - a);
        const double crossLength = glm::length(cross);
        const bool repeatsVertex = welded.x == welded.y || welded.y == welded.z || welded.x == welded.z;
        if (repeatsVertex || !(crossLength > minCrossLength)) {
            ++adjacency.counts.degenerateFaces;
            continue;
        }
        const glm::dvec3 normal = cross / crossLength;
        adjacency.faceNormals[faceIndex] = glm::vec3(normal);
        // The offset from the stored (float) normal, so eyeSideOfFace() tests exactly the plane through `a` it
        // describes.
        adjacency.facePlaneOffsets[faceIndex] = glm::dot(glm::dvec3(adjacency.faceNormals[faceIndex]), a);

        const auto face = std::uint32_t(faceIndex);
        // Every edge of the face on its own: Lander 2000's Templist marked a face "found" at its first matching edge
        // and never added the other two.
        for (int corner = 0; corner < 3; ++corner) {
            const std::uint32_t from = welded[corner];
            const std::uint32_t to = welded[(corner + 1) % 3];
            const auto [edgeIndex, inserted] =
                edgeOfKey.findOrInsert(edgeKey(from, to), std::uint32_t(adjacency.edges.size()));
            if (inserted) {
                MeshEdge edge{};
                edge.vertices = glm::uvec2(triangle[corner], triangle[(corner + 1) % 3]);
                edge.welded = glm::uvec2(from, to);
                adjacency.edges.push_back(edge);
            }
            pending.push_back({edgeIndex, {face, from > to}});
        }
    }

    // Group the uses by edge (a counting sort keeps face order within each edge).
    std::vector<std::uint32_t> useCount(adjacency.edges.size(), 0);
    for (const PendingUse& use : pending) ++useCount[use.edge];
    std::uint32_t offset = 0;
    for (std::size_t edge = 0; edge < adjacency.edges.size(); ++edge) {
        adjacency.edges[edge].firstFaceUse = offset;
        adjacency.edges[edge].faceCount = useCount[edge];
        offset += useCount[edge];
    }
    adjacency.faceUses.resize(pending.size());
    std::vector<std::uint32_t> nextSlot(adjacency.edges.size());
    for (std::size_t edge = 0; edge < adjacency.edges.size(); ++edge)
        nextSlot[edge] = adjacency.edges[edge].firstFaceUse;
    for (const PendingUse& use : pending) adjacency.faceUses[nextSlot[use.edge]++] = use.use;

    for (MeshEdge& edge : adjacency.edges) {
        if (edge.faceCount == 1) {
            edge.kind = EdgeKind::Boundary;
            ++adjacency.counts.boundary;
            continue;
        }
        if (edge.faceCount > 2) {
            edge.kind = EdgeKind::NonManifold;
            ++adjacency.counts.nonManifold;
            continue;
        }
        edge.kind = EdgeKind::Manifold;
        ++adjacency.counts.manifold;
        const EdgeFaceUse& first = adjacency.faceUses[edge.firstFaceUse];
        const EdgeFaceUse& second = adjacency.faceUses[edge.firstFaceUse + 1];
        // Consistently oriented neighbours run their shared edge in opposite directions.
        edge.inconsistentOrientation = first.againstKey == second.againstKey;
        adjacency.counts.inconsistent += edge.inconsistentOrientation;
        const glm::dvec3 n1(adjacency.faceNormals[first.face]);
        const glm::dvec3 n2 =
            glm::dvec3(adjacency.faceNormals[second.face]) * (edge.inconsistentOrientation ? -1.0 : 1.0);
        edge.normalAngle = float(std::atan2(glm::length(glm::cross(n1, n2)), glm::dot(n1, n2)));
    }
    return adjacency;
}

bool isSilhouetteEdge(const EdgeAdjacency& adjacency, const MeshEdge& edge, const glm::dvec3& eye) {
    if (edge.kind != EdgeKind::Manifold) return false;
    const double first = eyeSideOfFace(adjacency, adjacency.faceUses[edge.firstFaceUse].face, eye);
    const double second = eyeSideOfFace(adjacency, adjacency.faceUses[edge.firstFaceUse + 1].face, eye);
    return facesEye(first, false) != facesEye(second, edge.inconsistentOrientation);
}

std::vector<std::uint32_t> selectSilhouetteEdges(const EdgeAdjacency& adjacency, const glm::dvec3& eye) {
    // s per face once: a face serves three edges.
    std::vector<double> side(adjacency.faceNormals.size());
    for (std::size_t face = 0; face < side.size(); ++face)
        side[face] = eyeSideOfFace(adjacency, std::uint32_t(face), eye);
    std::vector<std::uint32_t> indices;
    for (const MeshEdge& edge : adjacency.edges) {
        if (edge.kind != EdgeKind::Manifold) continue;
        const bool firstFront = facesEye(side[adjacency.faceUses[edge.firstFaceUse].face], false);
        const bool secondFront =
            facesEye(side[adjacency.faceUses[edge.firstFaceUse + 1].face], edge.inconsistentOrientation);
        if (firstFront == secondFront) continue;
        indices.push_back(edge.vertices.x);
        indices.push_back(edge.vertices.y);
    }
    return indices;
}

namespace {

/** A crease: a manifold edge whose faces' normals meet at more than the angle. */
bool isCrease(const MeshEdge& edge, double creaseAngleRadians) {
    return edge.kind == EdgeKind::Manifold && double(edge.normalAngle) > creaseAngleRadians;
}

} // namespace

std::vector<std::uint32_t> selectCreaseEdges(const EdgeAdjacency& adjacency, double creaseAngleRadians) {
    std::vector<std::uint32_t> indices;
    for (const MeshEdge& edge : adjacency.edges) {
        if (!isCrease(edge, creaseAngleRadians)) continue;
        indices.push_back(edge.vertices.x);
        indices.push_back(edge.vertices.y);
    }
    return indices;
}

EdgeChains chainEdges(const EdgeAdjacency& adjacency, std::span<const glm::vec3> positions,
                      std::span<const std::uint32_t> edges, double maxTurnRadians) {
    if (!(maxTurnRadians >= 0.0 && maxTurnRadians <= 3.14159265358979323846))
        throw std::invalid_argument("chainEdges(): 'maxTurnRadians' must be in [0, pi], got " +
                                    std::to_string(maxTurnRadians));
    std::uint32_t weldedCount = 0;
    for (std::uint32_t edge : edges) {
        if (edge >= adjacency.edges.size())
            throw std::out_of_range("chainEdges(): edge " + std::to_string(edge) + " is past the " +
                                    std::to_string(adjacency.edges.size()) + " edges");
        const MeshEdge& meshEdge = adjacency.edges[edge];
        if (std::max(meshEdge.vertices.x, meshEdge.vertices.y) >= positions.size())
            throw std::out_of_range("chainEdges(): edge " + std::to_string(edge) + " names a vertex past the " +
                                    std::to_string(positions.size()) + " positions");
        weldedCount = std::max(weldedCount, std::max(meshEdge.welded.x, meshEdge.welded.y) + 1);
    }
    const std::size_t count = edges.size();
    // An edge end is 2 x slot + end (end 0: vertices.x). The ends at each welded point, grouped (counting sort).
    std::vector<std::uint32_t> firstEnd(std::size_t(weldedCount) + 1, 0);
    for (std::uint32_t edge : edges) {
        ++firstEnd[adjacency.edges[edge].welded.x + 1];
        ++firstEnd[adjacency.edges[edge].welded.y + 1];
    }
    for (std::size_t point = 0; point < weldedCount; ++point) firstEnd[point + 1] += firstEnd[point];
    std::vector<std::uint32_t> endsAt(2 * count);
    {
        std::vector<std::uint32_t> next(firstEnd.begin(), firstEnd.end() - 1);
        for (std::size_t slot = 0; slot < count; ++slot) {
            const glm::uvec2 welded = adjacency.edges[edges[slot]].welded;
            endsAt[next[welded.x]++] = std::uint32_t(2 * slot);
            endsAt[next[welded.y]++] = std::uint32_t(2 * slot + 1);
        }
    }

    // Pair the ends at each point, straightest first. The turn between an edge arriving along -u_a and one leaving
    // along u_b is pi minus the angle between the unit directions u_a, u_b away from the point: cos(turn) = -u_a.u_b.
    constexpr std::uint32_t kNone = ~std::uint32_t(0);
    std::vector<std::uint32_t> partner(2 * count, kNone);
    const double minStraightness = std::cos(maxTurnRadians) - 1e-12; // the turn's cosine; a tolerance for 60 exactly
    struct Pair {
        double straightness; // cos(turn)
        std::uint32_t a, b;
    };
    std::vector<Pair> pairs;
    std::vector<glm::dvec3> away;
    for (std::size_t point = 0; point < weldedCount; ++point) {
        const std::uint32_t begin = firstEnd[point], end = firstEnd[point + 1];
        if (end - begin < 2) continue;
        away.clear();
        for (std::uint32_t index = begin; index < end; ++index) {
            const std::uint32_t edgeEnd = endsAt[index];
            const MeshEdge& edge = adjacency.edges[edges[edgeEnd / 2]];
            const glm::dvec3 here(positions[edgeEnd % 2 ? edge.vertices.y : edge.vertices.x]);
            const glm::dvec3 there(positions[edgeEnd % 2 ? edge.vertices.x : edge.vertices.y]);
            const double length = glm::length(there - here);
            away.push_back(length > 0.0 ? (there - here) / length : glm::dvec3(0.0));
        }
        pairs.clear();
        for (std::uint32_t a = 0; a + 1 < end - begin; ++a)
            for (std::uint32_t b = a + 1; b < end - begin; ++b) {
                if (away[a] == glm::dvec3(0.0) || away[b] == glm::dvec3(0.0)) continue; // no direction to follow
                const double straightness = -glm::dot(away[a], away[b]);
                if (straightness >= minStraightness) pairs.push_back({straightness, begin + a, begin + b});
            }
        // Ties (a symmetric star) go to the earlier ends, so the result does not depend on the sort.
        std::sort(pairs.begin(), pairs.end(), [](const Pair& x, const Pair& y) {
            if (x.straightness != y.straightness) return x.straightness > y.straightness;
            return x.a != y.a ? x.a < y.a : x.b < y.b;
        });
        for (const Pair& pair : pairs) {
            const std::uint32_t a = endsAt[pair.a], b = endsAt[pair.b];
            if (partner[a] != kNone || partner[b] != kNone) continue;
            partner[a] = b;
            partner[b] = a;
        }
    }

    // Each edge has at most one partner per end: the chains are the connected runs (union-find over the pairs).
    std::vector<std::uint32_t> parent(count);
    for (std::size_t slot = 0; slot < count; ++slot) parent[slot] = std::uint32_t(slot);
    const auto root = [&parent](std::uint32_t slot) {
        while (parent[slot] != slot) slot = parent[slot] = parent[parent[slot]];
        return slot;
    };
    for (std::size_t edgeEnd = 0; edgeEnd < 2 * count; ++edgeEnd)
        if (partner[edgeEnd] != kNone) {
            const std::uint32_t a = root(std::uint32_t(edgeEnd / 2)), b = root(partner[edgeEnd] / 2);
            if (a != b) parent[std::max(a, b)] = std::min(a, b);
        }

    EdgeChains chains;
    chains.edges.assign(edges.begin(), edges.end());
    chains.chainOf.assign(count, kNone);
    std::vector<std::uint32_t> chainOfRoot(count, kNone);
    for (std::size_t slot = 0; slot < count; ++slot) {
        const std::uint32_t top = root(std::uint32_t(slot));
        if (chainOfRoot[top] == kNone) {
            chainOfRoot[top] = std::uint32_t(chains.chainLength.size());
            chains.chainLength.push_back(0.0);
            chains.chainNormalAngle.push_back(0.0);
        }
        const std::uint32_t chain = chainOfRoot[top];
        chains.chainOf[slot] = chain;
        const MeshEdge& edge = adjacency.edges[edges[slot]];
        const double length =
            glm::length(glm::dvec3(positions[edge.vertices.y]) - glm::dvec3(positions[edge.vertices.x]));
        chains.chainLength[chain] += length;
        chains.chainNormalAngle[chain] += length * double(edge.normalAngle);
    }
    for (std::size_t chain = 0; chain < chains.chainLength.size(); ++chain)
        chains.chainNormalAngle[chain] =
            chains.chainLength[chain] > 0.0 ? chains.chainNormalAngle[chain] / chains.chainLength[chain] : 0.0;
    return chains;
}

CreaseSelection selectProminentCreaseEdges(const EdgeAdjacency& adjacency, std::span<const glm::vec3> positions,
                                           double creaseAngleRadians, double minChainLength) {
    if (!std::isfinite(minChainLength) || minChainLength < 0.0)
        throw std::invalid_argument("selectProminentCreaseEdges(): 'minChainLength' must be finite and >= 0, got " +
                                    std::to_string(minChainLength));
    std::vector<std::uint32_t> creases;
    for (std::size_t index = 0; index < adjacency.edges.size(); ++index)
        if (isCrease(adjacency.edges[index], creaseAngleRadians)) creases.push_back(std::uint32_t(index));
    CreaseSelection selection;
    selection.edgesByAngle = creases.size();
    const EdgeChains chains = chainEdges(adjacency, positions, creases, kCreaseChainMaxTurnRadians);
    selection.chains = chains.chainLength.size();
    std::vector<bool> keep(chains.chainLength.size());
    for (std::size_t chain = 0; chain < keep.size(); ++chain) {
        keep[chain] = chains.chainLength[chain] >= minChainLength;
        selection.chainsKept += keep[chain];
    }
    for (std::size_t slot = 0; slot < creases.size(); ++slot) {
        if (!keep[chains.chainOf[slot]]) continue;
        const MeshEdge& edge = adjacency.edges[creases[slot]];
        selection.indices.push_back(edge.vertices.x);
        selection.indices.push_back(edge.vertices.y);
        ++selection.edgesKept;
    }
    return selection;
}

std::vector<std::uint32_t> selectBorderEdges(const EdgeAdjacency& adjacency) {
    std::vector<std::uint32_t> indices;
    for (const MeshEdge& edge : adjacency.edges) {
        if (edge.kind == EdgeKind::Manifold) continue;
        indices.push_back(edge.vertices.x);
        indices.push_back(edge.vertices.y);
    }
    return indices;
}

} // namespace inkgraph
