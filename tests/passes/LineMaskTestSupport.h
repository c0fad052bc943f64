#pragma once
/** @file Shared by the line-pass GL tests: a scene with a camera, one line pass run next to the G-buffer's coverage
 *  through the compiler and executor, and measurements on the masks (ring widths along rows and columns, distances
 *  from an analytic sphere silhouette). */

#include "gl/GraphExecutor.h"
#include "gl/ShaderLibrary.h"
#include "graph/GraphCompiler.h"
#include "passes/FrameParams.h"
#include "passes/GpuScene.h"
#include "passes/gbuffer/GBufferPass.h"
#include "scene/Camera.h"
#include "scene/mesh/Procedural.h"
#include "tests/support/GlTestContext.h"
#include "tests/support/PassHarness.h"
#include "tests/support/TestCamera.h"

#include <gtest/gtest.h>

#include <glm/glm.hpp>
#include <opencv2/core.hpp>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

namespace inkgraph::test {

/** The masks of one run: the line pass's `lines` and the G-buffer's coverage (both 0 or 255, row 0 at the top). */
struct LineRender {
    cv::Mat lines;
    cv::Mat coverage;
};

class LinePassFixture : public ::testing::Test, protected test::PassHarness {
protected:
    void SetUp() override { sharedGlContext(); }

    /** Replaces the scene (and the GpuScene built on it). */
    void setScene(Scene newScene) {
        gbuffer.reset();
        gpuScene.reset();
        scene = std::move(newScene);
        gpuScene = std::make_unique<GpuScene>(scene, computeBoundingSphere(scene).center);
        gbuffer = std::make_unique<GBufferPass>("gbuffer", shaders, *gpuScene, frame);
    }

    /** Resolves a camera like the app (near and far fitted to the bounding sphere) at `width` x `height`. */
    void lookFrom(glm::dvec3 eye, glm::dvec3 target, double fovYDegrees, int width, int height) {
        frame.camera = test::lookingAt(scene, eye, target, fovYDegrees, width, height);
        frame.worldOrigin = gpuScene->worldOrigin();
    }

    /** Runs `linePass` (whose mask is "<name>.lines") and, when `withCoverage`, the G-buffer's coverage, through
     *  compile() and the executor, as the app does. */
    LineRender render(GlPass& linePass, bool withCoverage = true) {
        const std::string lines = std::string(linePass.name()) + ".lines";
        std::vector<std::string> requested = {lines};
        if (withCoverage) requested.push_back("gbuffer.coverage");
        const Plan plan = compile({gbuffer.get(), &linePass}, requested);
        executor.run(plan, {gbuffer.get(), &linePass}, {frame.camera.width, frame.camera.height, false});
        LineRender result;
        result.lines = executor.store().image(lines).clone();
        if (withCoverage) result.coverage = executor.store().image("gbuffer.coverage").clone();
        return result;
    }

    std::unique_ptr<GBufferPass> gbuffer; ///< coverage for the line tests, built on gpuScene
};

/** A unit sphere at the origin, fine enough that its polygon lies within 0.02 px of the circle at these sizes. */
inline Scene fineSphereScene() { return makeScene(makeUvSphere({0.0f, 0.0f, 0.0f}, 1.0f, 256, 128)); }

/** Starting at `from` and stepping by (stepCol, stepRow): walks while `coverage` is set, then counts the
 *  consecutive set pixels of `lines` from the first uncovered pixel. `strayBeyond` counts set line pixels after
 *  that run up to the image border (they should not exist outside a lone convex object). */
struct OutsideRun {
    int length = 0;
    int strayBeyond = 0;
};
inline OutsideRun measureOutsideRun(const LineRender& render, cv::Point from, int stepCol, int stepRow) {
    OutsideRun run;
    const auto inside = [&](cv::Point p) {
        return p.x >= 0 && p.y >= 0 && p.x < render.lines.cols && p.y < render.lines.rows;
    };
    cv::Point p = from;
    while (inside(p) && render.coverage.at<uchar>(p) == 255) p += cv::Point(stepCol, stepRow);
    while (inside(p) && render.lines.at<uchar>(p) == 255) {
        ++run.length;
        p += cv::Point(stepCol, stepRow);
    }
    for (; inside(p); p += cv::Point(stepCol, stepRow)) run.strayBeyond += render.lines.at<uchar>(p) == 255;
    return run;
}

/** The sphere of radius `radius` at distance `distance` on the view axis: its silhouette circle in pixels. */
struct SilhouetteCircle {
    double centreCol;
    double centreRow;
    double radius;
    /** Signed distance in pixels of pixel (col, row)'s centre from the circle: > 0 outside. */
    double distance(int col, int row) const {
        return std::hypot(col + 0.5 - centreCol, row + 0.5 - centreRow) - radius;
    }
};
inline SilhouetteCircle silhouetteOf(const Camera& camera, double radius, double distance) {
    return {camera.width / 2.0, camera.height / 2.0,
            camera.focalPixels() * radius / std::sqrt(distance * distance - radius * radius)};
}

/** The four runs through the image centre (left, right, up, down), for a sphere centred on the view axis. */
inline std::vector<OutsideRun> runsFromCentre(const LineRender& render) {
    const cv::Point centre(render.lines.cols / 2, render.lines.rows / 2);
    return {measureOutsideRun(render, centre, -1, 0), measureOutsideRun(render, centre, 1, 0),
            measureOutsideRun(render, centre, 0, -1), measureOutsideRun(render, centre, 0, 1)};
}

} // namespace inkgraph::test
