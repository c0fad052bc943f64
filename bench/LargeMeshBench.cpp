// The CPU work a large model costs before any pixel is drawn (issue 20): loading a 1.3M-triangle OBJ, welding,
// smooth and hull normals, edge adjacency and curvature, each alone, on the armadillo subdivided 5 x 5 (1,300,000
// triangles, 650,002 vertices: what `inkgraph_make_mesh subdivide 5` writes). The OBJ is written once per machine
// to the temporary folder and reused. Only scene/ functions whose signatures predate the work are timed, so the same
// file measures a build before a change and one after.
//
//     ./build/bench/inkgraph_bench --benchmark_filter=Large
#include "bench/LargeMesh.h"
#include "scene/mesh/BackToBackSheets.h"
#include "scene/mesh/EdgeAdjacency.h"
#include "scene/mesh/MeshCurvature.h"
#include "scene/mesh/MeshOps.h"
#include "scene/Scene.h"

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace inkgraph {
namespace {

const std::string kArmadilloPath = std::string(INKGRAPH_SOURCE_ROOT) + "/models/armadillo_cgal_52k.obj";
constexpr int kSubdivision = 5;

/** The subdivided armadillo's OBJ, written on first use (a few seconds) unless a previous run left it. */
const std::string& largeObjPath() {
    static const std::string path = [] {
        const std::string file =
            (std::filesystem::temp_directory_path() / "inkgraph-bench-armadillo-1.3m.obj").string();
        if (!std::filesystem::exists(file)) {
            std::vector<Mesh> meshes;
            for (const Mesh& mesh : loadScene(kArmadilloPath).meshes)
                meshes.push_back(bench::subdivided(mesh, kSubdivision));
            const std::string partial = file + ".partial";
            if (!bench::writeObj(meshes, partial))
                throw std::runtime_error("largeObjPath(): cannot write '" + partial + "'");
            std::filesystem::rename(partial, file);
        }
        return file;
    }();
    return path;
}

/** The loaded model (one mesh), as the renderer holds it. */
const Mesh& largeMesh() {
    static const Scene scene = loadScene(largeObjPath());
    return scene.meshes.front();
}

/** The weld distance GpuScene derives with: the loader's default tolerance times the model's diagonal. */
double derivedWeldDistance(const Mesh& mesh) {
    return LoadOptions{}.weldTolerance * computeBoundingBox(mesh.positions).diagonal();
}

/** Every triangle with its own three vertices, as an STL file gives them: the weld has 6 copies of each point to
 *  merge. */
const std::vector<glm::vec3>& largeSoup() {
    static const std::vector<glm::vec3> soup = [] {
        const Mesh& mesh = largeMesh();
        std::vector<glm::vec3> positions;
        positions.reserve(mesh.triangles.size() * 3);
        for (const glm::uvec3& t : mesh.triangles)
            for (int corner = 0; corner < 3; ++corner) positions.push_back(mesh.positions[t[corner]]);
        return positions;
    }();
    return soup;
}

void setTriangleCounters(benchmark::State& state, std::size_t triangles) {
    state.counters["triangles"] = double(triangles);
    state.counters["Mtri/s"] =
        benchmark::Counter(double(triangles) * 1e-6, benchmark::Counter::kIsIterationInvariantRate);
}

/** Loads `path` once per iteration. */
void timeLoading(benchmark::State& state, const std::string& path) {
    std::size_t triangles = 0;
    for (auto _ : state) {
        const Scene scene = loadScene(path);
        triangles = scene.triangleCount();
        benchmark::DoNotOptimize(scene.meshes.data());
    }
    setTriangleCounters(state, triangles);
}

void BM_LargeLoadObj(benchmark::State& state) { timeLoading(state, largeObjPath()); }
BENCHMARK(BM_LargeLoadObj)->Unit(benchmark::kMillisecond)->UseRealTime();

/** A file of polygons written once per machine to the temporary folder: `quads`, a warped height field of 806 x 806
 *  quads (1,299,272 triangles, like the armadillo's), every quad convex, as subdivision modellers export; or 20,000
 *  concave polygons of 83 corners each (1,620,000 triangles): combs of 40 teeth, the shape of a text's glyphs. */
const std::string& polygonObjPath(bool quads) {
    static std::string paths[2];
    std::string& path = paths[quads ? 1 : 0];
    if (path.empty()) {
        const std::string file = (std::filesystem::temp_directory_path() /
                                  (quads ? "inkgraph-bench-quads-1.3m.obj" : "inkgraph-bench-combs-20k.obj"))
                                     .string();
        if (!std::filesystem::exists(file)) {
            const std::string partial = file + ".partial";
            std::FILE* out = std::fopen(partial.c_str(), "w");
            if (out == nullptr) throw std::runtime_error("polygonObjPath(): cannot write '" + partial + "'");
            if (quads) {
                constexpr int kSide = 806;
                for (int y = 0; y <= kSide; ++y)
                    for (int x = 0; x <= kSide; ++x)
                        std::fprintf(out, "v %.7g %.7g %.7g\n", x / double(kSide), y / double(kSide),
                                     0.05 * std::sin(x * 0.05) * std::cos(y * 0.07));
                for (int y = 0; y < kSide; ++y)
                    for (int x = 0; x < kSide; ++x) {
                        const int corner = y * (kSide + 1) + x + 1;
                        std::fprintf(out, "f %d %d %d %d\n", corner, corner + 1, corner + kSide + 2,
                                     corner + kSide + 1);
                    }
            } else {
                // Counter-clockwise: the bottom edge, then up the right side and along the teeth right to left.
                constexpr int kTeeth = 40;
                constexpr int kCorners = 2 * kTeeth + 3;
                for (int comb = 0; comb < 20000; ++comb) {
                    const double left = comb % 200 * (kTeeth + 1.0), bottom = comb / 200 * 4.0;
                    std::fprintf(out, "v %.7g %.7g 0\nv %.7g %.7g 0\nv %.7g %.7g 0\n", left, bottom, left + kTeeth,
                                 bottom, left + kTeeth, bottom + 1.0);
                    for (int tooth = kTeeth - 1; tooth >= 0; --tooth)
                        std::fprintf(out, "v %.7g %.7g 0\nv %.7g %.7g 0\n", left + tooth + 0.5, bottom + 3.0,
                                     left + tooth, bottom + 1.0);
                    std::fprintf(out, "f");
                    for (int corner = kCorners; corner >= 1; --corner) std::fprintf(out, " -%d", corner);
                    std::fprintf(out, "\n");
                }
            }
            if (std::fclose(out) != 0) throw std::runtime_error("polygonObjPath(): cannot write '" + partial + "'");
            std::filesystem::rename(partial, file);
        }
        path = file;
    }
    return path;
}

/** Arg 1: the quads; 0: the concave combs. */
void BM_LoadObjPolygons(benchmark::State& state) { timeLoading(state, polygonObjPath(state.range(0) == 1)); }
BENCHMARK(BM_LoadObjPolygons)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();

/** 0: the loaded mesh by position alone, as every derived datum welds it (nothing merges); 1: the soup (every point
 *  merges with its copies). */
void BM_LargeWeld(benchmark::State& state) {
    const Mesh& mesh = largeMesh();
    const std::vector<glm::vec3>& positions = state.range(0) == 0 ? mesh.positions : largeSoup();
    const double distance = derivedWeldDistance(mesh);
    std::size_t kept = 0;
    for (auto _ : state) {
        const WeldMap map = weldVertices(positions, {}, distance);
        kept = map.kept.size();
        benchmark::DoNotOptimize(map.outputOf.data());
    }
    state.counters["vertices"] = double(positions.size());
    state.counters["kept"] = double(kept);
}
BENCHMARK(BM_LargeWeld)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_LargeSmoothNormals(benchmark::State& state) {
    const Mesh& mesh = largeMesh();
    for (auto _ : state) benchmark::DoNotOptimize(computeSmoothNormals(mesh.positions, mesh.triangles).data());
    setTriangleCounters(state, mesh.triangles.size());
}
BENCHMARK(BM_LargeSmoothNormals)->Unit(benchmark::kMillisecond)->UseRealTime();

/** The back-to-back twin search finalizeMesh() runs on every two-sided mesh (none to find here): its share of a load
 *  is this over BM_LargeLoadObj. */
void BM_LargeBackToBackTwins(benchmark::State& state) {
    const Mesh& mesh = largeMesh();
    std::size_t twins = 0;
    for (auto _ : state) {
        const std::vector<std::uint32_t> found = backToBackTwins(mesh.triangles);
        twins = found.size();
        benchmark::DoNotOptimize(found.data());
    }
    setTriangleCounters(state, mesh.triangles.size());
    state.counters["twins"] = double(twins);
}
BENCHMARK(BM_LargeBackToBackTwins)->Unit(benchmark::kMillisecond)->UseRealTime();

/** The scene-wide search for sheets back to back with sides of their own (cullBackToBackSheets()), which every load
 *  of more than one mesh, or of a textured or coloured one, runs after finalizeMesh(): the armadillo with texture
 *  coordinates, alone (0: the pass over centroids finds no twin for its first triangle, and ends there) or with a
 *  second mesh holding that triangle's back sheet (1: the whole search, a weld of every vertex, which culls that
 *  sheet alone: the armadillo's other triangles are uncovered). Nothing changes between iterations. Its share of a
 *  load is this over BM_LargeLoadObj. */
void BM_LargeBackToBackSheets(benchmark::State& state) {
    static const std::vector<Mesh> alone = [] {
        Mesh mesh = largeMesh();
        mesh.texcoords[0].assign(mesh.positions.size(), glm::vec2(0.0f));
        return std::vector<Mesh>{std::move(mesh)};
    }();
    std::vector<Mesh> meshes = alone;
    if (state.range(0) == 1) {
        const Mesh& armadillo = alone.front();
        Mesh back;
        const glm::uvec3 first = armadillo.triangles.front();
        back.positions = {armadillo.positions[first.x], armadillo.positions[first.z], armadillo.positions[first.y]};
        back.normals.assign(3, glm::vec3(0.0f, 0.0f, 1.0f));
        back.triangles = {{0, 1, 2}};
        meshes.push_back(std::move(back));
    }
    const double distance = derivedWeldDistance(alone.front());
    std::size_t culled = 0;
    for (auto _ : state) culled = cullBackToBackSheets(meshes, distance);
    setTriangleCounters(state, alone.front().triangles.size());
    state.counters["culled"] = double(culled);
}
BENCHMARK(BM_LargeBackToBackSheets)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

/** The silhouette hull's normals, weld included. */
void BM_LargeHullNormals(benchmark::State& state) {
    const Mesh& mesh = largeMesh();
    const double distance = derivedWeldDistance(mesh);
    for (auto _ : state)
        benchmark::DoNotOptimize(computePositionWeldedNormals(mesh.positions, mesh.triangles, distance).data());
    setTriangleCounters(state, mesh.triangles.size());
}
BENCHMARK(BM_LargeHullNormals)->Unit(benchmark::kMillisecond)->UseRealTime();

/** The mesh-edges pass's adjacency, weld included. */
void BM_LargeEdgeAdjacency(benchmark::State& state) {
    const Mesh& mesh = largeMesh();
    const double distance = derivedWeldDistance(mesh);
    std::size_t edges = 0;
    for (auto _ : state) {
        const EdgeAdjacency adjacency = buildEdgeAdjacency(mesh.positions, mesh.triangles, distance);
        edges = adjacency.edges.size();
        benchmark::DoNotOptimize(adjacency.edges.data());
    }
    setTriangleCounters(state, mesh.triangles.size());
    state.counters["edges"] = double(edges);
}
BENCHMARK(BM_LargeEdgeAdjacency)->Unit(benchmark::kMillisecond)->UseRealTime();

/** The object-space suggestive contours' curvature, weld included, unsmoothed. */
void BM_LargeCurvature(benchmark::State& state) {
    const Mesh& mesh = largeMesh();
    const double distance = derivedWeldDistance(mesh);
    for (auto _ : state)
        benchmark::DoNotOptimize(computeMeshCurvature(mesh.positions, mesh.triangles, distance).normals.data());
    setTriangleCounters(state, mesh.triangles.size());
}
BENCHMARK(BM_LargeCurvature)->Unit(benchmark::kMillisecond)->UseRealTime();

} // namespace
} // namespace inkgraph
