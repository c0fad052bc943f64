// Speed of the pieces of one still, measured warm (programs built and meshes uploaded once, as in a batch):
//   - loading the 70k-triangle bunny (OBJ parse + weld + normals);
//   - the G-buffer pass alone at 1024x1024, over sphere meshes from 1k to 1M triangles and the bunny, with the two
//     outputs Lambert needs and with all seven;
//   - the default cel shading and composite passes at 1024x1024;
//   - the G-buffer of the bunny comic look (issue 20) against a bare draw of the same meshes into targets of the same
//     formats (BM_GBufferVsBareDraw), and that look shaded deferred against forward (BM_DeferredShading);
//   - the bunny's suggestive-contour layer (`--lines suggestive`, default smoothing): reading gbuffer.radial and
//     gbuffer.depth back and the CPU kernel, as the pass's one time;
//   - reading a 1024x1024 RGBA32F texture back (gl/Readback), turned over by the driver and by the CPU.
// Times are the pass's own execute() up to glFinish (manual time), which is what --stats reports.
#include "bench/BenchScene.h"
#include "bench/Median.h"
#include "gl/Readback.h"
#include "passes/gbuffer/GBufferPass.h"
#include "passes/shade/ShadePass.h"

#include <glm/gtc/type_ptr.hpp>

#include <chrono>
#include <ctime>

namespace inkgraph::bench {
namespace {

// The two buffers deferred Lambert read (the size of the smallest useful G-buffer).
const std::vector<std::string> kLambertOutputs = {"gbuffer.normal", "gbuffer.baseColor"};
const std::vector<std::string> kAllOutputs = {"gbuffer.normal", "gbuffer.view",     "gbuffer.wVec",     "gbuffer.nDotV",
                                              "gbuffer.depth",  "gbuffer.coverage", "gbuffer.baseColor"};

void BM_LoadBunny(benchmark::State& state) {
    for (auto _ : state) benchmark::DoNotOptimize(loadScene(kBunnyPath));
}
BENCHMARK(BM_LoadBunny)->Unit(benchmark::kMillisecond);

void BM_GBufferSphere_LambertOutputs(benchmark::State& state) {
    Bench bench(sphereScene(int(state.range(0))), Look{}, kLambertOutputs);
    reportPass(state, bench, "gbuffer");
}
BENCHMARK(BM_GBufferSphere_LambertOutputs)
    ->Arg(1000)
    ->Arg(100000)
    ->Arg(1000000)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

void BM_GBufferSphere_AllOutputs(benchmark::State& state) {
    Bench bench(sphereScene(int(state.range(0))), Look{}, kAllOutputs);
    reportPass(state, bench, "gbuffer");
}
BENCHMARK(BM_GBufferSphere_AllOutputs)
    ->Arg(1000)
    ->Arg(100000)
    ->Arg(1000000)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

void BM_GBufferBunny_AllOutputs(benchmark::State& state) {
    Bench bench(loadScene(kBunnyPath), Look{}, kAllOutputs);
    reportPass(state, bench, "gbuffer");
}
BENCHMARK(BM_GBufferBunny_AllOutputs)->UseManualTime()->Unit(benchmark::kMillisecond);

void BM_CelBunny(benchmark::State& state) {
    Bench bench(loadScene(kBunnyPath), Look{}, {"composite.final"});
    reportPass(state, bench, "shade");
}
BENCHMARK(BM_CelBunny)->UseManualTime()->Unit(benchmark::kMillisecond);

void BM_CompositeBunny(benchmark::State& state) {
    Bench bench(loadScene(kBunnyPath), Look{}, {"composite.final"});
    reportPass(state, bench, "composite");
}
BENCHMARK(BM_CompositeBunny)->UseManualTime()->Unit(benchmark::kMillisecond);

/** CPU time of every thread of the process (llvmpipe's rasteriser threads included): unlike wall time, it does not
 *  count the time other processes of a shared host hold the cores. */
double processCpuMilliseconds() {
    timespec time{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &time);
    return double(time.tv_sec) * 1e3 + double(time.tv_nsec) * 1e-6;
}

/** Issue 20's comic still: the bunny, cel, silhouette + contour + suggestive contours. */
Look comicStillLook() {
    Look look;
    look.shading = ShadingModel::Cel;
    look.lines = {"silhouette", "contour", "suggestive"};
    return look;
}

/** The floor a G-buffer is measured against: the same meshes (their vertex arrays) into colour targets of the same
 *  formats and size with a depth test, cleared as the G-buffer clears, but with a shader that only transforms the
 *  positions and writes constants (bench/shaders/bare_draw.*). What the G-buffer costs beyond it is its own work:
 *  attributes, per-fragment maths, material binds. */
class BareDraw {
public:
    BareDraw(Bench& bench, const std::vector<Format>& formats)
        : mBench(bench), mShaders(std::string(INKGRAPH_SOURCE_ROOT) + "/bench/shaders"), mDepth("bare draw depth") {
        for (const Format format : formats)
            mTargets.push_back(std::make_unique<GlTexture>(format, kFrameSize, kFrameSize, "bare draw target"));
        mProgram = std::make_unique<GlProgram>(mShaders.build(
            {"bare draw", "bare_draw.vert", "bare_draw.frag", {"TARGET_COUNT " + std::to_string(formats.size())}}));
        mBench.gpuScene->meshes();
    }

    /** Milliseconds of one draw, from binding the framebuffer to glFinish (as the executor times a pass). */
    double run() {
        glFinish();
        const auto start = std::chrono::steady_clock::now();
        GlFramebuffer framebuffer("bare draw");
        std::vector<int> slots;
        for (std::size_t slot = 0; slot < mTargets.size(); ++slot) {
            framebuffer.attachColor(int(slot), *mTargets[slot]);
            slots.push_back(int(slot));
        }
        framebuffer.attachDepth(mDepth.sized(kFrameSize, kFrameSize));
        framebuffer.finish(slots);
        framebuffer.bind();
        glViewport(0, 0, kFrameSize, kFrameSize);
        clearColorAndDepth(int(slots.size()));
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(kDepthNearer);
        mProgram->use();
        const glm::mat4 clipFromModel = mBench.frame.clipFromView() * mBench.frame.viewFromModel();
        glUniformMatrix4fv(mProgram->uniform("clipFromModel"), 1, GL_FALSE, glm::value_ptr(clipFromModel));
        for (const GpuScene::DrawMesh& mesh : mBench.gpuScene->meshes()) {
            mesh.vertexArray.bind();
            glDrawElements(GL_TRIANGLES, mesh.indexCount, GL_UNSIGNED_INT, nullptr);
        }
        glBindVertexArray(0);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glDisable(GL_DEPTH_TEST);
        glFinish();
        return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    }

private:
    Bench& mBench;
    ShaderLibrary mShaders;
    std::vector<std::unique_ptr<GlTexture>> mTargets;
    std::unique_ptr<GlProgram> mProgram;
    PassDepthBuffer mDepth;
};

/** Issue 20's bound: the G-buffer at most 1.3x a bare draw of the same triangles into the same targets. The G-buffer
 *  computes exactly the fields the comic still's plan reads (from the compiled plan, so the benchmark follows the
 *  look), and the two alternate draw by draw so that a shared host's drift hits both; the ratio is the median of the
 *  per-round ratios. */
void BM_GBufferVsBareDraw(benchmark::State& state) {
    Bench bench(loadScene(kBunnyPath), comicStillLook(), {"composite.final"});
    const PlannedPass* gbuffer = bench.plan.findPass("gbuffer");
    if (gbuffer == nullptr) {
        state.SkipWithError("the comic still's plan does not run the G-buffer");
        return;
    }
    const std::vector<std::string> fields = gbuffer->liveWrites;
    std::vector<Format> formats;
    // The z-buffer the silhouette reads is the G-buffer's depth attachment, which the bare draw has too.
    for (const std::string& field : fields)
        if (const Format format = bench.plan.findResource(field)->desc.format; format != Format::Depth32F)
            formats.push_back(format);
    bench.plan = compile(bench.graph.view(), fields); // the G-buffer alone, with the look's fields
    BareDraw bare(bench, formats);
    bench.run("gbuffer"); // warm-up: llvmpipe compiles shader variants on the first draw
    bare.run();
    std::vector<double> gbufferTimes, bareTimes, ratios, cpuRatios;
    for (auto _ : state) {
        const double gbufferStart = processCpuMilliseconds();
        const double gbufferTime = bench.run("gbuffer");
        const double bareStart = processCpuMilliseconds();
        const double bareTime = bare.run();
        const double bareEnd = processCpuMilliseconds();
        gbufferTimes.push_back(gbufferTime);
        bareTimes.push_back(bareTime);
        ratios.push_back(gbufferTime / bareTime);
        cpuRatios.push_back((bareStart - gbufferStart) / (bareEnd - bareStart));
        state.SetIterationTime(gbufferTime / 1000.0);
    }
    state.counters["triangles"] = double(bench.scene.triangleCount());
    state.counters["fields"] = double(fields.size());
    state.counters["gbuffer_ms"] = median(gbufferTimes);
    state.counters["bare_ms"] = median(bareTimes);
    state.counters["ratio"] = median(ratios);
    state.counters["cpu_ratio"] = median(cpuRatios);
    std::string label;
    for (const std::string& field : fields) {
        if (!label.empty()) label += ",";
        label += ResourceName::split(field).field;
    }
    state.SetLabel(label);
}
BENCHMARK(BM_GBufferVsBareDraw)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(15);

/** The fields of the G-buffer that `bench`'s look reads for its lines (its plan with forward shading). */
std::vector<std::string> lineFields(Bench& bench) {
    const Plan plan = compile(bench.graph.view(), {bench.graph.finalResource});
    const PlannedPass* gbuffer = plan.findPass("gbuffer");
    return gbuffer ? gbuffer->liveWrites : std::vector<std::string>{};
}

/** G-buffer plus shade milliseconds of one run of `bench`'s plan. */
struct ShadingTime {
    double gbuffer = 0.0;
    double shade = 0.0;
};
ShadingTime timeShading(Bench& bench) {
    ShadingTime time;
    for (const PassTiming& timing : bench.run()) {
        if (timing.pass == "gbuffer") time.gbuffer = timing.milliseconds;
        if (timing.pass == "shade") time.shade = timing.milliseconds;
    }
    return time;
}

/** Deferred against forward shading of the comic still (docs/shading.md): the same look twice, one graph as built
 *  (deferred: the G-buffer also writes the fields shading reads, and shading is a full-screen triangle), one with the
 *  shade pass told that no line reads the G-buffer (forward: it draws the meshes again). Both plans run the G-buffer
 *  with the lines' fields and the shade pass, nothing else; they alternate round by round, and the saving is the median
 *  of the per-round differences of G-buffer + shade. */
void BM_DeferredShading(benchmark::State& state, ShadingModel model) {
    Look look = comicStillLook();
    look.shading = model;
    Bench deferred(loadScene(kBunnyPath), look, {"composite.final"});
    Bench forward(loadScene(kBunnyPath), look, {"composite.final"}, /*allowDeferredShading=*/false);
    std::vector<std::string> requested = lineFields(forward);
    requested.push_back("shade.color");
    forward.plan = forward.graph.compilePlan(requested);
    deferred.plan = deferred.graph.compilePlan(requested);
    if (deferred.graph.shadingModeIn(deferred.plan) != "deferred") {
        state.SkipWithError(
            ("the look shades forward: " + deferred.graph.shadingForwardReasonIn(deferred.plan)).c_str());
        return;
    }
    timeShading(forward); // warm-up: llvmpipe compiles shader variants on the first draw
    timeShading(deferred);
    std::vector<double> forwardGBuffer, forwardShade, deferredGBuffer, deferredShade, savings;
    for (auto _ : state) {
        const ShadingTime a = timeShading(forward);
        const ShadingTime b = timeShading(deferred);
        forwardGBuffer.push_back(a.gbuffer);
        forwardShade.push_back(a.shade);
        deferredGBuffer.push_back(b.gbuffer);
        deferredShade.push_back(b.shade);
        savings.push_back((a.gbuffer + a.shade) - (b.gbuffer + b.shade));
        state.SetIterationTime((b.gbuffer + b.shade) / 1000.0);
    }
    state.counters["forward_gbuffer_ms"] = median(forwardGBuffer);
    state.counters["forward_shade_ms"] = median(forwardShade);
    state.counters["deferred_gbuffer_ms"] = median(deferredGBuffer);
    state.counters["deferred_shade_ms"] = median(deferredShade);
    state.counters["saved_ms"] = median(savings);
}
BENCHMARK_CAPTURE(BM_DeferredShading, cel, ShadingModel::Cel)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(9);
BENCHMARK_CAPTURE(BM_DeferredShading, lambert, ShadingModel::Lambert)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(9);
BENCHMARK_CAPTURE(BM_DeferredShading, phong, ShadingModel::Phong)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(9);
BENCHMARK_CAPTURE(BM_DeferredShading, comic, ShadingModel::Comic)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(9);

void BM_SuggestiveLayerBunny(benchmark::State& state) {
    Look look;
    look.lines = {"suggestive"};
    Bench bench(loadScene(kBunnyPath), look, {"suggestive.skeleton"});
    reportPass(state, bench, "suggestive");
}
BENCHMARK(BM_SuggestiveLayerBunny)->UseManualTime()->Unit(benchmark::kMillisecond);

/** The radial field's size and format. Warm: after the first read the allocator hands the same memory back, so this
 *  is the copy alone, not the first touch of fresh memory a still pays. */
void BM_ReadbackRgba32f(benchmark::State& state) {
    context();
    GlTexture texture(Format::RGBA32F, kFrameSize, kFrameSize, "readback bench");
    uploadImage(texture, cv::Mat(kFrameSize, kFrameSize, CV_32FC4, cv::Scalar(0.5, -0.25, 2.0, 1.0)));
    const ReadbackFlip flip = state.range(0) == 0 ? ReadbackFlip::Fastest : ReadbackFlip::Cpu;
    for (auto _ : state) benchmark::DoNotOptimize(readTexture(texture, flip));
    state.counters["MiB/s"] = benchmark::Counter(double(kFrameSize) * kFrameSize * 16.0 / (1 << 20),
                                                 benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_ReadbackRgba32f)->Arg(0)->Arg(1)->ArgName("cpu_flip")->Unit(benchmark::kMillisecond);

} // namespace
} // namespace inkgraph::bench
