#include "scene/mesh/MeshIntersections.h"

#include "scene/mesh/ParallelRanges.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace inkgraph {
namespace {

using Triangle = std::array<glm::dvec3, 3>;

/** A signed distance below this share of its own rounding scale is zero: double's rounding of float inputs is
 *  about 1e-16 of it, so only points on the plane (to float's precision, 1e-7) fall under it. */
constexpr double kOnPlaneRelative = 1e-12;

/** Triangles per leaf of the hierarchy. */
constexpr std::uint32_t kLeafSize = 4;
/** The fewest triangles a thread of the search is started for. */
constexpr std::size_t kMinTrianglesPerThread = 4096;

/** Each of `points`' signed distance to `plane`'s plane (unnormalised: n = (p1 - p0) x (p2 - p0)), zero within
 *  rounding. */
std::array<double, 3> planeDistances(const Triangle& plane, const Triangle& points) {
    const glm::dvec3 normal = glm::cross(plane[1] - plane[0], plane[2] - plane[0]);
    const double normalScale = std::abs(normal.x) + std::abs(normal.y) + std::abs(normal.z);
    std::array<double, 3> distances{};
    for (int k = 0; k < 3; ++k) {
        const glm::dvec3 offset = points[k] - plane[0];
        const double distance = glm::dot(normal, offset);
        const double scale = normalScale * std::max({std::abs(offset.x), std::abs(offset.y), std::abs(offset.z)});
        distances[k] = std::abs(distance) <= kOnPlaneRelative * scale ? 0.0 : distance;
    }
    return distances;
}

bool strictlyOnBothSides(const std::array<double, 3>& d) {
    const bool above = d[0] > 0.0 || d[1] > 0.0 || d[2] > 0.0;
    const bool below = d[0] < 0.0 || d[1] < 0.0 || d[2] < 0.0;
    return above && below;
}

bool lexicographicallyLess(const glm::dvec3& a, const glm::dvec3& b) {
    if (a.x != b.x) return a.x < b.x;
    if (a.y != b.y) return a.y < b.y;
    return a.z < b.z;
}

/** Where `triangle` meets the other's plane, given its vertices' distances `d` to it (strictly on both sides): a
 *  vertex on the plane and one crossing edge, or two crossing edges. An edge's point is computed from its ends in one
 *  order whichever triangle holds it, so the two triangles beside an edge give bitwise the same point and the
 *  segments chain exactly. */
std::array<glm::dvec3, 2> planeCut(const Triangle& triangle, const std::array<double, 3>& d) {
    std::array<glm::dvec3, 2> cut{};
    std::size_t found = 0;
    for (int k = 0; k < 3 && found < 2; ++k) {
        if (d[k] == 0.0) {
            cut[found++] = triangle[k];
            continue;
        }
        const int next = (k + 1) % 3;
        if ((d[k] > 0.0 && d[next] < 0.0) || (d[k] < 0.0 && d[next] > 0.0)) {
            int from = k, to = next;
            if (lexicographicallyLess(triangle[to], triangle[from])) std::swap(from, to);
            cut[found++] = triangle[from] + (triangle[to] - triangle[from]) * (d[from] / (d[from] - d[to]));
        }
    }
    return cut;
}

/** A triangle's bounding box, in float: the positions are float, so it is exact. */
struct Box {
    glm::vec3 min{std::numeric_limits<float>::max()};
    glm::vec3 max{std::numeric_limits<float>::lowest()};
    void add(const Box& other) {
        min = glm::min(min, other.min);
        max = glm::max(max, other.max);
    }
    bool overlaps(const Box& other) const {
        // Inclusive: touching triangles are tested, and the plane test turns them away.
        return min.x <= other.max.x && other.min.x <= max.x && min.y <= other.max.y && other.min.y <= max.y &&
               min.z <= other.max.z && other.min.z <= max.z;
    }
};

/** A node of the hierarchy: a leaf (count > 0) over order[first, first + count), or an inner node whose children are
 *  the next node and node `first`. */
struct Node {
    Box box;
    std::uint32_t first = 0;
    std::uint32_t count = 0;
};

class Hierarchy {
public:
    explicit Hierarchy(const std::vector<Box>& boxes) : mBoxes(boxes), mOrder(boxes.size()) {
        for (std::uint32_t i = 0; i < mOrder.size(); ++i) mOrder[i] = i;
        if (!mOrder.empty()) {
            mNodes.reserve(2 * (mOrder.size() / kLeafSize + 1));
            build(0, std::uint32_t(mOrder.size()));
        }
    }

    std::size_t nodeCount() const { return mNodes.size(); }

    /** Calls visit(other) for every triangle other > `self` whose box overlaps self's. */
    template <class Visit>
    void forOverlapsAfter(std::uint32_t self, Visit&& visit) const {
        if (mNodes.empty()) return;
        const Box& box = mBoxes[self];
        std::uint32_t stack[64];
        int top = 0;
        stack[top++] = 0;
        while (top > 0) {
            const Node& node = mNodes[stack[--top]];
            if (!node.box.overlaps(box)) continue;
            if (node.count > 0) {
                for (std::uint32_t i = node.first; i < node.first + node.count; ++i) {
                    const std::uint32_t other = mOrder[i];
                    if (other > self && mBoxes[other].overlaps(box)) visit(other);
                }
                continue;
            }
            const auto index = std::uint32_t(&node - mNodes.data());
            stack[top++] = node.first; // the right child
            stack[top++] = index + 1;  // the left child, visited first
        }
    }

private:
    /** Median split along the longest axis of the centroids: depth log2(n / kLeafSize), under 64 for any mesh that
     *  fits in memory. */
    std::uint32_t build(std::uint32_t begin, std::uint32_t end) {
        const auto index = std::uint32_t(mNodes.size());
        mNodes.emplace_back();
        Box box, centres;
        for (std::uint32_t i = begin; i < end; ++i) {
            const Box& own = mBoxes[mOrder[i]];
            box.add(own);
            const glm::vec3 centre = 0.5f * (own.min + own.max);
            centres.add(Box{centre, centre});
        }
        if (end - begin <= kLeafSize) {
            mNodes[index] = Node{box, begin, end - begin};
            return index;
        }
        const glm::vec3 extent = centres.max - centres.min;
        const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
        const std::uint32_t middle = begin + (end - begin) / 2;
        // Ties broken by index, so the tree (and so nothing but speed) is the same on every standard library.
        std::nth_element(mOrder.begin() + begin, mOrder.begin() + middle, mOrder.begin() + end,
                         [&](std::uint32_t a, std::uint32_t b) {
                             const float ca = mBoxes[a].min[axis] + mBoxes[a].max[axis];
                             const float cb = mBoxes[b].min[axis] + mBoxes[b].max[axis];
                             return ca < cb || (ca == cb && a < b);
                         });
        build(begin, middle);
        const std::uint32_t right = build(middle, end);
        mNodes[index] = Node{box, right, 0};
        return index;
    }

    const std::vector<Box>& mBoxes;
    std::vector<std::uint32_t> mOrder;
    std::vector<Node> mNodes;
};

double millisecondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

} // namespace

std::optional<std::array<glm::dvec3, 2>> triangleIntersectionSegment(const std::array<glm::dvec3, 3>& a,
                                                                     const std::array<glm::dvec3, 3>& b) {
    // Moller 1997: reject unless each triangle straddles the other's plane, then overlap the two plane cuts along
    // the planes' common line.
    const std::array<double, 3> aToB = planeDistances(b, a);
    if (!strictlyOnBothSides(aToB)) return std::nullopt;
    const std::array<double, 3> bToA = planeDistances(a, b);
    if (!strictlyOnBothSides(bToA)) return std::nullopt;
    const std::array<glm::dvec3, 2> cutA = planeCut(a, aToB);
    const std::array<glm::dvec3, 2> cutB = planeCut(b, bToA);
    const glm::dvec3 direction = glm::cross(glm::cross(a[1] - a[0], a[2] - a[0]), glm::cross(b[1] - b[0], b[2] - b[0]));
    // Each cut as an interval along the common line: (parameter, point), sorted.
    auto interval = [&](const std::array<glm::dvec3, 2>& cut) {
        std::array<std::pair<double, glm::dvec3>, 2> ends{
            {{glm::dot(direction, cut[0]), cut[0]}, {glm::dot(direction, cut[1]), cut[1]}}};
        if (ends[1].first < ends[0].first) std::swap(ends[0], ends[1]);
        return ends;
    };
    const auto onA = interval(cutA), onB = interval(cutB);
    const auto& low = onA[0].first >= onB[0].first ? onA[0] : onB[0];
    const auto& high = onA[1].first <= onB[1].first ? onA[1] : onB[1];
    // Cuts that only meet (edges touching) or miss: no crossing.
    if (!(high.first > low.first)) return std::nullopt;
    return std::array<glm::dvec3, 2>{low.second, high.second};
}

MeshIntersections findMeshIntersections(std::span<const Mesh> meshes, std::span<const WeldMap* const> welds) {
    if (welds.size() != meshes.size())
        throw std::invalid_argument("findMeshIntersections(): " + std::to_string(welds.size()) + " welds for " +
                                    std::to_string(meshes.size()) + " meshes");
    for (std::size_t mesh = 0; mesh < meshes.size(); ++mesh)
        if (welds[mesh] == nullptr || welds[mesh]->outputOf.size() != meshes[mesh].positions.size())
            throw std::invalid_argument("findMeshIntersections(): the weld of mesh '" + meshes[mesh].name +
                                        "' does not map its " + std::to_string(meshes[mesh].positions.size()) +
                                        " positions");

    MeshIntersections result;
    IntersectionReport& report = result.report;
    const auto indexStart = std::chrono::steady_clock::now();
    // Every triangle of every mesh, numbered in mesh order: (mesh, triangle) of number g is found by the offsets.
    std::vector<std::uint32_t> firstOf(meshes.size() + 1, 0);
    for (std::size_t mesh = 0; mesh < meshes.size(); ++mesh) {
        const std::size_t total = std::size_t(firstOf[mesh]) + meshes[mesh].triangles.size();
        if (total >= std::numeric_limits<std::uint32_t>::max())
            throw std::invalid_argument("findMeshIntersections(): more than 2^32 - 1 triangles");
        firstOf[mesh + 1] = std::uint32_t(total);
    }
    const std::size_t count = firstOf.back();
    std::vector<std::uint32_t> meshOf(count);
    std::vector<Box> boxes(count);
    for (std::size_t mesh = 0; mesh < meshes.size(); ++mesh) {
        const Mesh& source = meshes[mesh];
        for (std::size_t t = 0; t < source.triangles.size(); ++t) {
            const glm::uvec3& triangle = source.triangles[t];
            Box& box = boxes[firstOf[mesh] + t];
            for (int k = 0; k < 3; ++k) box.add(Box{source.positions[triangle[k]], source.positions[triangle[k]]});
            meshOf[firstOf[mesh] + t] = std::uint32_t(mesh);
        }
    }
    const Hierarchy hierarchy(boxes);
    report.triangles = count;
    report.indexNodes = hierarchy.nodeCount();
    report.indexMilliseconds = millisecondsSince(indexStart);

    const auto searchStart = std::chrono::steady_clock::now();
    struct Chunk {
        std::vector<IntersectionSegment> segments;
        std::size_t boxPairs = 0, sharedVertexPairs = 0, pairsTested = 0;
    };
    std::vector<Chunk> chunks(parallelChunkCount(count, kMinTrianglesPerThread));
    auto corners = [&](std::uint32_t mesh, std::uint32_t triangle) {
        const Mesh& source = meshes[mesh];
        const glm::uvec3& indices = source.triangles[triangle];
        return Triangle{glm::dvec3(source.positions[indices.x]), glm::dvec3(source.positions[indices.y]),
                        glm::dvec3(source.positions[indices.z])};
    };
    parallelRanges(count, kMinTrianglesPerThread, [&](std::size_t chunkIndex, std::size_t begin, std::size_t end) {
        Chunk& chunk = chunks[chunkIndex];
        for (std::size_t g = begin; g < end; ++g) {
            const auto self = std::uint32_t(g);
            const std::uint32_t mesh = meshOf[self];
            const std::uint32_t triangle = self - firstOf[mesh];
            const glm::uvec3& own = meshes[mesh].triangles[triangle];
            const std::vector<std::uint32_t>& welded = welds[mesh]->outputOf;
            const std::uint32_t ownWelded[3] = {welded[own.x], welded[own.y], welded[own.z]};
            std::optional<Triangle> ownCorners;
            hierarchy.forOverlapsAfter(self, [&](std::uint32_t other) {
                ++chunk.boxPairs;
                const std::uint32_t otherMesh = meshOf[other];
                const std::uint32_t otherTriangle = other - firstOf[otherMesh];
                if (otherMesh == mesh) {
                    const glm::uvec3& indices = meshes[mesh].triangles[otherTriangle];
                    for (int k = 0; k < 3; ++k) {
                        const std::uint32_t vertex = welded[indices[k]];
                        if (vertex == ownWelded[0] || vertex == ownWelded[1] || vertex == ownWelded[2]) {
                            ++chunk.sharedVertexPairs;
                            return;
                        }
                    }
                }
                ++chunk.pairsTested;
                if (!ownCorners) ownCorners = corners(mesh, triangle);
                const auto segment = triangleIntersectionSegment(*ownCorners, corners(otherMesh, otherTriangle));
                if (segment) chunk.segments.push_back({*segment, {mesh, otherMesh}, {triangle, otherTriangle}});
            });
        }
    });
    for (Chunk& chunk : chunks) {
        report.boxPairs += chunk.boxPairs;
        report.sharedVertexPairs += chunk.sharedVertexPairs;
        report.pairsTested += chunk.pairsTested;
        result.segments.insert(result.segments.end(), chunk.segments.begin(), chunk.segments.end());
    }
    report.segments = result.segments.size();
    report.selfSegments =
        std::size_t(std::count_if(result.segments.begin(), result.segments.end(),
                                  [](const IntersectionSegment& s) { return s.meshes[0] == s.meshes[1]; }));
    report.searchMilliseconds = millisecondsSince(searchStart);
    return result;
}

MeshIntersections findMeshIntersections(std::span<const Mesh> meshes, double weldDistance) {
    std::vector<WeldMap> welds;
    welds.reserve(meshes.size());
    for (const Mesh& mesh : meshes) welds.push_back(weldMeshPositions(mesh, weldDistance));
    std::vector<const WeldMap*> pointers;
    for (const WeldMap& weld : welds) pointers.push_back(&weld);
    return findMeshIntersections(meshes, pointers);
}

} // namespace inkgraph
