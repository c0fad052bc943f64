#include "scene/mesh/BackToBackSheets.h"

#include "scene/mesh/MeshOps.h"

#include <algorithm>
#include <cstdint>
#include <tuple>
#include <unordered_map>
#include <utility>

namespace inkgraph {
namespace {

/** Whether the first triangle of some two-sided mesh may lie back to back with another triangle: one whose centroid is
 *  within twice `weldDistance` of it on every axis, as a twin's is (the weld joins each vertex to a first one within
 *  its reach, so two corners it merges are at most twice that apart). A mesh is culled only when all its triangles
 *  are covered, its first among them, so when none may be, nothing is; this pass over the centroids costs a fraction
 *  of the weld the full search needs. Errs towards yes. */
bool someFirstTriangleMayHaveATwin(const std::vector<Mesh>& meshes, double weldDistance) {
    if (!(weldDistance > 0.0)) return true;
    const double reachOfTwin = 2.0 * weldDistance;
    const double cell = 2.0 * reachOfTwin; // a probe's cells reach half a cell around it
    const auto centroidOf = [](const Mesh& mesh, const glm::uvec3& triangle) {
        return (glm::dvec3(mesh.positions[triangle.x]) + glm::dvec3(mesh.positions[triangle.y]) +
                glm::dvec3(mesh.positions[triangle.z])) /
               3.0;
    };
    struct Probe {
        glm::dvec3 centroid;
        std::size_t mesh;
    };
    std::vector<Probe> probes;
    BoundingBox reach;
    for (std::size_t m = 0; m < meshes.size(); ++m) {
        if (!meshes[m].material.doubleSided || meshes[m].triangles.empty()) continue;
        probes.push_back({centroidOf(meshes[m], meshes[m].triangles.front()), m});
        reach.add(probes.back().centroid - glm::dvec3(reachOfTwin));
        reach.add(probes.back().centroid + glm::dvec3(reachOfTwin));
    }
    if (probes.empty()) return false;
    // Each probe in the cells within half a cell of it (one or two per axis): a centroid within the weld of it lies in
    // one of them.
    std::unordered_multimap<std::uint64_t, std::size_t> cells;
    // The cell of a point, its index held to 2^52 (a weld tiny beside the model's size): cells that then share an
    // index, or a key, only make more candidates, each judged on its distance.
    const auto cellOf = [&](glm::dvec3 point) {
        constexpr double kLargestIndex = 4503599627370496.0;
        return glm::i64vec3(glm::clamp(glm::floor(point / cell), -kLargestIndex, kLargestIndex));
    };
    const auto keyOfCell = [](glm::i64vec3 index) {
        return std::uint64_t(index.x) * 73856093u ^ std::uint64_t(index.y) * 19349663u ^
               std::uint64_t(index.z) * 83492791u;
    };
    for (std::size_t p = 0; p < probes.size(); ++p) {
        const glm::i64vec3 low = cellOf(probes[p].centroid - 0.5 * cell);
        const glm::i64vec3 high = cellOf(probes[p].centroid + 0.5 * cell);
        for (std::int64_t x = low.x; x <= high.x; ++x)
            for (std::int64_t y = low.y; y <= high.y; ++y)
                for (std::int64_t z = low.z; z <= high.z; ++z) cells.emplace(keyOfCell(glm::i64vec3(x, y, z)), p);
    }
    for (std::size_t m = 0; m < meshes.size(); ++m) {
        for (std::size_t t = 0; t < meshes[m].triangles.size(); ++t) {
            const glm::dvec3 centroid = centroidOf(meshes[m], meshes[m].triangles[t]);
            if (glm::any(glm::lessThan(centroid, reach.min)) || glm::any(glm::greaterThan(centroid, reach.max)))
                continue;
            const auto [begin, end] = cells.equal_range(keyOfCell(cellOf(centroid)));
            for (auto found = begin; found != end; ++found) {
                const Probe& probe = probes[found->second];
                if ((probe.mesh != m || t != 0) &&
                    glm::all(glm::lessThanEqual(glm::abs(centroid - probe.centroid), glm::dvec3(reachOfTwin))))
                    return true;
            }
        }
    }
    return false;
}

} // namespace

std::size_t cullBackToBackSheets(std::vector<Mesh>& meshes, double weldDistance) {
    if (std::none_of(meshes.begin(), meshes.end(), [](const Mesh& mesh) { return mesh.material.doubleSided; }))
        return 0;
    // A lone mesh of positions and normals had its twins matched on positions when it was finalized, and dropped.
    if (meshes.size() == 1 && meshes[0].texcoords[0].empty() && meshes[0].texcoords[1].empty() &&
        meshes[0].colors.empty())
        return 0;
    if (!someFirstTriangleMayHaveATwin(meshes, weldDistance)) return 0;

    std::vector<std::size_t> firstVertex{0};
    std::vector<std::size_t> meshOfTriangle;
    for (std::size_t m = 0; m < meshes.size(); ++m) {
        firstVertex.push_back(firstVertex.back() + meshes[m].positions.size());
        meshOfTriangle.insert(meshOfTriangle.end(), meshes[m].triangles.size(), m);
    }
    std::vector<glm::vec3> positions;
    positions.reserve(firstVertex.back());
    for (const Mesh& mesh : meshes) positions.insert(positions.end(), mesh.positions.begin(), mesh.positions.end());
    const WeldMap weld = weldVertices(positions, {}, weldDistance);
    positions = {};
    // Each triangle as its welded corners in ascending order, with the parity of that order (sortedCorners()).
    struct Placed {
        glm::uvec3 corners;
        std::uint32_t triangle;
        bool odd;
    };
    std::vector<Placed> placed;
    placed.reserve(meshOfTriangle.size());
    for (std::size_t m = 0; m < meshes.size(); ++m) {
        const std::size_t base = firstVertex[m];
        for (const glm::uvec3& triangle : meshes[m].triangles) {
            const SortedCorners corners = sortedCorners(glm::uvec3(
                weld.outputOf[base + triangle.x], weld.outputOf[base + triangle.y], weld.outputOf[base + triangle.z]));
            placed.push_back({corners.sorted, std::uint32_t(placed.size()), corners.odd});
        }
    }
    const auto cornersBefore = [](const Placed& a, const Placed& b) {
        return std::tie(a.corners.x, a.corners.y, a.corners.z) < std::tie(b.corners.x, b.corners.y, b.corners.z);
    };
    std::sort(placed.begin(), placed.end(), cornersBefore);
    // A triangle's back is covered when some opaque triangle on its corners faces the other way: a blended one lets
    // the back behind it show, an alpha-masked one its holes, which need not be the back's own.
    std::vector<bool> covered(placed.size(), false);
    bool any = false;
    for (std::size_t runStart = 0; runStart < placed.size();) {
        std::size_t runEnd = runStart + 1;
        while (runEnd < placed.size() && placed[runEnd].corners == placed[runStart].corners) ++runEnd;
        if (runEnd - runStart > 1) {
            bool opaque[2] = {false, false}; // an opaque triangle of each facing in the run
            for (std::size_t i = runStart; i < runEnd; ++i)
                if (meshes[meshOfTriangle[placed[i].triangle]].material.alphaMode == AlphaMode::Opaque)
                    opaque[placed[i].odd ? 1 : 0] = true;
            for (std::size_t i = runStart; i < runEnd; ++i) {
                const bool backCovered = opaque[placed[i].odd ? 0 : 1];
                covered[placed[i].triangle] = backCovered;
                any = any || backCovered;
            }
        }
        runStart = runEnd;
    }
    if (!any) return 0;

    std::size_t culled = 0;
    std::size_t base = 0;
    for (Mesh& mesh : meshes) {
        const auto begin = covered.begin() + std::ptrdiff_t(base);
        base += mesh.triangles.size();
        if (!mesh.material.doubleSided ||
            !std::all_of(begin, begin + std::ptrdiff_t(mesh.triangles.size()), [](bool back) { return back; }))
            continue;
        mesh.backCulled = true;
        culled += mesh.triangles.size();
    }
    return culled;
}

} // namespace inkgraph
