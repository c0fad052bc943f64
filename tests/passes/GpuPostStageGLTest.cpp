// The post stage on the GPU (--post-stage gpu, passes/lines/types/GpuImageEdges.h): the compute-shader kernels find
// what the CPU kernels of postfx/ find, point for point within 1e-3 px, on ray-cast analytic G-buffers uploaded as
// textures (held to the analytic lines with the tolerances of tests/postfx/AnalyticLinesTest.cpp) and on the G-buffer
// of rendered models through the still graph; the GPU composite (passes/composite/GpuCompositePass.h) makes the CPU
// composite's picture to the byte; and auto picks the CPU on a software rasterizer.
#include "gl/Readback.h"
#include "graph/GraphCompiler.h"
#include "passes/PostStage.h"
#include "passes/StillGraph.h"
#include "passes/lines/types/GpuImageEdges.h"
#include "postfx/LineMetrics.h"
#include "scene/mesh/Procedural.h"
#include "tests/support/AnalyticLines.h"
#include "tests/support/GlTestContext.h"
#include "tests/support/PassHarness.h"
#include "tests/support/SyntheticGBuffer.h"
#include "tests/support/TestCamera.h"

#include <gtest/gtest.h>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

namespace inkgraph {
namespace {

constexpr double kAgreementPixels = 1e-3;

/** The CPU and the GPU skeleton are the same: the same mask, the same points in the same order within 1e-3 px. */
void expectSameSkeleton(const LineSkeleton& cpu, const LineSkeleton& gpu, const std::string& what) {
    SCOPED_TRACE(what);
    ASSERT_EQ(cpu.mask.size(), gpu.mask.size());
    EXPECT_EQ(cv::countNonZero(cpu.mask != gpu.mask), 0) << "mask pixels differ";
    ASSERT_EQ(cpu.points.size(), gpu.points.size());
    EXPECT_GT(cpu.points.size(), 0u);
    double worst = 0.0;
    for (std::size_t i = 0; i < cpu.points.size(); ++i) {
        worst = std::max(worst, double(cv::norm(cpu.points[i].position - gpu.points[i].position)));
        EXPECT_EQ(cpu.points[i].strength, gpu.points[i].strength);
    }
    EXPECT_LE(worst, kAgreementPixels) << "largest distance between a CPU point and its GPU point";
}

/** As tests/postfx/AnalyticLinesTest.cpp prints it, for docs/accuracy.md. */
void printAccuracy(const std::string& what, const LineAccuracy& accuracy) {
    std::cout << what << ": P " << accuracy.precision << " R " << accuracy.recall << " F1 " << accuracy.f1
              << "; predicted->truth P95 " << accuracy.predictedToTruthP95 << " max " << accuracy.predictedToTruthMax
              << "; truth->predicted P95 " << accuracy.truthToPredictedP95 << "\n";
}

GlTexture uploaded(const cv::Mat& image, Format format, const std::string& label) {
    GlTexture texture(format, image.cols, image.rows, label);
    uploadImage(texture, image);
    return texture;
}

class GpuPostStage : public ::testing::Test, protected test::PassHarness {
protected:
    void SetUp() override { test::sharedGlContext(); }

    /** The three kernels on a synthetic G-buffer, on the GPU and on the CPU. */
    void expectKernelsAgree(const test::SyntheticGBuffer& buffer, const std::string& what) {
        const GlTexture nDotV = uploaded(buffer.nDotV, Format::R32F, "nDotV");
        const GlTexture depth = uploaded(buffer.depth, Format::R32F, "depth");
        const GlTexture normal = uploaded(buffer.normal, Format::RGBA32F, "normal");
        GpuNeighbourPairsKernel contour("gbuffer", ContourSettings{}, shaders);
        expectSameSkeleton(extractContours(buffer.nDotV, buffer.depth, {}), contour.findInTextures({&nDotV, &depth}),
                           what + " contour");
        GpuNeighbourPairsKernel depthEdge("gbuffer", DepthEdgeSettings{}, shaders);
        expectSameSkeleton(extractDepthEdges(buffer.depth, {}), depthEdge.findInTextures({&depth}),
                           what + " depth-edge");
        for (const float crease : {0.0f, 10.0f, 30.0f, 180.0f}) {
            NormalEdgeSettings settings;
            settings.creaseAngleDegrees = crease;
            GpuNeighbourPairsKernel normalEdge("gbuffer", settings, shaders);
            const LineSkeleton cpu = extractNormalEdges(buffer.normal, buffer.depth, settings);
            const LineSkeleton gpu = normalEdge.findInTextures({&normal, &depth});
            if (cpu.points.empty()) { // a smooth surface at a wide angle: nothing on either side
                EXPECT_TRUE(gpu.points.empty()) << what << " normal-edge at " << crease << " degrees";
                continue;
            }
            expectSameSkeleton(cpu, gpu, what + " normal-edge at " + std::to_string(crease) + " degrees");
        }
    }
};

test::SyntheticCamera torusCamera() {
    test::SyntheticCamera camera;
    camera.width = camera.height = 512;
    const double elevation = glm::radians(30.0);
    camera.eye = {0.0, -5.0 * std::cos(elevation), 5.0 * std::sin(elevation)};
    camera.up = {0.0, 0.0, 1.0};
    return camera;
}

TEST_F(GpuPostStage, ContoursOfRayCastSpheresMeetTheAnalyticTolerances) {
    for (const test::SphereCase& sphereCase : test::kSphereCases) {
        test::SyntheticCamera camera;
        camera.eye = sphereCase.eye;
        camera.target = sphereCase.target;
        const test::SyntheticGBuffer buffer = test::renderSphere(camera, sphereCase.center, sphereCase.radius);
        const GlTexture nDotV = uploaded(buffer.nDotV, Format::R32F, "nDotV");
        const GlTexture depth = uploaded(buffer.depth, Format::R32F, "depth");
        GpuNeighbourPairsKernel kernel("gbuffer", ContourSettings{}, shaders);
        const LineSkeleton skeleton = kernel.findInTextures({&nDotV, &depth});
        const auto truth = test::sphereSilhouette(camera, sphereCase.center, sphereCase.radius);
        const LineAccuracy accuracy = scoreLinePoints(outputPixelPositions(skeleton, 1), truth, 1.0);
        printAccuracy("gpu contour, sphere radius " + std::to_string(sphereCase.radius), accuracy);
        EXPECT_GE(accuracy.f1, 0.99);
        EXPECT_LT(accuracy.predictedToTruthP95, 0.75);
        EXPECT_LT(accuracy.truthToPredictedP95, 0.75);
        EXPECT_EQ(kernel.lastEventCount(), skeleton.points.size());
    }
}

TEST_F(GpuPostStage, ContoursOfARayCastTorusMeetTheAnalyticTolerances) {
    const test::SyntheticCamera camera = torusCamera();
    const test::SyntheticGBuffer buffer = test::renderTorus(camera, glm::dvec3(0.0), 1.0, 0.4);
    const GlTexture nDotV = uploaded(buffer.nDotV, Format::R32F, "nDotV");
    const GlTexture depth = uploaded(buffer.depth, Format::R32F, "depth");
    GpuNeighbourPairsKernel kernel("gbuffer", ContourSettings{}, shaders);
    const LineSkeleton skeleton = kernel.findInTextures({&nDotV, &depth});
    const LineAccuracy accuracy =
        scoreLinePoints(outputPixelPositions(skeleton, 1), test::torusContours(camera, glm::dvec3(0.0), 1.0, 0.4), 1.0);
    printAccuracy("gpu contour, torus", accuracy);
    EXPECT_GE(accuracy.f1, 0.99);
    EXPECT_LT(accuracy.predictedToTruthP95, 0.75);
    EXPECT_LT(accuracy.truthToPredictedP95, 0.75);
}

TEST_F(GpuPostStage, KernelsAgreeWithTheCpuKernelsOnAnalyticGBuffers) {
    for (const test::SphereCase& sphereCase : test::kSphereCases) {
        test::SyntheticCamera camera;
        camera.eye = sphereCase.eye;
        camera.target = sphereCase.target;
        expectKernelsAgree(test::renderSphere(camera, sphereCase.center, sphereCase.radius), "sphere");
    }
    expectKernelsAgree(test::renderTorus(torusCamera(), glm::dvec3(0.0), 1.0, 0.4), "torus");
}

TEST_F(GpuPostStage, AFrameFullOfLinesGrowsTheEventBuffer) {
    // Alternating n.v on one plane: a crossing between every two neighbours, far more than the buffer first holds.
    cv::Mat nDotV(64, 96, CV_32FC1), depth(64, 96, CV_32FC1, cv::Scalar(2.0f));
    for (int row = 0; row < nDotV.rows; ++row)
        for (int col = 0; col < nDotV.cols; ++col) nDotV.at<float>(row, col) = ((row + col) % 2 ? 0.3f : -0.1f);
    const GlTexture nDotVTexture = uploaded(nDotV, Format::R32F, "nDotV");
    const GlTexture depthTexture = uploaded(depth, Format::R32F, "depth");
    GpuNeighbourPairsKernel kernel("gbuffer", ContourSettings{}, shaders);
    expectSameSkeleton(extractContours(nDotV, depth, {}), kernel.findInTextures({&nDotVTexture, &depthTexture}),
                       "checkerboard");
    EXPECT_EQ(kernel.lastEventCount(), std::size_t(63 * 96 + 64 * 95));
}

TEST_F(GpuPostStage, RefusesInputsItCannotRead) {
    GpuNeighbourPairsKernel kernel("gbuffer", ContourSettings{}, shaders);
    const GlTexture small(Format::R32F, 8, 8, "small");
    const GlTexture large(Format::R32F, 16, 8, "large");
    try {
        kernel.findInTextures({&small, &large});
        FAIL() << "textures of two sizes";
    } catch (const std::invalid_argument& error) {
        EXPECT_EQ(std::string(error.what()).rfind("GpuNeighbourPairsKernel::findInTextures(): 'large'", 0), 0u)
            << error.what();
    }
    EXPECT_THROW(kernel.findInTextures({&small}), std::invalid_argument);
    EXPECT_THROW(GpuNeighbourPairsKernel("gbuffer", ContourSettings{-1.0f}, shaders), std::invalid_argument);
}

/** Runs the still graph of `look` over `scene`; returns each type's skeleton. */
class GpuPostStageStill : public GpuPostStage {
protected:
    std::vector<LineSkeleton> skeletons(Look look, PostStageDevice device, const std::vector<std::string>& types) {
        look.postStage = device;
        look.lines = types;
        gpuScene = std::make_unique<GpuScene>(scene, frame.worldOrigin);
        StillGraphSetup setup{look, shaders, scene, computeBoundingSphere(scene), *gpuScene, frame, std::nullopt};
        StillGraph graph = buildStillGraph(setup);
        EXPECT_EQ(graph.postStageDevice, device);
        std::vector<std::string> requested = {graph.finalResource};
        for (const std::string& type : types) requested.push_back(type + ".skeleton");
        const Plan plan = compile(graph.view(), requested);
        ExecuteOptions options;
        options.frameWidth = frame.camera.width;
        options.frameHeight = frame.camera.height;
        executor.run(plan, graph.mutableView(), options);
        std::vector<LineSkeleton> result;
        for (const std::string& type : types)
            result.push_back(executor.store().object<LineSkeleton>(type + ".skeleton"));
        const nlohmann::ordered_json postStage = graph.describePostStage({});
        EXPECT_EQ(postStage["device"], postStageDeviceName(device));
        return result;
    }

    void expectSameOnBothDevices(const std::string& what, int supersample = 1) {
        Look look;
        look.supersample = supersample;
        const std::vector<std::string> types = {"contour", "depth-edge", "normal-edge"};
        const std::vector<LineSkeleton> cpu = skeletons(look, PostStageDevice::Cpu, types);
        const std::vector<LineSkeleton> gpu = skeletons(look, PostStageDevice::Gpu, types);
        for (std::size_t i = 0; i < types.size(); ++i) {
            if (types[i] == "normal-edge" && cpu[i].points.empty()) { // a smooth model has no crease at 30 degrees
                EXPECT_TRUE(gpu[i].points.empty()) << what;
                continue;
            }
            expectSameSkeleton(cpu[i], gpu[i], what + " " + types[i]);
        }
    }
};

TEST_F(GpuPostStageStill, CpuAndGpuSkeletonsAgreeOnATorus) {
    scene = makeScene(makeTorus(1.0f, 0.4f, 96, 48));
    frame.camera = test::lookingAt(scene, {0.0, -4.3, 2.5}, glm::dvec3(0.0), 35.0, 256, 256);
    expectSameOnBothDevices("torus");
    expectSameOnBothDevices("torus at supersample 2", 2);
}

TEST_F(GpuPostStageStill, CpuAndGpuSkeletonsAgreeOnTheFandisk) {
    scene = loadScene(std::string(INKGRAPH_SOURCE_ROOT) + "/models/fandisk_c3d.obj");
    CameraRequest request; // auto-framed, as the app frames a model
    request.width = 320;
    request.height = 240;
    frame.camera = resolveCamera(request, scene);
    frame.worldOrigin = computeBoundingSphere(scene).center;
    expectSameOnBothDevices("fandisk");
}

/** The final picture of `look` with the post stage on `device`. */
cv::Mat finalPicture(test::PassHarness& harness, Look look, PostStageDevice device) {
    look.postStage = device;
    harness.gpuScene = std::make_unique<GpuScene>(harness.scene, harness.frame.worldOrigin);
    StillGraphSetup setup{
        look,          harness.shaders, harness.scene, computeBoundingSphere(harness.scene), *harness.gpuScene,
        harness.frame, std::nullopt};
    StillGraph graph = buildStillGraph(setup);
    const Plan plan = compile(graph.view(), {graph.finalResource});
    ExecuteOptions options;
    options.frameWidth = harness.frame.camera.width;
    options.frameHeight = harness.frame.camera.height;
    harness.executor.run(plan, graph.mutableView(), options);
    return harness.executor.store().image(graph.finalResource).clone();
}

TEST_F(GpuPostStageStill, TheGpuCompositeIsTheCpuCompositeToTheByte) {
    scene = makeScene(makeTorus(1.0f, 0.4f, 96, 48));
    frame.camera = test::lookingAt(scene, {0.0, -4.3, 2.5}, glm::dvec3(0.0), 35.0, 200, 150);
    frame.background = glm::vec4(0.9f, 0.85f, 0.7f, 1.0f); // paper that is not white
    Look look;
    look.lines = {"silhouette", "contour", "suggestive"};
    look.lineStyles["contour"].color = {0.8, 0.1, 0.2, 0.5}; // a translucent layer over another
    look.lineStyles["silhouette"].widthPixels = 5.0;
    for (const ShadingModel shading : {ShadingModel::Cel, ShadingModel::None}) {
        look.shading = shading;
        const cv::Mat cpu = finalPicture(*this, look, PostStageDevice::Cpu);
        const cv::Mat gpu = finalPicture(*this, look, PostStageDevice::Gpu);
        ASSERT_EQ(cpu.size(), gpu.size());
        ASSERT_EQ(cpu.type(), gpu.type());
        EXPECT_EQ(cv::norm(cpu, gpu, cv::NORM_INF), 0.0) << traitsOf(shading).name;
    }
    // --msaa: the shading is multisampled (forward, no line reads the G-buffer); the GPU pass composites it on the
    // CPU after its resolving read-back.
    look.shading = ShadingModel::Cel;
    look.lines = {"silhouette"};
    look.msaa = 4;
    EXPECT_EQ(cv::norm(finalPicture(*this, look, PostStageDevice::Cpu), finalPicture(*this, look, PostStageDevice::Gpu),
                       cv::NORM_INF),
              0.0);
}

TEST(PostStageDevice, AutoTakesTheCpuOnSoftwareRasterizersAndWithoutARenderer) {
    EXPECT_TRUE(isSoftwareRasterizer("llvmpipe (LLVM 15.0.6, 256 bits)"));
    EXPECT_TRUE(isSoftwareRasterizer("softpipe"));
    EXPECT_TRUE(isSoftwareRasterizer("Mesa X11 SWRast"));
    EXPECT_TRUE(isSoftwareRasterizer("Google SwiftShader"));
    EXPECT_FALSE(isSoftwareRasterizer("NVIDIA H200/PCIe/SSE2"));
    EXPECT_EQ(resolvePostStage(PostStageDevice::Auto, "llvmpipe (LLVM 15.0.6, 256 bits)"), PostStageDevice::Cpu);
    EXPECT_EQ(resolvePostStage(PostStageDevice::Auto, "NVIDIA H200/PCIe/SSE2"), PostStageDevice::Gpu);
    EXPECT_EQ(resolvePostStage(PostStageDevice::Auto, ""), PostStageDevice::Cpu);
    EXPECT_EQ(resolvePostStage(PostStageDevice::Gpu, "llvmpipe"), PostStageDevice::Gpu);
    EXPECT_EQ(resolvePostStage(PostStageDevice::Cpu, "NVIDIA H200/PCIe/SSE2"), PostStageDevice::Cpu);
}

} // namespace
} // namespace inkgraph
