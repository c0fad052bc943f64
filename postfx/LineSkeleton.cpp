#include "postfx/LineSkeleton.h"
#include "postfx/SizeText.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

namespace inkgraph {
namespace {

uchar toByte(float coverage) { return static_cast<uchar>(coverage * 255.0f + 0.5f); }

/** A disc as drawn: coverage clamp(radius + 0.5 - d, 0, 1), i.e. full out to the inner radius (radius - 0.5), then
 *  a one-pixel linear ramp centred on the rim down to 0 at the outer radius (radius + 0.5). */
struct DiscShape {
    explicit DiscShape(float radius)
        : outer(radius + 0.5f), outerSquared(outer * outer),
          innerSquared(radius >= 0.5f ? (radius - 0.5f) * (radius - 0.5f) : -1.0f) {}

    /** Coverage of a pixel centre at squared distance `distanceSquared`; the square root only on the ramp. */
    float coverage(float distanceSquared) const {
        if (distanceSquared <= innerSquared) return 1.0f;
        return std::clamp(outer - std::sqrt(distanceSquared), 0.0f, 1.0f);
    }

    float outer;
    float outerSquared;
    float innerSquared; ///< -1 when the disc has no full interior
};

/** Narrow discs: each point visits every pixel of its bounding box. */
void stampDiscsByPixel(const std::vector<LinePoint>& points, float radius, cv::Mat& canvas) {
    const float lastCol = static_cast<float>(canvas.cols - 1);
    const float lastRow = static_cast<float>(canvas.rows - 1);
    for (const LinePoint& point : points) {
        const DiscShape disc(radius * point.width);
        // Clamped in float first, so a point far off the image cannot overflow the int conversion.
        const float left = std::max(std::ceil(point.position.x - disc.outer), 0.0f);
        const float right = std::min(std::floor(point.position.x + disc.outer), lastCol);
        const float top = std::max(std::ceil(point.position.y - disc.outer), 0.0f);
        const float bottom = std::min(std::floor(point.position.y + disc.outer), lastRow);
        if (left > right || top > bottom) continue;
        const int firstCol = static_cast<int>(left);
        const int endCol = static_cast<int>(right) + 1;
        for (int row = static_cast<int>(top); row <= static_cast<int>(bottom); ++row) {
            const float dy = static_cast<float>(row) - point.position.y;
            const float dySquared = dy * dy;
            uchar* out = canvas.ptr<uchar>(row);
            for (int col = firstCol; col < endCol; ++col) {
                const float dx = static_cast<float>(col) - point.position.x;
                const float distanceSquared = dx * dx + dySquared;
                if (distanceSquared >= disc.outerSquared) continue;
                const uchar value = toByte(disc.coverage(distanceSquared) * point.strength);
                out[col] = std::max(out[col], value);
            }
        }
    }
}

/** Wide discs, row by row: the run of pixels under a disc's full interior is filled at once (a byte maximum the
 *  compiler vectorises), and only the pixels on the one-pixel rim ramp compute a distance. The run ends come from a
 *  square root per row; a pixel there lands on whichever side, since the ramp gives 1 at the inner radius and 0 at
 *  the outer one. */
void stampDiscsByRow(const std::vector<LinePoint>& points, float radius, cv::Mat& canvas) {
    const float lastCol = static_cast<float>(canvas.cols - 1);
    const float lastRow = static_cast<float>(canvas.rows - 1);
    for (const LinePoint& point : points) {
        const DiscShape disc(radius * point.width);
        const float x = point.position.x;
        const float y = point.position.y;
        // Clamped in float first, so a point far off the image cannot overflow the int conversion.
        const float top = std::max(std::ceil(y - disc.outer), 0.0f);
        const float bottom = std::min(std::floor(y + disc.outer), lastRow);
        const uchar fullValue = toByte(point.strength);
        for (int row = static_cast<int>(top); row <= static_cast<int>(bottom); ++row) {
            const float dy = static_cast<float>(row) - y;
            const float dySquared = dy * dy;
            if (dySquared >= disc.outerSquared) continue;
            const float outerHalfWidth = std::sqrt(disc.outerSquared - dySquared);
            const float left = std::max(std::ceil(x - outerHalfWidth), 0.0f);
            const float right = std::min(std::floor(x + outerHalfWidth), lastCol);
            if (left > right) continue;
            // The full run, clipped to [left, right]; empty (fullFirst > fullLast) where the row misses the interior.
            float fullFirst = right + 1.0f;
            float fullLast = right;
            if (dySquared < disc.innerSquared) {
                const float innerHalfWidth = std::sqrt(disc.innerSquared - dySquared);
                fullFirst = std::max(std::ceil(x - innerHalfWidth), left);
                fullLast = std::min(std::floor(x + innerHalfWidth), right);
                if (fullFirst > fullLast) {
                    fullFirst = right + 1.0f;
                    fullLast = right;
                }
            }
            uchar* out = canvas.ptr<uchar>(row);
            auto ramp = [&](int col) {
                const float dx = static_cast<float>(col) - x;
                const uchar value = toByte(disc.coverage(dx * dx + dySquared) * point.strength);
                out[col] = std::max(out[col], value);
            };
            const int firstCol = static_cast<int>(left);
            const int lastColOfRow = static_cast<int>(right);
            const int firstFull = static_cast<int>(fullFirst);
            const int lastFull = static_cast<int>(fullLast);
            for (int col = firstCol; col < std::min(firstFull, lastColOfRow + 1); ++col) ramp(col);
            for (int col = firstFull; col <= lastFull; ++col) out[col] = std::max(out[col], fullValue);
            for (int col = std::max(lastFull + 1, firstCol); col <= lastColOfRow; ++col) ramp(col);
        }
    }
}

/** Many wide discs: every pixel takes the disc of its nearest point only. The nearest point is found by an exact
 *  Euclidean distance transform over the points' pixels (a separable lower envelope of parabolas, after Felzenszwalb
 *  and Huttenlocher 2004, that also tells which site is nearest), so the cost is a few passes over the image whatever
 *  the width or the number of points. Each pixel holding points is one site, represented by its strongest point;
 *  the coverage is then taken from that point's exact sub-pixel position and strength. Nearest is judged between
 *  pixel centres, so where two sites are almost equally near, a pixel may take the point up to ~0.7 px farther: for
 *  the discs this path draws (many pixels wide) that only moves the anti-aliased rim. */
void drawDiscsByNearestPoint(const std::vector<LinePoint>& points, float radius, cv::Mat& canvas) {
    const int rows = canvas.rows;
    const int cols = canvas.cols;
    constexpr int none = -1;

    // Two ints per pixel: 8 bytes x the data size (128 MiB at 4096^2), held only during the call.
    std::vector<int> pointAtSite(static_cast<size_t>(rows) * cols, none);
    for (size_t index = 0; index < points.size(); ++index) {
        const cv::Point2f& position = points[index].position;
        // A point off the image is represented by the nearest pixel on it; its coverage still uses its own position.
        const int col = static_cast<int>(std::lround(std::clamp(position.x, 0.0f, static_cast<float>(cols - 1))));
        const int row = static_cast<int>(std::lround(std::clamp(position.y, 0.0f, static_cast<float>(rows - 1))));
        int& site = pointAtSite[static_cast<size_t>(row) * cols + col];
        if (site == none || points[index].strength > points[site].strength) site = static_cast<int>(index);
    }

    // Pass 1, down each column: the row of the nearest site in the same column.
    std::vector<int> nearestSiteRow(static_cast<size_t>(rows) * cols, none);
    std::vector<int> lastSiteRow(cols, none);
    for (int row = 0; row < rows; ++row) {
        const int* sites = &pointAtSite[static_cast<size_t>(row) * cols];
        int* nearest = &nearestSiteRow[static_cast<size_t>(row) * cols];
        for (int col = 0; col < cols; ++col) {
            if (sites[col] != none) lastSiteRow[col] = row;
            nearest[col] = lastSiteRow[col];
        }
    }
    std::fill(lastSiteRow.begin(), lastSiteRow.end(), none);
    for (int row = rows - 1; row >= 0; --row) {
        const int* sites = &pointAtSite[static_cast<size_t>(row) * cols];
        int* nearest = &nearestSiteRow[static_cast<size_t>(row) * cols];
        for (int col = 0; col < cols; ++col) {
            if (sites[col] != none) lastSiteRow[col] = row;
            const int below = lastSiteRow[col];
            if (below != none && (nearest[col] == none || below - row < row - nearest[col])) nearest[col] = below;
        }
    }

    // Pass 2, along each row: the lower envelope of the parabolas (x - col)^2 + (row - siteRow(col))^2.
    const DiscShape disc(radius);
    // A site is its point rounded to a pixel after clamping onto the image (which brings it no farther from any
    // pixel), so a pixel farther than the outer radius + sqrt(0.5) from the nearest site centre gets no coverage.
    const double reach = static_cast<double>(disc.outer) + 0.7072;
    const double reachSquared = reach * reach;
    std::vector<int> envelopeCols(cols);
    std::vector<double> envelopeStarts(cols);
    std::vector<double> heights(cols);
    for (int row = 0; row < rows; ++row) {
        const int* nearest = &nearestSiteRow[static_cast<size_t>(row) * cols];
        int count = 0;
        for (int col = 0; col < cols; ++col) {
            if (nearest[col] == none) continue;
            const double dy = row - nearest[col];
            heights[col] = dy * dy;
            double start = -std::numeric_limits<double>::infinity();
            while (count > 0) {
                const int previous = envelopeCols[count - 1];
                start = ((heights[col] + double(col) * col) - (heights[previous] + double(previous) * previous)) /
                        (2.0 * (col - previous));
                if (start > envelopeStarts[count - 1]) break;
                --count;
                start = -std::numeric_limits<double>::infinity();
            }
            envelopeCols[count] = col;
            envelopeStarts[count] = start;
            ++count;
        }
        if (count == 0) continue; // no site in the whole image
        uchar* out = canvas.ptr<uchar>(row);
        int segment = 0;
        for (int col = 0; col < cols; ++col) {
            while (segment + 1 < count && envelopeStarts[segment + 1] <= col) ++segment;
            const int siteCol = envelopeCols[segment];
            const double dx = col - siteCol;
            if (dx * dx + heights[siteCol] > reachSquared) continue;
            const int siteRow = nearest[siteCol];
            const LinePoint& point = points[pointAtSite[static_cast<size_t>(siteRow) * cols + siteCol]];
            const float px = static_cast<float>(col) - point.position.x;
            const float py = static_cast<float>(row) - point.position.y;
            const float coverage = disc.coverage(px * px + py * py);
            if (coverage > 0.0f) out[col] = toByte(coverage * point.strength);
        }
    }
}

/** Rough costs of the three ways to draw, measured on the 2-core 2.3 GHz development VM; strokeLines() takes the
 *  cheapest for the skeleton at hand (only their ratios matter). */
constexpr double widestBoxByPixel = 24.0;         ///< bounding-box sides up to this are stamped pixel by pixel
constexpr double nanosecondsPerBoxPixel = 1.5;    ///< stampDiscsByPixel, per pixel of each disc's bounding box
constexpr double nanosecondsPerDiscRow = 30.0;    ///< stampDiscsByRow, per row of each disc
constexpr double nanosecondsPerRunPixel = 0.1;    ///< stampDiscsByRow, per pixel of each row's run
constexpr double nanosecondsPerImagePixel = 15.0; ///< drawDiscsByNearestPoint, per pixel of the data buffer

} // namespace

LineSkeleton skeletonFromMask(const cv::Mat& mask) {
    if (mask.empty() || mask.type() != CV_8UC1)
        throw std::invalid_argument("skeletonFromMask(): 'mask' must be a non-empty CV_8UC1");
    LineSkeleton skeleton;
    skeleton.mask = cv::Mat::zeros(mask.size(), CV_8UC1);
    skeleton.points.reserve(static_cast<size_t>(cv::countNonZero(mask)));
    for (int row = 0; row < mask.rows; ++row) {
        const uchar* in = mask.ptr<uchar>(row);
        uchar* out = skeleton.mask.ptr<uchar>(row);
        int col = 0;
        auto take = [&](int at) {
            if (in[at] == 0) return;
            out[at] = 255;
            skeleton.points.push_back({{static_cast<float>(at), static_cast<float>(row)}, in[at] / 255.0f});
        };
        // Line masks are nearly all zero: skip them eight at a time.
        for (; col + 8 <= mask.cols; col += 8) {
            std::uint64_t word;
            std::memcpy(&word, in + col, sizeof word);
            if (word == 0) continue;
            for (int offset = 0; offset < 8; ++offset) take(col + offset);
        }
        for (; col < mask.cols; ++col) take(col);
    }
    return skeleton;
}

cv::Mat strokeLines(const LineSkeleton& skeleton, float widthPixels, int supersample) {
    const cv::Mat& mask = skeleton.mask;
    if (mask.empty() || mask.type() != CV_8UC1)
        throw std::invalid_argument("strokeLines(): 'skeleton.mask' must be a non-empty CV_8UC1");
    if (!std::isfinite(widthPixels) || widthPixels <= 0.0f)
        throw std::invalid_argument("strokeLines(): 'widthPixels' must be finite and positive");
    if (supersample < 1) throw std::invalid_argument("strokeLines(): 'supersample' must be at least 1");
    if (mask.cols % supersample != 0 || mask.rows % supersample != 0)
        throw std::invalid_argument("strokeLines(): 'supersample' (" + std::to_string(supersample) +
                                    ") must divide the size of 'skeleton.mask' (" + sizeText(mask.size()) + ")");
    bool uniformWidth = true;
    for (const LinePoint& point : skeleton.points) {
        if (!std::isfinite(point.position.x) || !std::isfinite(point.position.y) || !(point.strength > 0.0f) ||
            point.strength > 1.0f || !(point.width > 0.0f) || point.width > 1.0f)
            throw std::invalid_argument(
                "strokeLines(): 'skeleton.points' must have finite positions and strengths and widths in (0, 1]");
        uniformWidth = uniformWidth && point.width == 1.0f;
    }

    const float radius = 0.5f * widthPixels * static_cast<float>(supersample);
    cv::Mat canvas = cv::Mat::zeros(mask.size(), CV_8UC1);
    const double boxSide = 2.0 * std::ceil(static_cast<double>(radius) + 0.5) + 1.0;
    const double pointCount = static_cast<double>(skeleton.points.size());
    const bool byPixel = boxSide <= widestBoxByPixel;
    const double stampCost = byPixel
                                 ? pointCount * boxSide * boxSide * nanosecondsPerBoxPixel
                                 : pointCount * boxSide * (nanosecondsPerDiscRow + boxSide * nanosecondsPerRunPixel);
    // The nearest-point path draws one disc size; varying widths are stamped.
    if (uniformWidth && stampCost > nanosecondsPerImagePixel * static_cast<double>(mask.total()))
        drawDiscsByNearestPoint(skeleton.points, radius, canvas);
    else if (byPixel)
        stampDiscsByPixel(skeleton.points, radius, canvas);
    else
        stampDiscsByRow(skeleton.points, radius, canvas);

    if (supersample == 1) return canvas;
    cv::Mat lines;
    cv::resize(canvas, lines, cv::Size(mask.cols / supersample, mask.rows / supersample), 0.0, 0.0, cv::INTER_AREA);
    return lines;
}

} // namespace inkgraph
