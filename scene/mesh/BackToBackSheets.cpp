#include "scene/mesh/BackToBackSheets.h"

#include "scene/mesh/MeshOps.h"

#include <algorithm>
#include <cstdint>
#include <unordered_map>

namespace inkgraph {
namespace {

/** Whether the first triangle of some two-sided mesh may lie back to back with another triangle: one whose centroid is
 *  within twice `weldDistance` of it on every axis, as a twin's is (the weld joins each vertex to a first one within
 *  its reach, so two corners it merges are at most twice that apart). A mesh
 *  is culled only when all its triangles are covered, its first among them, so when none may be, nothing is; this
 *  pass over the centroids costs a fraction of the weld the full search needs. Errs towards yes. */
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
    // Cells that share a key only make more candidates, each judged on its distance.
    const auto keyOfCell = [](glm::dvec3 cellIndex) {
        const glm::i64vec3 index(cellIndex);
        return std::uint64_t(index.x) * 73856093u ^ std::uint64_t(index.y) * 19349663u ^
               std::uint64_t(index.z) * 83492791u;
    };
    for (std::size_t p = 0; p < probes.size(); ++p) {
        const glm::dvec3 low = glm::floor((probes[p].centroid - 0.5 * cell) / cell);
        const glm::dvec3 high = glm::floor((probes[p].centroid + 0.5 * cell) / cell);
        for (double x = low.x; x <= high.x; ++x)
            for (double y = low.y; y <= high.y; ++y)
                for (double z = low.z; z <= high.z; ++z) cells.emplace(keyOfCell(glm::dvec3(x, y, z)), p);
    }
    for (std::size_t m = 0; m < meshes.size(); ++m) {
        for (std::size_t t = 0; t < meshes[m].triangles.size(); ++t) {
            const glm::dvec3 centroid = centroidOf(meshes[m], meshes[m].triangles[t]);
            if (glm::any(glm::lessThan(centroid, reach.min)) || glm::any(glm::greaterThan(centroid, reach.max)))
                continue;
            const auto [begin, end] = cells.equal_range(keyOfCell(glm::floor(centroid / cell)));
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
    std::vector<glm::uvec3> welded;
    welded.reserve(meshOfTriangle.size());
    for (std::size_t m = 0; m < meshes.size(); ++m) {
        const std::size_t base = firstVertex[m];
        for (const glm::uvec3& triangle : meshes[m].triangles)
            welded.emplace_back(weld.outputOf[base + triangle.x], weld.outputOf[base + triangle.y],
                                weld.outputOf[base + triangle.z]);
    }
    const auto pairs = backToBackPairs(welded);
    if (pairs.empty()) return 0;
    std::vector<bool> covered(welded.size(), false);
    const auto covers = [&](std::size_t t) { return meshes[meshOfTriangle[t]].material.alphaMode != AlphaMode::Blend; };
    for (const auto& [first, second] : pairs) {
        if (covers(second)) covered[first] = true;
        if (covers(first)) covered[second] = true;
    }

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
