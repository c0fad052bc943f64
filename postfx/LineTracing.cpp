#include "postfx/LineTracing.h"

#include <opencv2/core/check.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace inkgraph {
namespace {

// The eight directions, clockwise from north; bit d of a neighbourhood or link byte is direction d.
constexpr int kNorth = 0, kNorthEast = 1, kEast = 2, kSouthEast = 3, kSouth = 4, kSouthWest = 5, kWest = 6,
              kNorthWest = 7;
constexpr std::array<int, 8> kColStep = {0, 1, 1, 1, 0, -1, -1, -1};
constexpr std::array<int, 8> kRowStep = {-1, -1, 0, 1, 1, 1, 0, -1};

constexpr bool hasBit(unsigned bits, int direction) { return (bits >> direction) & 1u; }
constexpr int opposite(int direction) { return (direction + 4) & 7; }

/** The 8-neighbourhood byte of a pixel in a padded 0/1 image (one unset pixel of border all round). */
unsigned neighbourhood(const uchar* pixel, std::ptrdiff_t stride) {
    unsigned bits = 0;
    for (int direction = 0; direction < 8; ++direction)
        bits |= unsigned(pixel[kRowStep[direction] * stride + kColStep[direction]] != 0) << direction;
    return bits;
}

/** The links of a pixel with neighbourhood `bits`: every 4-neighbour, and a diagonal neighbour only where neither
 *  pixel beside both is set (else two 4-links already join them), so staircases make no spurious junctions. */
constexpr unsigned linksOf(unsigned bits) {
    unsigned links = bits & ((1u << kNorth) | (1u << kEast) | (1u << kSouth) | (1u << kWest));
    for (const int diagonal : {kNorthEast, kSouthEast, kSouthWest, kNorthWest}) {
        const int before = (diagonal + 7) & 7, after = (diagonal + 1) & 7;
        if (hasBit(bits, diagonal) && !hasBit(bits, before) && !hasBit(bits, after)) links |= 1u << diagonal;
    }
    return links;
}

constexpr std::array<uchar, 256> makeLinkTable() {
    std::array<uchar, 256> table{};
    for (unsigned bits = 0; bits < 256; ++bits) table[bits] = static_cast<uchar>(linksOf(bits));
    return table;
}
constexpr std::array<uchar, 256> kLinks = makeLinkTable();

/** Whether a set pixel with neighbourhood `bits` may be removed in thinning: it is simple (Yokoi's 8-connectivity
 *  number sum over the 4-neighbours k of (1 - x_k) - (1 - x_k)(1 - x_k+1)(1 - x_k+2) is 1, so removing it changes
 *  neither the 8-connected shapes nor the 4-connected background) and it is not an end (>= 2 set neighbours). */
constexpr bool isRemovable(unsigned bits) {
    int connectivity = 0;
    for (int k = 0; k < 8; k += 2) {
        const int clear0 = !hasBit(bits, k), clear1 = !hasBit(bits, (k + 1) & 7), clear2 = !hasBit(bits, (k + 2) & 7);
        connectivity += clear0 - clear0 * clear1 * clear2;
    }
    return connectivity == 1 && std::popcount(bits) >= 2;
}

constexpr std::array<bool, 256> makeRemovableTable() {
    std::array<bool, 256> table{};
    for (unsigned bits = 0; bits < 256; ++bits) table[bits] = isRemovable(bits);
    return table;
}
constexpr std::array<bool, 256> kRemovable = makeRemovableTable();

void checkMask(const char* function, const cv::Mat& mask, const char* name) {
    if (mask.empty()) throw std::invalid_argument(std::string(function) + ": '" + name + "' must not be empty");
    if (mask.type() != CV_8UC1)
        throw std::invalid_argument(std::string(function) + ": '" + name + "' must be CV_8UC1, got " +
                                    cv::typeToString(mask.type()));
}

void checkTolerance(const char* function, double tolerance, const char* name) {
    if (!std::isfinite(tolerance) || tolerance < 0.0)
        throw std::invalid_argument(std::string(function) + ": '" + name + "' must be finite and >= 0, got " +
                                    std::to_string(tolerance));
}

/** A padded copy with 255 where `mask` >= threshold, 0 elsewhere and on the one-pixel border (so neighbours never
 *  leave the image), and its set pixels as offsets from its first byte, in raster order. */
cv::Mat paddedBinary(const cv::Mat& mask, uchar threshold, std::vector<std::ptrdiff_t>& setPixels) {
    cv::Mat padded = cv::Mat::zeros(mask.rows + 2, mask.cols + 2, CV_8UC1);
    cv::Mat inside = padded(cv::Rect(1, 1, mask.cols, mask.rows));
    cv::compare(mask, threshold, inside, cv::CMP_GE); // writes into `padded`: the size and type already match
    // Eight bytes at a time: line masks are mostly empty, so most words are skipped at once.
    const std::ptrdiff_t stride = static_cast<std::ptrdiff_t>(padded.step1());
    setPixels.clear();
    for (int row = 1; row <= mask.rows; ++row) {
        const uchar* pixels = padded.ptr<uchar>(row);
        const int end = mask.cols + 2;
        int col = 0;
        for (; col + 8 <= end; col += 8) {
            std::uint64_t word;
            std::memcpy(&word, pixels + col, sizeof word);
            if (word == 0) continue;
            for (int offset = 0; offset < 8; ++offset)
                if (pixels[col + offset]) setPixels.push_back(row * stride + col + offset);
        }
        for (; col < end; ++col)
            if (pixels[col]) setPixels.push_back(row * stride + col);
    }
    return padded;
}

/** The mean position of the sub-pixel points of each pixel, by row: O(rows + points log points) to build, a short
 *  binary search in one row to look up. */
class PixelPositions {
public:
    PixelPositions(const std::vector<LinePoint>& points, cv::Size size) : mRowStart(std::size_t(size.height) + 1, 0) {
        struct Sample {
            int row, col;
            double x, y;
        };
        std::vector<Sample> samples;
        samples.reserve(points.size());
        const double colLimit = size.width - 0.5, rowLimit = size.height - 0.5;
        for (std::size_t index = 0; index < points.size(); ++index) {
            const double x = points[index].position.x, y = points[index].position.y;
            if (!std::isfinite(x) || !std::isfinite(y))
                throw std::invalid_argument("traceSkeleton(): 'skeleton.points' [" + std::to_string(index) +
                                            "] has a non-finite position");
            // Compared in floating point first, so a point far off the image cannot overflow the conversion.
            if (!(x >= -0.5 && x < colLimit && y >= -0.5 && y < rowLimit)) continue;
            samples.push_back({static_cast<int>(std::floor(y + 0.5)), static_cast<int>(std::floor(x + 0.5)), x, y});
        }
        // Counting sort by row, then by column within each row; then one mean per pixel.
        std::vector<std::size_t> rowCount(std::size_t(size.height) + 1, 0);
        for (const Sample& sample : samples) ++rowCount[std::size_t(sample.row) + 1];
        for (std::size_t row = 1; row < rowCount.size(); ++row) rowCount[row] += rowCount[row - 1];
        std::vector<Sample> byRow(samples.size());
        {
            std::vector<std::size_t> next(rowCount.begin(), rowCount.end() - 1);
            for (const Sample& sample : samples) byRow[next[std::size_t(sample.row)]++] = sample;
        }
        mEntries.reserve(byRow.size());
        for (int row = 0; row < size.height; ++row) {
            const auto begin = byRow.begin() + std::ptrdiff_t(rowCount[std::size_t(row)]);
            const auto end = byRow.begin() + std::ptrdiff_t(rowCount[std::size_t(row) + 1]);
            std::sort(begin, end, [](const Sample& a, const Sample& b) { return a.col < b.col; });
            for (auto it = begin; it != end;) {
                double sumX = 0.0, sumY = 0.0;
                int count = 0;
                const int col = it->col;
                for (; it != end && it->col == col; ++it, ++count) {
                    sumX += it->x;
                    sumY += it->y;
                }
                mEntries.push_back({col, cv::Point2d(sumX / count, sumY / count)});
            }
            mRowStart[std::size_t(row) + 1] = mEntries.size();
        }
    }

    /** The pixel's mean sample position, or its centre when no sample rounds to it. */
    cv::Point2d at(int col, int row) const {
        const auto begin = mEntries.begin() + std::ptrdiff_t(mRowStart[std::size_t(row)]);
        const auto end = mEntries.begin() + std::ptrdiff_t(mRowStart[std::size_t(row) + 1]);
        const auto found = std::lower_bound(begin, end, col, [](const Entry& entry, int c) { return entry.col < c; });
        if (found != end && found->col == col) return found->position;
        return {double(col), double(row)};
    }

private:
    struct Entry {
        int col;
        cv::Point2d position;
    };
    std::vector<std::size_t> mRowStart; ///< entries of row r: [mRowStart[r], mRowStart[r + 1])
    std::vector<Entry> mEntries;
};

double squaredDistanceToSegment(const cv::Point2d& point, const cv::Point2d& a, const cv::Point2d& b) {
    const cv::Point2d ab = b - a, ap = point - a;
    const double lengthSquared = ab.dot(ab);
    if (lengthSquared == 0.0) return ap.dot(ap);
    const double t = std::clamp(ap.dot(ab) / lengthSquared, 0.0, 1.0);
    const cv::Point2d offset = ap - t * ab;
    return offset.dot(offset);
}

/** Marks in `keep` the vertices Ramer-Douglas-Peucker keeps between `first` and `last` (both kept by the caller),
 *  with an explicit stack so that long chains cannot overflow the call stack. */
void markDouglasPeucker(const std::vector<cv::Point2d>& points, std::size_t first, std::size_t last,
                        double toleranceSquared, std::vector<char>& keep) {
    std::vector<std::pair<std::size_t, std::size_t>> ranges{{first, last}};
    while (!ranges.empty()) {
        const auto [begin, end] = ranges.back();
        ranges.pop_back();
        if (end <= begin + 1) continue;
        double farthest = -1.0;
        std::size_t farthestIndex = begin;
        const cv::Point2d& a = points[begin % points.size()];
        const cv::Point2d& b = points[end % points.size()];
        for (std::size_t index = begin + 1; index < end; ++index) {
            const double distance = squaredDistanceToSegment(points[index], a, b);
            if (distance > farthest) {
                farthest = distance;
                farthestIndex = index;
            }
        }
        if (farthest <= toleranceSquared) continue;
        keep[farthestIndex] = 1;
        ranges.emplace_back(begin, farthestIndex);
        ranges.emplace_back(farthestIndex, end);
    }
}

/** simplifyPolyline() on points already checked, in double precision. */
Polyline simplifyPoints(const std::vector<cv::Point2d>& points, bool closed, double tolerance, bool keepFirstOfClosed) {
    Polyline result;
    result.closed = closed;
    const std::size_t count = points.size();
    auto toFloat = [](const cv::Point2d& p) { return cv::Point2f(static_cast<float>(p.x), static_cast<float>(p.y)); };
    if (count <= 2) {
        for (const cv::Point2d& point : points) result.points.push_back(toFloat(point));
        return result;
    }
    // Compared squared: no square root per point.
    const double toleranceSquared = tolerance * tolerance;
    std::vector<char> keep(count, 0);
    keep[0] = 1;
    if (!closed) {
        keep[count - 1] = 1;
        markDouglasPeucker(points, 0, count - 1, toleranceSquared, keep);
    } else {
        // Split at the first vertex and the one farthest from it; index `count` stands for vertex 0 again.
        std::size_t farthestIndex = 0;
        double farthest = 0.0;
        for (std::size_t index = 1; index < count; ++index) {
            const cv::Point2d offset = points[index] - points[0];
            const double distance = offset.dot(offset);
            if (distance > farthest) {
                farthest = distance;
                farthestIndex = index;
            }
        }
        if (farthestIndex == 0) { // every vertex on the first: a dot
            result.points.push_back(toFloat(points[0]));
            return result;
        }
        keep[farthestIndex] = 1;
        markDouglasPeucker(points, 0, farthestIndex, toleranceSquared, keep);
        markDouglasPeucker(points, farthestIndex, count, toleranceSquared, keep);
        std::size_t keptCount = std::size_t(std::count(keep.begin(), keep.end(), 1));
        if (!keepFirstOfClosed && keptCount >= 4) {
            // The first vertex may go when every point from the kept vertex before it round to the one after it
            // stays within tolerance of the segment joining those two.
            std::size_t previous = count - 1, next = 1;
            while (!keep[previous]) --previous;
            while (!keep[next]) ++next;
            bool holds = true;
            for (std::size_t index = previous + 1; index <= count + next - 1 && holds; ++index)
                holds =
                    squaredDistanceToSegment(points[index % count], points[previous], points[next]) <= toleranceSquared;
            if (holds) {
                keep[0] = 0;
                // Start at the next kept vertex so the order round the loop is unchanged.
                for (std::size_t step = 0; step < count; ++step) {
                    const std::size_t index = (next + step) % count;
                    if (keep[index]) result.points.push_back(toFloat(points[index]));
                }
                return result;
            }
        }
    }
    for (std::size_t index = 0; index < count; ++index)
        if (keep[index]) result.points.push_back(toFloat(points[index]));
    return result;
}

} // namespace

cv::Mat thinToSkeleton(const cv::Mat& mask, uchar threshold) {
    checkMask("thinToSkeleton()", mask, "mask");
    // `remaining`: the set pixels in raster order; thinning only ever removes pixels.
    std::vector<std::ptrdiff_t> remaining;
    cv::Mat set = paddedBinary(mask, threshold, remaining);
    const std::ptrdiff_t stride = static_cast<std::ptrdiff_t>(set.step1());
    uchar* const base = set.ptr<uchar>(0);

    std::vector<std::ptrdiff_t> candidates;
    bool changed = true;
    while (changed) {
        changed = false;
        for (const int side : {kNorth, kSouth, kEast, kWest}) {
            const std::ptrdiff_t sideOffset = kRowStep[std::size_t(side)] * stride + kColStep[std::size_t(side)];
            // The border pixels of this side as they are now, so that a sub-pass peels one layer only.
            candidates.clear();
            for (const std::ptrdiff_t offset : remaining) {
                const uchar* pixel = base + offset;
                if (*pixel != 0 && pixel[sideOffset] == 0 && kRemovable[neighbourhood(pixel, stride)])
                    candidates.push_back(offset);
            }
            // Removed one by one, each only if still removable: every removal keeps the topology.
            for (const std::ptrdiff_t offset : candidates) {
                uchar* pixel = base + offset;
                if (kRemovable[neighbourhood(pixel, stride)]) {
                    *pixel = 0;
                    changed = true;
                }
            }
        }
        std::erase_if(remaining, [&](std::ptrdiff_t offset) { return base[offset] == 0; });
    }
    cv::Mat skeleton;
    cv::compare(set(cv::Rect(1, 1, mask.cols, mask.rows)), 0, skeleton, cv::CMP_NE);
    return skeleton;
}

std::vector<PixelChain> tracePixelChains(const LineSkeleton& skeleton) {
    checkMask("tracePixelChains()", skeleton.mask, "skeleton.mask");
    const cv::Mat& mask = skeleton.mask;
    const PixelPositions positions(skeleton.points, mask.size());

    // The on-pixels in raster order, and the links of each.
    std::vector<std::ptrdiff_t> onPixels;
    cv::Mat links = paddedBinary(mask, 1, onPixels);
    const std::ptrdiff_t stride = static_cast<std::ptrdiff_t>(links.step1());
    std::array<std::ptrdiff_t, 8> step{};
    for (std::size_t direction = 0; direction < 8; ++direction)
        step[direction] = kRowStep[direction] * stride + kColStep[direction];
    // Each pixel's links from the 0/255 image, all read before any is written over its pixel (the off pixels stay
    // 0), then copied whole, so neither image is cleared first.
    {
        std::vector<uchar> pixelLinks(onPixels.size());
        uchar* const onBase = links.ptr<uchar>(0);
        for (std::size_t index = 0; index < onPixels.size(); ++index)
            pixelLinks[index] = kLinks[neighbourhood(onBase + onPixels[index], stride)];
        for (std::size_t index = 0; index < onPixels.size(); ++index) onBase[onPixels[index]] = pixelLinks[index];
    }
    cv::Mat remaining = links.clone(); // `links`: every pixel's full links; `remaining`: the links not yet traced
    uchar* const remainingBase = remaining.ptr<uchar>(0);
    const uchar* const linkBase = links.ptr<uchar>(0);
    auto degree = [&](std::ptrdiff_t offset) { return std::popcount(unsigned(linkBase[offset])); };
    auto pixelOf = [&](std::ptrdiff_t offset) { return cv::Point(int(offset % stride) - 1, int(offset / stride) - 1); };

    std::vector<PixelChain> chains;
    PixelChain chain;
    auto add = [&](std::ptrdiff_t offset) {
        const cv::Point pixel = pixelOf(offset);
        chain.pixels.push_back(pixel);
        chain.positions.push_back(positions.at(pixel.x, pixel.y));
    };
    auto begin = [&](std::ptrdiff_t offset) {
        chain = {};
        add(offset);
    };
    // Follows untraced links from `start` through pixels of degree 2, clearing each link at both ends, until it
    // reaches an end or junction (or, round a loop, a pixel with no untraced link left). Returns the last pixel.
    auto walk = [&](std::ptrdiff_t start, int direction) {
        std::ptrdiff_t current = start;
        for (;;) {
            const std::ptrdiff_t next = current + step[std::size_t(direction)];
            remainingBase[current] &= uchar(~(1u << direction));
            remainingBase[next] &= uchar(~(1u << opposite(direction)));
            current = next;
            if (degree(current) != 2 || remainingBase[current] == 0) return current;
            add(current);
            direction = std::countr_zero(unsigned(remainingBase[current]));
        }
    };

    // Chains from every end and junction.
    for (const std::ptrdiff_t start : onPixels) {
        if (degree(start) == 2) continue;
        while (remainingBase[start] != 0) {
            begin(start);
            const std::ptrdiff_t end = walk(start, std::countr_zero(unsigned(remainingBase[start])));
            if (end == start) {
                chain.closed = true; // a loop back to its junction, starting there
            } else {
                add(end);
            }
            chains.push_back(std::move(chain));
        }
    }
    // Loops with no end or junction, from their first pixel in raster order.
    for (const std::ptrdiff_t start : onPixels) {
        if (remainingBase[start] == 0) continue;
        begin(start);
        walk(start, std::countr_zero(unsigned(remainingBase[start])));
        chain.closed = true;
        chain.anchored = false;
        chains.push_back(std::move(chain));
    }
    // Isolated pixels: dots.
    for (const std::ptrdiff_t pixel : onPixels) {
        if (linkBase[pixel] != 0) continue;
        begin(pixel);
        chains.push_back(std::move(chain));
    }
    return chains;
}

std::vector<Polyline> traceSkeleton(const LineSkeleton& skeleton, const TraceSettings& settings) {
    checkMask("traceSkeleton()", skeleton.mask, "skeleton.mask");
    checkTolerance("traceSkeleton()", settings.tolerancePixels, "settings.tolerancePixels");
    std::vector<Polyline> polylines;
    for (const PixelChain& chain : tracePixelChains(skeleton)) {
        if (chain.positions.size() == 1) {
            polylines.push_back({{cv::Point2f(chain.positions.front())}, false});
            continue;
        }
        // A loop's raster-order start may go when the loop holds without it; a junction is always kept.
        polylines.push_back(simplifyPoints(chain.positions, chain.closed, settings.tolerancePixels, chain.anchored));
    }
    return polylines;
}

std::vector<Polyline> traceMask(const cv::Mat& mask, const TraceSettings& settings) {
    checkMask("traceMask()", mask, "mask");
    checkTolerance("traceMask()", settings.tolerancePixels, "settings.tolerancePixels");
    return traceSkeleton({thinToSkeleton(mask, settings.maskThreshold), {}}, settings);
}

Polyline simplifyPolyline(const Polyline& polyline, double tolerancePixels, bool keepFirstOfClosed) {
    checkTolerance("simplifyPolyline()", tolerancePixels, "tolerancePixels");
    std::vector<cv::Point2d> points;
    points.reserve(polyline.points.size());
    for (std::size_t index = 0; index < polyline.points.size(); ++index) {
        const cv::Point2f& point = polyline.points[index];
        if (!std::isfinite(point.x) || !std::isfinite(point.y))
            throw std::invalid_argument("simplifyPolyline(): 'polyline' point " + std::to_string(index) +
                                        " is not finite");
        points.emplace_back(point.x, point.y);
    }
    return simplifyPoints(points, polyline.closed, tolerancePixels, keepFirstOfClosed);
}

} // namespace inkgraph
