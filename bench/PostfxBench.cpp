// The post stage alone (no GL): each line kernel, the stroke and the composite on a ray-cast torus G-buffer at
// 512x512, 1024x1024, 1920x1080 and 4096x4096 (the torus fills about 40% of the frame at every size), and the post
// stage of `--lines silhouette,contour,suggestive` (contour and suggestive kernels, their strokes, the composite of
// three layers) as one number. Suggestive contours unsmoothed (BM_PostfxSuggestive), with the app's default
// smoothing (BM_PostfxSuggestiveSmoothed, as `--lines suggestive` runs it; BM_PostfxSuggestiveSmoothedSurfaceIds the
// same with a surface id per pixel, as a scene of several smooth patches runs it), and the smoothing alone
// (BM_PostfxSmoothRadialField). The stroke stage of the three (BM_PostfxStrokes: thinning, chaining, the kept
// skeletons drawn). Counters: Mpixel/s of the frame, skeleton points (strokes for BM_PostfxStrokes).
//   ./build/bench/inkgraph_bench --benchmark_filter=Postfx
#include "postfx/Composite.h"
#include "postfx/Contour.h"
#include "postfx/ImageEdges.h"
#include "postfx/LineSkeleton.h"
#include "postfx/LineTracing.h"
#include "postfx/Strokes.h"
#include "postfx/SuggestiveContours.h"
#include "tests/support/SyntheticGBuffer.h"

#include <benchmark/benchmark.h>

#include <map>
#include <utility>

namespace inkgraph::bench {
namespace {

/** The torus's bounding radius: ring 1 + tube 0.4. */
constexpr double kTorusRadius = 1.4;

/** The camera of torusAt(): 30 degrees above the torus's plane. */
test::SyntheticCamera torusCamera(int width, int height) {
    test::SyntheticCamera camera;
    camera.width = width;
    camera.height = height;
    camera.eye = 4.2 * glm::dvec3(std::cos(glm::radians(30.0)), 0.0, std::sin(glm::radians(30.0)));
    camera.up = {0.0, 0.0, 1.0};
    return camera;
}

/** A torus (ring 1, tube 0.4) seen from 30 degrees above, ray cast once per size and kept. */
const test::SyntheticGBuffer& torusAt(int width, int height) {
    static std::map<std::pair<int, int>, test::SyntheticGBuffer> buffers;
    auto found = buffers.find({width, height});
    if (found != buffers.end()) return found->second;
    return buffers
        .emplace(std::make_pair(width, height),
                 test::renderTorus(torusCamera(width, height), glm::dvec3(0.0), 1.0, kTorusRadius - 1.0))
        .first->second;
}

SuggestiveSettings suggestiveSettings() {
    SuggestiveSettings settings;
    settings.featureSize = float(0.05 * kTorusRadius); // 5% of the torus's bounding radius, as the app sets it
    return settings;
}

/** suggestiveSettings() with the app's default smoothing (--suggestive-smoothing) for the image of torusAt(). */
SuggestiveSettings smoothedSettings(int width, int height) {
    SuggestiveSettings settings = suggestiveSettings();
    settings.smoothing = float(kSuggestiveSmoothingFraction * kTorusRadius);
    settings.focalPixels = float(torusCamera(width, height).focalPixels());
    return settings;
}

void finish(benchmark::State& state, int width, int height, std::size_t points) {
    state.counters["Mpixel/s"] =
        benchmark::Counter(double(width) * height * 1e-6, benchmark::Counter::kIsIterationInvariantRate);
    state.counters["points"] = double(points);
}

int widthOf(const benchmark::State& state) { return int(state.range(0)); }
int heightOf(const benchmark::State& state) { return int(state.range(1)); }

void BM_PostfxContour(benchmark::State& state) {
    const test::SyntheticGBuffer& buffer = torusAt(widthOf(state), heightOf(state));
    std::size_t points = 0;
    for (auto _ : state) points = extractContours(buffer.nDotV, buffer.depth, {}).points.size();
    finish(state, widthOf(state), heightOf(state), points);
}

void BM_PostfxSuggestive(benchmark::State& state) {
    const test::SyntheticGBuffer& buffer = torusAt(widthOf(state), heightOf(state));
    std::size_t points = 0;
    for (auto _ : state)
        points = extractSuggestiveContours(buffer.radial, buffer.depth, suggestiveSettings()).points.size();
    finish(state, widthOf(state), heightOf(state), points);
}

void BM_PostfxSuggestiveSmoothed(benchmark::State& state) {
    const test::SyntheticGBuffer& buffer = torusAt(widthOf(state), heightOf(state));
    const SuggestiveSettings settings = smoothedSettings(widthOf(state), heightOf(state));
    std::size_t points = 0;
    for (auto _ : state) points = extractSuggestiveContours(buffer.radial, buffer.depth, settings).points.size();
    finish(state, widthOf(state), heightOf(state), points);
}

void BM_PostfxSuggestiveSmoothedSurfaceIds(benchmark::State& state) {
    const test::SyntheticGBuffer& buffer = torusAt(widthOf(state), heightOf(state));
    const SuggestiveSettings settings = smoothedSettings(widthOf(state), heightOf(state));
    // One id over the whole torus: every comparison is made and none cuts a window, so the lines and the work are
    // BM_PostfxSuggestiveSmoothed's and the difference is what reading the ids costs.
    const cv::Mat surface(buffer.depth.size(), CV_32FC1, cv::Scalar::all(1.0));
    std::size_t points = 0;
    for (auto _ : state)
        points = extractSuggestiveContours(buffer.radial, buffer.depth, settings, surface).points.size();
    finish(state, widthOf(state), heightOf(state), points);
}

void BM_PostfxSmoothRadialField(benchmark::State& state) {
    const test::SyntheticGBuffer& buffer = torusAt(widthOf(state), heightOf(state));
    const SuggestiveSettings settings = smoothedSettings(widthOf(state), heightOf(state));
    for (auto _ : state) benchmark::DoNotOptimize(smoothRadialField(buffer.radial, buffer.depth, settings));
    finish(state, widthOf(state), heightOf(state), 0);
}

void BM_PostfxDepthEdge(benchmark::State& state) {
    const test::SyntheticGBuffer& buffer = torusAt(widthOf(state), heightOf(state));
    std::size_t points = 0;
    for (auto _ : state) points = extractDepthEdges(buffer.depth, {}).points.size();
    finish(state, widthOf(state), heightOf(state), points);
}

void BM_PostfxNormalEdge(benchmark::State& state) {
    const test::SyntheticGBuffer& buffer = torusAt(widthOf(state), heightOf(state));
    std::size_t points = 0;
    for (auto _ : state) points = extractNormalEdges(buffer.normal, buffer.depth, {}).points.size();
    finish(state, widthOf(state), heightOf(state), points);
}

void BM_PostfxStrokeContour(benchmark::State& state) {
    const test::SyntheticGBuffer& buffer = torusAt(widthOf(state), heightOf(state));
    const LineSkeleton skeleton = extractContours(buffer.nDotV, buffer.depth, {});
    for (auto _ : state) benchmark::DoNotOptimize(strokeLines(skeleton, 2.0f, 1));
    finish(state, widthOf(state), heightOf(state), skeleton.points.size());
}

void BM_PostfxComposite3(benchmark::State& state) {
    const cv::Size size(widthOf(state), heightOf(state));
    const test::SyntheticGBuffer& buffer = torusAt(size.width, size.height);
    CompositeInputs inputs;
    inputs.size = size;
    inputs.shading = cv::Mat(size, CV_8UC4, cv::Scalar(180, 160, 140, 255));
    const cv::Mat contour = strokeLines(extractContours(buffer.nDotV, buffer.depth, {}), 2.0f, 1);
    for (int layer = 0; layer < 3; ++layer) inputs.lines.push_back({"layer", contour, {0.0f, 0.0f, 0.0f, 1.0f}});
    for (auto _ : state) benchmark::DoNotOptimize(compositeFinal(inputs));
    finish(state, size.width, size.height, 0);
}

/** What `--lines silhouette,contour,suggestive` adds on the CPU after readback: two kernels, two strokes and the
 *  composite of three layers over the shading (the silhouette mask comes from GL). */
void BM_PostfxStageSilhouetteContourSuggestive(benchmark::State& state) {
    const cv::Size size(widthOf(state), heightOf(state));
    const test::SyntheticGBuffer& buffer = torusAt(size.width, size.height);
    CompositeInputs inputs;
    inputs.size = size;
    inputs.shading = cv::Mat(size, CV_8UC4, cv::Scalar(180, 160, 140, 255));
    const cv::Mat hull = strokeLines(extractDepthEdges(buffer.depth, {}), 2.0f, 1);
    std::size_t points = 0;
    for (auto _ : state) {
        const LineSkeleton contour = extractContours(buffer.nDotV, buffer.depth, {});
        const LineSkeleton suggestive = extractSuggestiveContours(buffer.radial, buffer.depth, suggestiveSettings());
        inputs.lines = {{"silhouette", hull, {0.0f, 0.0f, 0.0f, 1.0f}},
                        {"suggestive", strokeLines(suggestive, 2.0f, 1), {0.0f, 0.0f, 0.0f, 1.0f}},
                        {"contour", strokeLines(contour, 2.0f, 1), {0.0f, 0.0f, 0.0f, 1.0f}}};
        benchmark::DoNotOptimize(compositeFinal(inputs));
        points = contour.points.size() + suggestive.points.size();
    }
    finish(state, size.width, size.height, points);
}

/** The stroke stage of `--lines silhouette,contour,suggestive` (passes/lines/StrokesPass.cpp, its defaults): the
 *  silhouette's mask thinned, the three skeletons chained into strokes, and each layer's kept skeleton drawn. */
void BM_PostfxStrokes(benchmark::State& state) {
    const cv::Size size(widthOf(state), heightOf(state));
    const test::SyntheticGBuffer& buffer = torusAt(size.width, size.height);
    const cv::Mat hull = strokeLines(extractDepthEdges(buffer.depth, {}), 2.0f, 1);
    const LineSkeleton contour = extractContours(buffer.nDotV, buffer.depth, {});
    const LineSkeleton suggestive = extractSuggestiveContours(buffer.radial, buffer.depth, suggestiveSettings());
    const StrokeSettings settings = strokeSettingsFor(size.height, 1);
    std::size_t strokes = 0;
    for (auto _ : state) {
        const LineSkeleton silhouette = skeletonFromMask(thinToSkeleton(hull));
        const std::vector<StrokeLayer> layers = {{&silhouette}, {&contour}, {&suggestive}};
        const Strokes chained = chainStrokes(layers, settings);
        for (int layer = 0; layer < int(layers.size()); ++layer)
            benchmark::DoNotOptimize(strokeLines(keptSkeleton(chained, layers, layer), 2.0f, 1));
        strokes = chained.strokes.size();
    }
    finish(state, size.width, size.height, strokes);
}

void sizes(benchmark::internal::Benchmark* benchmark) {
    benchmark->Args({512, 512})->Args({1024, 1024})->Args({1920, 1080})->Args({4096, 4096});
    benchmark->ArgNames({"w", "h"})->Unit(benchmark::kMillisecond);
}

BENCHMARK(BM_PostfxContour)->Apply(sizes);
BENCHMARK(BM_PostfxSuggestive)->Apply(sizes);
BENCHMARK(BM_PostfxSuggestiveSmoothed)->Apply(sizes);
BENCHMARK(BM_PostfxSuggestiveSmoothedSurfaceIds)->Apply(sizes);
BENCHMARK(BM_PostfxSmoothRadialField)->Apply(sizes);
BENCHMARK(BM_PostfxDepthEdge)->Apply(sizes);
BENCHMARK(BM_PostfxNormalEdge)->Apply(sizes);
BENCHMARK(BM_PostfxStrokeContour)->Apply(sizes);
BENCHMARK(BM_PostfxComposite3)->Apply(sizes);
BENCHMARK(BM_PostfxStageSilhouetteContourSuggestive)->Apply(sizes);
BENCHMARK(BM_PostfxStrokes)->Apply(sizes);

} // namespace
} // namespace inkgraph::bench
