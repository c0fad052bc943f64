// The intersection line type's search (scene/mesh/MeshIntersections.h, issue 36) on about a million triangles, no GL:
// two interpenetrating UV spheres of 499,848 triangles each (closed meshes: almost every candidate pair is a pair of
// neighbours, skipped for sharing a vertex; one circle of crossings), and one mesh of 250,000 crossing quad pairs
// (1,000,000 triangles: hair cards, every card crossed by another). The position welds are made once, outside the
// timing, as GpuScene shares them with the other derived data. Counters: the search's own (segments, pairs tested),
// and its index build and query times of the last run.
//
//     ./build/bench/inkgraph_bench --benchmark_filter=Intersection
#include "scene/mesh/MeshIntersections.h"
#include "scene/mesh/MeshOps.h"
#include "scene/mesh/Procedural.h"

#include <benchmark/benchmark.h>

#include <vector>

namespace inkgraph {
namespace {

/** 250,000 cells of a 500 x 500 grid, each an X of two quads (in the planes x = cx and y = cy, 0.8 cells wide, 0.8
 *  high) crossing on the cell's vertical axis; every quad its own four vertices, all in one mesh. */
Mesh crossingCards() {
    constexpr int kSide = 500;
    Mesh mesh;
    mesh.name = "cards";
    auto addQuad = [&](glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d) {
        const auto first = std::uint32_t(mesh.positions.size());
        for (const glm::vec3& corner : {a, b, c, d}) {
            mesh.positions.push_back(corner);
            mesh.normals.push_back({0.0f, 0.0f, 1.0f});
        }
        mesh.triangles.push_back({first, first + 1, first + 2});
        mesh.triangles.push_back({first, first + 2, first + 3});
    };
    for (int i = 0; i < kSide; ++i)
        for (int j = 0; j < kSide; ++j) {
            const float x = float(i), y = float(j), h = 0.4f;
            addQuad({x, y - h, -h}, {x, y + h, -h}, {x, y + h, h}, {x, y - h, h});
            addQuad({x - h, y, -h}, {x + h, y, -h}, {x + h, y, h}, {x - h, y, h});
        }
    return mesh;
}

void runSearch(benchmark::State& state, const std::vector<Mesh>& meshes) {
    std::vector<WeldMap> welds;
    std::vector<const WeldMap*> pointers;
    for (const Mesh& mesh : meshes)
        welds.push_back(
            weldMeshPositions(mesh, LoadOptions{}.weldTolerance * computeBoundingBox(mesh.positions).diagonal()));
    for (const WeldMap& weld : welds) pointers.push_back(&weld);
    IntersectionReport report;
    for (auto _ : state) {
        const MeshIntersections found = findMeshIntersections(meshes, pointers);
        report = found.report;
        benchmark::DoNotOptimize(found.segments.data());
    }
    state.counters["triangles"] = double(report.triangles);
    state.counters["segments"] = double(report.segments);
    state.counters["box_pairs"] = double(report.boxPairs);
    state.counters["pairs_tested"] = double(report.pairsTested);
    state.counters["index_ms"] = report.indexMilliseconds;
    state.counters["search_ms"] = report.searchMilliseconds;
}

void BM_IntersectionSpheres(benchmark::State& state) {
    static const std::vector<Mesh> meshes = {makeUvSphere({0.45f, 0.0f, 0.0f}, 0.8f, 708, 354),
                                             makeUvSphere({-0.45f, 0.0f, 0.0f}, 0.8f, 708, 354)};
    runSearch(state, meshes);
}
BENCHMARK(BM_IntersectionSpheres)->Unit(benchmark::kMillisecond)->UseRealTime()->Repetitions(5);

void BM_IntersectionCards(benchmark::State& state) {
    static const std::vector<Mesh> meshes = {crossingCards()};
    runSearch(state, meshes);
}
BENCHMARK(BM_IntersectionCards)->Unit(benchmark::kMillisecond)->UseRealTime()->Repetitions(5);

} // namespace
} // namespace inkgraph
