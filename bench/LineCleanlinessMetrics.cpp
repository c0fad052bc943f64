#include "bench/LineCleanlinessMetrics.h"

#include "postfx/LineMetrics.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace inkgraph::bench {

namespace {

void requireByteImage(const cv::Mat& image, const std::string& function, const std::string& argument) {
    if (image.empty() || image.type() != CV_8UC1)
        throw std::invalid_argument(function + ": '" + argument + "' must be a non-empty CV_8UC1 image");
}

void requireInkThreshold(int inkThreshold, const std::string& function) {
    if (inkThreshold < 1 || inkThreshold > 255)
        throw std::invalid_argument(function + ": 'inkThreshold' must be 1 to 255, got " +
                                    std::to_string(inkThreshold));
}

void requireFinitePoints(const std::vector<cv::Point2d>& points, const std::string& function,
                         const std::string& argument) {
    for (const cv::Point2d& point : points)
        if (!std::isfinite(point.x) || !std::isfinite(point.y))
            throw std::invalid_argument(function + ": '" + argument + "' holds a non-finite coordinate");
}

/** Points bucketed by square cells of one size, so a neighbour search looks at 3 x 3 cells only. */
class PointGrid {
public:
    PointGrid(const std::vector<cv::Point2d>& points, double cellSize) : mPoints(points), mCellSize(cellSize) {
        for (std::size_t index = 0; index < points.size(); ++index)
            mCells[key(cellOf(points[index].x), cellOf(points[index].y))].push_back(index);
    }

    bool anyWithin(const cv::Point2d& point, double tolerance) const {
        const double toleranceSquared = tolerance * tolerance;
        const std::int64_t column = cellOf(point.x);
        const std::int64_t row = cellOf(point.y);
        for (std::int64_t dy = -1; dy <= 1; ++dy)
            for (std::int64_t dx = -1; dx <= 1; ++dx) {
                const auto found = mCells.find(key(column + dx, row + dy));
                if (found == mCells.end()) continue;
                for (const std::size_t index : found->second) {
                    const cv::Point2d difference = mPoints[index] - point;
                    if (difference.dot(difference) <= toleranceSquared) return true;
                }
            }
        return false;
    }

private:
    std::int64_t cellOf(double coordinate) const { return std::int64_t(std::floor(coordinate / mCellSize)); }
    static std::int64_t key(std::int64_t column, std::int64_t row) {
        // Rows and columns of any image fit in 32 bits; the key packs both.
        return (row << 32) ^ (column & 0xffffffffLL);
    }

    const std::vector<cv::Point2d>& mPoints;
    double mCellSize;
    std::unordered_map<std::int64_t, std::vector<std::size_t>> mCells;
};

void requireDepth(const cv::Mat& depth, const PinholeView& view, const std::string& argument) {
    if (depth.empty() || depth.type() != CV_32FC1 || depth.size() != view.size)
        throw std::invalid_argument("reprojectPoints(): '" + argument +
                                    "' must be a CV_32FC1 image of its view's size " + std::to_string(view.size.width) +
                                    "x" + std::to_string(view.size.height));
}

/** The smallest positive depth within `radius` of the pixel nearest `point`; 0 when there is none. */
double nearestSurfaceDepth(const cv::Mat& depth, const cv::Point2d& point, int radius) {
    const int column = int(std::lround(point.x));
    const int row = int(std::lround(point.y));
    double nearest = 0.0;
    for (int y = std::max(0, row - radius); y <= std::min(depth.rows - 1, row + radius); ++y)
        for (int x = std::max(0, column - radius); x <= std::min(depth.cols - 1, column + radius); ++x) {
            const double value = depth.at<float>(y, x);
            if (value > 0.0 && std::isfinite(value) && (nearest == 0.0 || value < nearest)) nearest = value;
        }
    return nearest;
}

} // namespace

InkShare measureInkShare(const cv::Mat& coverage, const std::vector<cv::Mat>& lineLayers, int inkThreshold) {
    const std::string function = "measureInkShare()";
    requireByteImage(coverage, function, "coverage");
    requireInkThreshold(inkThreshold, function);
    cv::Mat darkest = cv::Mat::zeros(coverage.size(), CV_8UC1);
    for (std::size_t index = 0; index < lineLayers.size(); ++index) {
        const std::string argument = "lineLayers[" + std::to_string(index) + "]";
        requireByteImage(lineLayers[index], function, argument);
        if (lineLayers[index].size() != coverage.size())
            throw std::invalid_argument(function + ": '" + argument + "' differs in size from 'coverage'");
        cv::max(darkest, lineLayers[index], darkest);
    }
    InkShare share;
    for (int row = 0; row < coverage.rows; ++row)
        for (int column = 0; column < coverage.cols; ++column) {
            const bool model = coverage.at<std::uint8_t>(row, column) > 0;
            const bool ink = darkest.at<std::uint8_t>(row, column) >= inkThreshold;
            share.modelPixels += model;
            share.inkInsideModel += model && ink;
            share.inkOutsideModel += !model && ink;
        }
    if (share.modelPixels > 0) {
        share.insideShare = double(share.inkInsideModel) / double(share.modelPixels);
        share.outsideShare = double(share.inkOutsideModel) / double(share.modelPixels);
    }
    return share;
}

double pathLength(const std::vector<cv::Point2d>& points, bool closed) {
    if (points.empty()) throw std::invalid_argument("pathLength(): 'points' is empty");
    double length = 0.0;
    for (std::size_t index = 1; index < points.size(); ++index) length += cv::norm(points[index] - points[index - 1]);
    if (closed) length += cv::norm(points.front() - points.back());
    return length;
}

PathLengthSummary summarisePathLengths(const std::vector<double>& lengths, double shortBelow) {
    if (!std::isfinite(shortBelow) || shortBelow <= 0.0)
        throw std::invalid_argument("summarisePathLengths(): 'shortBelow' must be finite and > 0, got " +
                                    std::to_string(shortBelow));
    for (const double length : lengths)
        if (!std::isfinite(length) || length < 0.0)
            throw std::invalid_argument("summarisePathLengths(): 'lengths' holds " + std::to_string(length) +
                                        ", not a finite length >= 0");
    PathLengthSummary summary;
    summary.pathCount = lengths.size();
    if (lengths.empty()) return summary;
    summary.shortPathCount = std::size_t(
        std::count_if(lengths.begin(), lengths.end(), [shortBelow](double length) { return length < shortBelow; }));
    summary.shortShare = double(summary.shortPathCount) / double(summary.pathCount);
    std::vector<double> sorted = lengths;
    std::sort(sorted.begin(), sorted.end());
    const std::size_t middle = sorted.size() / 2;
    summary.medianLength = sorted.size() % 2 == 1 ? sorted[middle] : 0.5 * (sorted[middle - 1] + sorted[middle]);
    return summary;
}

std::vector<cv::Point2d> skeletonPoints(const cv::Mat& lineLayer, int inkThreshold) {
    requireByteImage(lineLayer, "skeletonPoints()", "lineLayer");
    requireInkThreshold(inkThreshold, "skeletonPoints()");
    cv::Mat ink;
    // THRESH_BINARY keeps values strictly above the threshold, so >= inkThreshold is > inkThreshold - 1.
    cv::threshold(lineLayer, ink, inkThreshold - 1, 255, cv::THRESH_BINARY);
    const cv::Mat skeleton = thinLines(ink);
    std::vector<cv::Point2d> points;
    for (int row = 0; row < skeleton.rows; ++row)
        for (int column = 0; column < skeleton.cols; ++column)
            if (skeleton.at<std::uint8_t>(row, column) != 0) points.emplace_back(column, row);
    return points;
}

std::vector<cv::Point2d> toSmallerImage(const std::vector<cv::Point2d>& points, double factor) {
    if (!std::isfinite(factor) || factor <= 0.0)
        throw std::invalid_argument("toSmallerImage(): 'factor' must be finite and > 0, got " + std::to_string(factor));
    std::vector<cv::Point2d> mapped;
    mapped.reserve(points.size());
    for (const cv::Point2d& point : points)
        mapped.emplace_back((point.x + 0.5) / factor - 0.5, (point.y + 0.5) / factor - 0.5);
    return mapped;
}

std::size_t countWithin(const std::vector<cv::Point2d>& points, const std::vector<cv::Point2d>& reference,
                        double tolerance) {
    if (!std::isfinite(tolerance) || tolerance < 0.0)
        throw std::invalid_argument("countWithin(): 'tolerance' must be finite and >= 0, got " +
                                    std::to_string(tolerance));
    requireFinitePoints(points, "countWithin()", "points");
    requireFinitePoints(reference, "countWithin()", "reference");
    if (reference.empty()) return 0;
    // A cell as wide as the tolerance (or a pixel for tolerance 0) puts every candidate in the 3 x 3 cells around.
    const PointGrid grid(reference, std::max(tolerance, 1.0));
    return std::size_t(std::count_if(points.begin(), points.end(),
                                     [&](const cv::Point2d& point) { return grid.anyWithin(point, tolerance); }));
}

PointSetAgreement agreementFromCounts(std::size_t firstCount, std::size_t firstWithin, std::size_t secondCount,
                                      std::size_t secondWithin) {
    if (firstWithin > firstCount || secondWithin > secondCount)
        throw std::invalid_argument("agreementFromCounts(): a within count exceeds its count (" +
                                    std::to_string(firstWithin) + " of " + std::to_string(firstCount) + ", " +
                                    std::to_string(secondWithin) + " of " + std::to_string(secondCount) + ")");
    PointSetAgreement agreement{firstCount, firstWithin, secondCount, secondWithin, 0.0, 0.0, 0.0};
    agreement.precision = firstCount == 0 ? 1.0 : double(firstWithin) / double(firstCount);
    agreement.recall = secondCount == 0 ? 1.0 : double(secondWithin) / double(secondCount);
    if (firstCount == 0 && secondCount > 0) agreement.recall = 0.0;    // nothing of B was found
    if (secondCount == 0 && firstCount > 0) agreement.precision = 0.0; // all of A is spurious
    const double sum = agreement.precision + agreement.recall;
    agreement.f1 = sum > 0.0 ? 2.0 * agreement.precision * agreement.recall / sum : 0.0;
    return agreement;
}

PointSetAgreement comparePointSets(const std::vector<cv::Point2d>& first, const std::vector<cv::Point2d>& second,
                                   double tolerance) {
    return agreementFromCounts(first.size(), countWithin(first, second, tolerance), second.size(),
                               countWithin(second, first, tolerance));
}

PointSetAgreement compareAcrossSizes(const std::vector<cv::Point2d>& smaller, const std::vector<cv::Point2d>& larger,
                                     double factor, double tolerance) {
    return comparePointSets(smaller, toSmallerImage(larger, factor), tolerance);
}

double smallestF1(const std::vector<PointSetAgreement>& agreements) {
    if (agreements.empty()) throw std::invalid_argument("smallestF1(): 'agreements' is empty");
    double smallest = agreements.front().f1;
    for (const PointSetAgreement& agreement : agreements) smallest = std::min(smallest, agreement.f1);
    return smallest;
}

Reprojection reprojectPoints(const std::vector<cv::Point2d>& points, const cv::Mat& sourceDepth,
                             const PinholeView& source, const cv::Mat& targetDepth, const PinholeView& target,
                             double relativeDepthTolerance, int searchRadius) {
    requireDepth(sourceDepth, source, "sourceDepth");
    requireDepth(targetDepth, target, "targetDepth");
    if (!std::isfinite(relativeDepthTolerance) || relativeDepthTolerance <= 0.0)
        throw std::invalid_argument("reprojectPoints(): 'relativeDepthTolerance' must be finite and > 0, got " +
                                    std::to_string(relativeDepthTolerance));
    if (searchRadius < 0)
        throw std::invalid_argument("reprojectPoints(): 'searchRadius' must be >= 0, got " +
                                    std::to_string(searchRadius));
    requireFinitePoints(points, "reprojectPoints()", "points");
    bool invertible = false;
    const cv::Matx44d sourceViewInverse = source.view.inv(cv::DECOMP_LU, &invertible);
    if (!invertible) throw std::invalid_argument("reprojectPoints(): the source view matrix is singular");
    const cv::Matx44d& projection = source.projection;

    Reprojection result;
    for (const cv::Point2d& point : points) {
        const double depth = nearestSurfaceDepth(sourceDepth, point, searchRadius);
        if (depth <= 0.0) {
            ++result.withoutDepth;
            continue;
        }
        // View-space z is -depth; x and y follow from the two NDC equations ndc * w = row . (x, y, z, 1), with
        // w = row 3 . (x, y, z, 1), a 2 x 2 linear system (exact for any projection, off-centre ones included).
        const double ndcX = (point.x + 0.5) / source.size.width * 2.0 - 1.0;
        const double ndcY = 1.0 - (point.y + 0.5) / source.size.height * 2.0;
        const double z = -depth;
        const cv::Matx22d system(projection(0, 0) - ndcX * projection(3, 0), projection(0, 1) - ndcX * projection(3, 1),
                                 projection(1, 0) - ndcY * projection(3, 0),
                                 projection(1, 1) - ndcY * projection(3, 1));
        const cv::Vec2d right(
            ndcX * (projection(3, 2) * z + projection(3, 3)) - projection(0, 2) * z - projection(0, 3),
            ndcY * (projection(3, 2) * z + projection(3, 3)) - projection(1, 2) * z - projection(1, 3));
        bool solvable = false;
        const cv::Vec2d xy = system.inv(cv::DECOMP_LU, &solvable) * right;
        if (!solvable) throw std::invalid_argument("reprojectPoints(): the source projection matrix is singular");
        const cv::Vec4d world = sourceViewInverse * cv::Vec4d(xy[0], xy[1], z, 1.0);
        const cv::Vec4d targetView = target.view * world;
        const double targetViewDepth = -targetView[2];
        const cv::Vec4d clip = target.projection * targetView;
        if (targetViewDepth <= 0.0 || clip[3] <= 0.0) {
            ++result.outsideFrame;
            continue;
        }
        const cv::Point2d landed((clip[0] / clip[3] + 1.0) * 0.5 * target.size.width - 0.5,
                                 (1.0 - clip[1] / clip[3]) * 0.5 * target.size.height - 0.5);
        if (!(landed.x >= -0.5 && landed.x < target.size.width - 0.5 && landed.y >= -0.5 &&
              landed.y < target.size.height - 0.5)) {
            ++result.outsideFrame;
            continue;
        }
        const double surface = nearestSurfaceDepth(targetDepth, landed, searchRadius);
        if (surface <= 0.0 || std::abs(targetViewDepth - surface) > relativeDepthTolerance * surface) {
            ++result.hiddenInTarget;
            continue;
        }
        result.points.push_back(landed);
    }
    return result;
}

ViewAgreement compareAcrossViews(const std::vector<cv::Point2d>& first, const cv::Mat& firstDepth,
                                 const PinholeView& firstView, const std::vector<cv::Point2d>& second,
                                 const cv::Mat& secondDepth, const PinholeView& secondView, double tolerance,
                                 double relativeDepthTolerance, int searchRadius) {
    ViewAgreement result;
    result.firstInSecond =
        reprojectPoints(first, firstDepth, firstView, secondDepth, secondView, relativeDepthTolerance, searchRadius);
    result.secondInFirst =
        reprojectPoints(second, secondDepth, secondView, firstDepth, firstView, relativeDepthTolerance, searchRadius);
    result.agreement = agreementFromCounts(
        result.firstInSecond.points.size(), countWithin(result.firstInSecond.points, second, tolerance),
        result.secondInFirst.points.size(), countWithin(result.secondInFirst.points, first, tolerance));
    return result;
}

cv::Mat disagreementPicture(cv::Size size, const std::vector<cv::Point2d>& first,
                            const std::vector<cv::Point2d>& second, double tolerance) {
    if (size.width <= 0 || size.height <= 0)
        throw std::invalid_argument("disagreementPicture(): 'size' must not be empty");
    cv::Mat picture(size, CV_8UC4, cv::Scalar(255, 255, 255, 255));
    const auto paint = [&](const std::vector<cv::Point2d>& points, const std::vector<cv::Point2d>& other,
                           const cv::Vec4b& matched, const cv::Vec4b& unmatched) {
        for (const cv::Point2d& point : points) {
            const bool within = countWithin({point}, other, tolerance) == 1;
            const double col = std::round(point.x);
            const double row = std::round(point.y);
            if (col < 0.0 || row < 0.0 || col >= size.width || row >= size.height) continue;
            picture.at<cv::Vec4b>(int(row), int(col)) = within ? matched : unmatched;
        }
    };
    paint(second, first, cv::Vec4b(150, 150, 150, 255), cv::Vec4b(0, 0, 255, 255));
    paint(first, second, cv::Vec4b(0, 0, 0, 255), cv::Vec4b(255, 0, 0, 255));
    return picture;
}

} // namespace inkgraph::bench
