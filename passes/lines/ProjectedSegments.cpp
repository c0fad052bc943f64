#include "passes/lines/ProjectedSegments.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace inkgraph {
namespace {

/** Samples are at most this far apart along the image (data pixels), so the one-pixel skeleton has no gaps and the
 *  stroke's discs overlap. */
constexpr double kSampleSpacingPixels = 0.5;

} // namespace

SegmentProjector::SegmentProjector(const Camera& camera, const cv::Mat& depth, double depthJump, SegmentVisibility keep)
    : mView(camera.viewMatrix()), mProjection(camera.projectionMatrix()), mDepth(depth), mTolerance(1.0 + depthJump),
      mKeep(keep) {
    if (depth.type() != CV_32FC1) throw std::invalid_argument("SegmentProjector: 'depth' must be a CV_32FC1 image");
    mSkeleton.mask = cv::Mat::zeros(depth.size(), CV_8UC1);
}

bool SegmentProjector::isVisible(double x, double y, double pointDepth) const {
    // The rule in the header: some surface pixel centre of the 2 x 2 around the point is not nearer than it by more
    // than the tolerance.
    const int left = int(std::floor(x)), top = int(std::floor(y));
    for (int row = top; row <= top + 1; ++row)
        for (int col = left; col <= left + 1; ++col) {
            if (row < 0 || col < 0 || row >= mDepth.rows || col >= mDepth.cols) continue;
            const double surface = mDepth.at<float>(row, col);
            if (surface > 0.0 && pointDepth <= surface * mTolerance) return true;
        }
    return false;
}

void SegmentProjector::add(const glm::dvec3& a, const glm::dvec3& b, double strengthA, double strengthB, int mesh,
                           long triangle) {
    const int width = mDepth.cols, height = mDepth.rows;
    // Pixel coordinates of a clip-space point: x right, y down, pixel centres at integers.
    auto toPixel = [&](const glm::dvec4& clip) {
        return glm::dvec2((clip.x / clip.w + 1.0) * 0.5 * width - 0.5, (1.0 - clip.y / clip.w) * 0.5 * height - 0.5);
    };
    const glm::dvec4 viewA = mView * glm::dvec4(a, 1.0);
    const glm::dvec4 viewB = mView * glm::dvec4(b, 1.0);
    const glm::dvec4 clipA = mProjection * viewA, clipB = mProjection * viewB;
    // Clip to GL's near (z >= -w) and far (z <= w) planes, as the rasteriser does.
    double from = 0.0, to = 1.0;
    for (const double side : {1.0, -1.0}) {
        const double startSide = clipA.w + side * clipA.z, endSide = clipB.w + side * clipB.z;
        if (startSide < 0.0 && endSide < 0.0)
            return;
        else if (startSide < 0.0)
            from = std::max(from, startSide / (startSide - endSide));
        else if (endSide < 0.0)
            to = std::min(to, startSide / (startSide - endSide));
    }
    if (!(to > from)) return;
    const glm::dvec2 start = toPixel(clipA + from * (clipB - clipA));
    const glm::dvec2 end = toPixel(clipA + to * (clipB - clipA));
    // Linear view depth at the clipped ends; its reciprocal is linear along the image under perspective.
    const double startDepth = -(viewA.z + from * (viewB.z - viewA.z));
    const double endDepth = -(viewA.z + to * (viewB.z - viewA.z));
    const int steps = std::max(1, int(std::ceil(glm::length(end - start) / kSampleSpacingPixels)));
    const bool keepVisible = mKeep == SegmentVisibility::Visible;
    for (int step = 0; step <= steps; ++step) {
        const double s = double(step) / double(steps);
        const double inverseDepth = (1.0 - s) / startDepth + s / endDepth;
        const double pointDepth = 1.0 / inverseDepth;
        // Where along the 3-D segment the sample lies, for the strength (linear there).
        const double along = from + (to - from) * (s / endDepth) / inverseDepth;
        const double strength = std::min(1.0, strengthA + along * (strengthB - strengthA));
        if (!(strength > 0.0)) continue; // a cut end at a threshold: nothing to draw
        const glm::dvec2 pixel = start + s * (end - start);
        const int col = int(std::lround(pixel.x)), row = int(std::lround(pixel.y));
        if (col < 0 || row < 0 || col >= width || row >= height) continue;
        if (isVisible(pixel.x, pixel.y, pointDepth) != keepVisible) continue;
        mSkeleton.points.push_back({cv::Point2f(float(pixel.x), float(pixel.y)), float(strength)});
        const glm::dvec3 onMesh = a + along * (b - a);
        mSkeleton.surface.push_back({cv::Point3d(onMesh.x, onMesh.y, onMesh.z), mesh, triangle});
        mSkeleton.mask.at<uchar>(row, col) = 255;
    }
}

} // namespace inkgraph
