// CPU cost of Winnemöller & Bangay's face-orientation methods (marking plus per-vertex lighting, as orientMesh() runs
// them) on UV spheres of about 1k to 1M triangles: rule 3, constant view vector, eye at 5 radii. The exact per-face
// count is there as the reference for one triangle pass. Derived data (face normals, betaMax, adjacency) is built once
// per size outside the timing, as the paper does at load time; holes are not counted in the timed loop. `reuse:1`
// passes the same MeshOrientation every iteration, so its lists are allocated once, as in an interactive renderer.
#include "scene/mesh/FaceOrientation.h"
#include "scene/mesh/Procedural.h"

#include <benchmark/benchmark.h>

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>

namespace inkgraph {
namespace {

/** One sphere with its derived data, shared by every case of the same size. */
struct OrientationInput {
    Mesh mesh;
    OrientationMeshData data;
    glm::dvec3 eye{0.0};
    ViewVectorChoice view;
};

/** A unit sphere of about `triangleCount` triangles (2 x segments x (rings - 1), segments = 2 x rings), built once. */
const OrientationInput& sphereInput(int triangleCount) {
    static std::map<int, std::unique_ptr<OrientationInput>> cache;
    std::unique_ptr<OrientationInput>& slot = cache[triangleCount];
    if (!slot) {
        const int rings = std::max(3, int(std::sqrt(triangleCount / 4.0)));
        slot = std::make_unique<OrientationInput>();
        slot->mesh = makeUvSphere({0.0f, 0.0f, 0.0f}, 1.0f, 2 * rings, rings);
        slot->data = deriveOrientationData(slot->mesh, true);
        // Off the axes, so no symmetry of the UV grid flatters a method.
        slot->eye = 5.0 * glm::normalize(glm::dvec3(1.0, 0.5, 0.8));
        slot->view = chooseViewVector(ViewVectorMode::Constant, slot->eye, glm::dvec3(0.0), 1.0);
    }
    return *slot;
}

void orientSphere(benchmark::State& state, FaceOrientationMethod method) {
    const OrientationInput& input = sphereInput(int(state.range(0)));
    OrientationRequest request;
    request.method = method;
    request.frontRule = 3;
    request.view = input.view;
    request.eye = input.eye;
    request.towardLight = glm::normalize(glm::dvec3(0.3, 0.5, 0.8));
    request.shininess = 32.0;
    request.countMissed = false;
    const bool reuse = state.range(1) != 0;
    MeshOrientation reused;
    std::size_t frontTriangles = 0;
    for (auto _ : state) {
        if (reuse) {
            orientMesh(input.mesh, input.data, request, reused);
            frontTriangles = reused.frontTriangles.size();
            benchmark::DoNotOptimize(reused.shadeCoords.data());
        } else {
            const MeshOrientation result = orientMesh(input.mesh, input.data, request);
            frontTriangles = result.frontTriangles.size();
            benchmark::DoNotOptimize(result.shadeCoords.data());
        }
    }
    const double triangles = double(input.mesh.triangleCount());
    state.counters["triangles"] = triangles;
    state.counters["frontShare"] = double(frontTriangles) / triangles;
    state.counters["Mtri/s"] =
        benchmark::Counter(triangles * double(state.iterations()) / 1e6, benchmark::Counter::kIsRate);
}

void BM_OrientDuringTriangles(benchmark::State& state) { orientSphere(state, FaceOrientationMethod::DuringTriangles); }
void BM_OrientDuringVertices(benchmark::State& state) { orientSphere(state, FaceOrientationMethod::DuringVertices); }
void BM_OrientAfterVertices(benchmark::State& state) { orientSphere(state, FaceOrientationMethod::AfterVertices); }

void BM_OrientExactFrontCount(benchmark::State& state) {
    const OrientationInput& input = sphereInput(int(state.range(0)));
    std::size_t frontTriangles = 0;
    for (auto _ : state) {
        frontTriangles = countExactFrontTriangles(input.mesh, input.eye);
        benchmark::DoNotOptimize(frontTriangles);
    }
    const double triangles = double(input.mesh.triangleCount());
    state.counters["triangles"] = triangles;
    state.counters["frontShare"] = double(frontTriangles) / triangles;
    state.counters["Mtri/s"] =
        benchmark::Counter(triangles * double(state.iterations()) / 1e6, benchmark::Counter::kIsRate);
}

void BM_DeriveOrientationData(benchmark::State& state) {
    const OrientationInput& input = sphereInput(int(state.range(0)));
    for (auto _ : state) {
        benchmark::DoNotOptimize(deriveOrientationData(input.mesh, true).betaMaxRadians);
    }
    state.counters["triangles"] = double(input.mesh.triangleCount());
}

constexpr int kSphereSizes[] = {1000, 10000, 100000, 1000000};

/** 1k to 1M triangles; a short minimum time keeps the 1M cases to a handful of iterations. */
void sphereSizes(benchmark::internal::Benchmark* bench) {
    for (const int size : kSphereSizes) bench->Arg(size);
    bench->ArgName("triangles")->Unit(benchmark::kMillisecond)->MinTime(0.2);
}

/** Each size with a fresh result per call (a still: one call per process, page faults included) and with a reused
 *  one (a renderer orienting every frame). */
void sphereSizesFreshAndReused(benchmark::internal::Benchmark* bench) {
    for (const int size : kSphereSizes) {
        bench->Args({size, 0})->Args({size, 1});
    }
    bench->ArgNames({"triangles", "reuse"})->Unit(benchmark::kMillisecond)->MinTime(0.2);
}

BENCHMARK(BM_OrientDuringTriangles)->Apply(sphereSizesFreshAndReused);
BENCHMARK(BM_OrientDuringVertices)->Apply(sphereSizesFreshAndReused);
BENCHMARK(BM_OrientAfterVertices)->Apply(sphereSizesFreshAndReused);
BENCHMARK(BM_OrientExactFrontCount)->Apply(sphereSizes);
BENCHMARK(BM_DeriveOrientationData)->Apply(sphereSizes);

} // namespace
} // namespace inkgraph
