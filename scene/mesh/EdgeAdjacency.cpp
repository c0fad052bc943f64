#include "scene/mesh/EdgeAdjacency.h"

#include "scene/mesh/DisjointSets.h"
#include "scene/mesh/MeshOps.h"
#include "scene/mesh/ParallelRanges.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace inkgraph {
namespace {

constexpr std::uint32_t kNone = ~std::uint32_t(0);

/** Faces per parallel chunk below which a thread is not worth starting. */
constexpr std::size_t kMinChunk = 1 << 14;

/** One face's use of an edge, filed under the edge's smaller welded id: the larger id and the use, (3 x face + corner)
 *  x 2 + 1 when the face runs the edge from the larger id to the smaller (against the key). */
struct EdgeEntry {
    std::uint32_t high;
    std::uint32_t use;
};

/** Sorts one bucket's entries by `high`, keeping their order (face order) among equal ones: an insertion sort, as a
 *  bucket holds a vertex's few edges, except at a fan's hub. */
void sortBucket(EdgeEntry* begin, EdgeEntry* end) {
    // Nothing to sort, and `begin + 1` is undefined when there are no entries at all (a null begin: a mesh whose
    // every face is degenerate once welded; fuzz_obj and fuzz_ply found it).
    if (end - begin < 2) return;
    if (end - begin > 32) {
        std::stable_sort(begin, end, [](const EdgeEntry& a, const EdgeEntry& b) { return a.high < b.high; });
        return;
    }
    for (EdgeEntry* at = begin + 1; at < end; ++at) {
        const EdgeEntry entry = *at;
        EdgeEntry* hole = at;
        for (; hole > begin && hole[-1].high > entry.high; --hole) *hole = hole[-1];
        *hole = entry;
    }
}

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

    // Uses are numbered 3 x face + corner and carry a direction bit: they must fit 32 bits.
    if (triangles.size() > (std::size_t(kNone) >> 1) / 3)
        throw std::length_error("buildEdgeAdjacency(): " + std::to_string(triangles.size()) +
                                " triangles are too many for 32-bit edge uses");
    const double diagonal = computeBoundingBox(positions).diagonal();
    // |cross| is twice the area.
    const double minCrossLength = 2.0 * kDegenerateAreaRelative * diagonal * diagonal;
    const std::size_t faceCount = triangles.size();
    const std::size_t weldedCount = weld.kept.size();

    EdgeAdjacency adjacency;
    adjacency.faceNormals.assign(faceCount, glm::vec3(0.0f));
    adjacency.facePlaneOffsets.assign(faceCount, 0.0);

    // 1. Each face's welded corners (x = kNone for a skipped face), unit normal and plane, in parallel.
    std::vector<glm::uvec3> weldedFaces(faceCount);
    std::vector<std::size_t> degenerate(parallelChunkCount(faceCount, kMinChunk), 0);
    parallelRanges(faceCount, kMinChunk, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
        for (std::size_t faceIndex = begin; faceIndex < end; ++faceIndex) {
            const glm::uvec3& triangle = triangles[faceIndex];
            const glm::uvec3 welded(weld.outputOf[triangle.x], weld.outputOf[triangle.y], weld.outputOf[triangle.z]);
            const glm::dvec3 a(positions[triangle.x]);
            const glm::dvec3 cross =
                glm::cross(glm::dvec3(positions[triangle.y]) - a, glm::dvec3(positions[triangle.z]) - a);
            const double crossLength = glm::length(cross);
            const bool repeatsVertex = welded.x == welded.y || welded.y == welded.z || welded.x == welded.z;
            if (repeatsVertex || !(crossLength > minCrossLength)) {
                ++degenerate[chunk];
                weldedFaces[faceIndex] = glm::uvec3(kNone);
                continue;
            }
            weldedFaces[faceIndex] = welded;
            const glm::dvec3 normal = cross / crossLength;
            adjacency.faceNormals[faceIndex] = glm::vec3(normal);
            // The offset from the stored (float) normal, so eyeSideOfFace() tests exactly the plane through `a` it
            // describes.
            adjacency.facePlaneOffsets[faceIndex] = glm::dot(glm::dvec3(adjacency.faceNormals[faceIndex]), a);
        }
    });
    for (const std::size_t count : degenerate) adjacency.counts.degenerateFaces += count;

    // 2. Every edge of every other face on its own (Lander 2000's Templist marked a face "found" at its first matching
    // edge and never added the other two), filed under its smaller welded id by a counting sort, which keeps face
    // order within each id; then each id's entries sorted by the larger id. A run of equal ids is one edge, its
    // entries the faces using it in face order. No hash table: on a large mesh its lookups were one cache miss each.
    std::vector<std::uint32_t> bucketStart(weldedCount + 1, 0);
    for (const glm::uvec3& welded : weldedFaces) {
        if (welded.x == kNone) continue;
        for (int corner = 0; corner < 3; ++corner)
            ++bucketStart[std::min(welded[corner], welded[(corner + 1) % 3]) + 1];
    }
    for (std::size_t vertex = 0; vertex < weldedCount; ++vertex) bucketStart[vertex + 1] += bucketStart[vertex];
    std::vector<EdgeEntry> entries(bucketStart[weldedCount]);
    {
        std::vector<std::uint32_t> next(bucketStart.begin(), bucketStart.end() - 1);
        for (std::size_t face = 0; face < faceCount; ++face) {
            const glm::uvec3& welded = weldedFaces[face];
            if (welded.x == kNone) continue;
            for (int corner = 0; corner < 3; ++corner) {
                const std::uint32_t from = welded[corner], to = welded[(corner + 1) % 3];
                const auto use = std::uint32_t(3 * face + std::size_t(corner));
                entries[next[std::min(from, to)]++] = {std::max(from, to), use << 1 | std::uint32_t(from > to)};
            }
        }
    }
    std::vector<std::uint32_t> groupsInChunk(parallelChunkCount(weldedCount, kMinChunk), 0);
    parallelRanges(weldedCount, kMinChunk, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
        for (std::size_t vertex = begin; vertex < end; ++vertex) {
            EdgeEntry* first = entries.data() + bucketStart[vertex];
            EdgeEntry* last = entries.data() + bucketStart[vertex + 1];
            sortBucket(first, last);
            for (EdgeEntry* at = first; at < last; ++at) groupsInChunk[chunk] += at == first || at[-1].high != at->high;
        }
    });

    // 3. The edges in order of first use (face order, then the face's edge order): each run's first entry is its
    // first use; marked by use, then read in use order.
    std::uint32_t groupCount = 0;
    for (std::uint32_t& groups : groupsInChunk) groupCount += std::exchange(groups, groupCount); // now: first id
    std::vector<std::uint32_t> groupBegin(std::size_t(groupCount) + 1, std::uint32_t(entries.size()));
    std::vector<std::uint32_t> groupOfFirstUse(3 * faceCount, kNone);
    parallelRanges(weldedCount, kMinChunk, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
        std::uint32_t group = groupsInChunk[chunk];
        for (std::size_t vertex = begin; vertex < end; ++vertex)
            for (std::uint32_t at = bucketStart[vertex]; at < bucketStart[vertex + 1]; ++at) {
                if (at != bucketStart[vertex] && entries[at - 1].high == entries[at].high) continue;
                groupBegin[group] = at;
                groupOfFirstUse[entries[at].use >> 1] = group++;
            }
    });
    // 4. The edges and their face uses (each edge's uses at the running total of those before it), then each edge's
    // kind and normal angle, in parallel over edges. Taken in edge order, the groups and the second faces' normals
    // are scattered over memory, so each is asked for (prefetched) kLookAhead edges before it is read.
    constexpr std::size_t kLookAhead = 16;
    std::vector<std::uint32_t> firstEntry(groupCount); // per edge, into entries
    adjacency.edges.resize(groupCount);
    {
        std::size_t edge = 0;
        std::uint32_t offset = 0;
        for (std::size_t use = 0; use < groupOfFirstUse.size(); ++use) {
            if (use + 4 * kLookAhead < groupOfFirstUse.size() && groupOfFirstUse[use + 4 * kLookAhead] != kNone)
                __builtin_prefetch(&groupBegin[groupOfFirstUse[use + 4 * kLookAhead]]);
            const std::uint32_t group = groupOfFirstUse[use];
            if (group == kNone) continue;
            firstEntry[edge] = groupBegin[group];
            adjacency.edges[edge].firstFaceUse = offset;
            adjacency.edges[edge].faceCount = groupBegin[group + 1] - groupBegin[group];
            offset += adjacency.edges[edge].faceCount;
            ++edge;
        }
    }
    groupOfFirstUse = {};
    groupBegin = {};
    adjacency.faceUses.resize(entries.size());
    std::vector<EdgeAdjacencyCounts> counts(parallelChunkCount(groupCount, kMinChunk));
    parallelRanges(groupCount, kMinChunk, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
        EdgeAdjacencyCounts& count = counts[chunk];
        for (std::size_t edgeIndex = begin; edgeIndex < end; ++edgeIndex) {
            if (edgeIndex + 2 * kLookAhead < end) __builtin_prefetch(&entries[firstEntry[edgeIndex + 2 * kLookAhead]]);
            if (edgeIndex + kLookAhead < end && adjacency.edges[edgeIndex + kLookAhead].faceCount == 2)
                __builtin_prefetch(&adjacency.faceNormals[entries[firstEntry[edgeIndex + kLookAhead] + 1].use / 6]);
            MeshEdge& edge = adjacency.edges[edgeIndex];
            const EdgeEntry* uses = entries.data() + firstEntry[edgeIndex];
            for (std::uint32_t at = 0; at < edge.faceCount; ++at)
                adjacency.faceUses[edge.firstFaceUse + at] = {uses[at].use / 6, (uses[at].use & 1u) != 0};
            const std::uint32_t firstUse = uses[0].use >> 1;
            const std::uint32_t face = firstUse / 3, corner = firstUse % 3, next = (corner + 1) % 3;
            edge.vertices = glm::uvec2(triangles[face][int(corner)], triangles[face][int(next)]);
            edge.welded = glm::uvec2(weldedFaces[face][int(corner)], weldedFaces[face][int(next)]);

            if (edge.faceCount == 1) {
                edge.kind = EdgeKind::Boundary;
                ++count.boundary;
                continue;
            }
            if (edge.faceCount > 2) {
                edge.kind = EdgeKind::NonManifold;
                ++count.nonManifold;
                continue;
            }
            edge.kind = EdgeKind::Manifold;
            ++count.manifold;
            const EdgeFaceUse& first = adjacency.faceUses[edge.firstFaceUse];
            const EdgeFaceUse& second = adjacency.faceUses[edge.firstFaceUse + 1];
            // Consistently oriented neighbours run their shared edge in opposite directions.
            edge.inconsistentOrientation = first.againstKey == second.againstKey;
            count.inconsistent += edge.inconsistentOrientation;
            const glm::dvec3 n1(adjacency.faceNormals[first.face]);
            const glm::dvec3 n2 =
                glm::dvec3(adjacency.faceNormals[second.face]) * (edge.inconsistentOrientation ? -1.0 : 1.0);
            edge.normalAngle = float(std::atan2(glm::length(glm::cross(n1, n2)), glm::dot(n1, n2)));
        }
    });
    for (const EdgeAdjacencyCounts& count : counts) {
        adjacency.counts.boundary += count.boundary;
        adjacency.counts.manifold += count.manifold;
        adjacency.counts.nonManifold += count.nonManifold;
        adjacency.counts.inconsistent += count.inconsistent;
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
    DisjointSets runs(count);
    for (std::size_t edgeEnd = 0; edgeEnd < 2 * count; ++edgeEnd)
        if (partner[edgeEnd] != kNone) runs.join(std::uint32_t(edgeEnd / 2), partner[edgeEnd] / 2);

    EdgeChains chains;
    chains.edges.assign(edges.begin(), edges.end());
    chains.chainOf.assign(count, kNone);
    std::vector<std::uint32_t> chainOfRoot(count, kNone);
    for (std::size_t slot = 0; slot < count; ++slot) {
        const std::uint32_t top = runs.find(std::uint32_t(slot));
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
