#include "postfx/LineMetrics.h"

#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

namespace inkgraph {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
/** Truth samples are at most this far apart (pixels), so recall by length is exact to a quarter pixel per end. */
constexpr double kTruthSpacing = 0.25;

struct Segment {
    cv::Point2d a;
    cv::Point2d b;
};

double distanceToSegment(const cv::Point2d& p, const Segment& segment) {
    const cv::Point2d along = segment.b - segment.a;
    const double length2 = along.dot(along);
    const double t = length2 > 0.0 ? std::clamp((p - segment.a).dot(along) / length2, 0.0, 1.0) : 0.0;
    const cv::Point2d offset = p - (segment.a + t * along);
    return std::sqrt(offset.dot(offset));
}

double distanceBetween(const cv::Point2d& p, const cv::Point2d& q) { return std::hypot(p.x - q.x, p.y - q.y); }

/** Items (points or segments) bucketed into square cells, so a nearest-item query looks at the cells around the
 *  query point ring by ring and stops once no farther ring can hold anything nearer. */
class UniformGrid {
public:
    /** `bounds`: a box holding every item; the cell size grows with it so the grid stays at most ~1024^2 cells. */
    UniformGrid(const cv::Rect2d& bounds, std::size_t itemCount) {
        const double extent = std::max({bounds.width, bounds.height, 1.0});
        // About two items per cell for evenly spread lines, never finer than 2 px nor coarser than 1024 cells a side.
        const double byCount = extent / std::max(1.0, std::sqrt(double(itemCount)));
        mCellSize = std::max({2.0, byCount, extent / 1024.0});
        mOrigin = bounds.tl();
        mColumns = int(std::floor(bounds.width / mCellSize)) + 1;
        mRows = int(std::floor(bounds.height / mCellSize)) + 1;
        mCells.resize(std::size_t(mColumns) * std::size_t(mRows));
    }

    /** Adds item `index` to every cell the box [low, high] touches. */
    void insert(int index, const cv::Point2d& low, const cv::Point2d& high) {
        const int col0 = columnOf(low.x), col1 = columnOf(high.x);
        const int row0 = rowOf(low.y), row1 = rowOf(high.y);
        for (int row = row0; row <= row1; ++row)
            for (int col = col0; col <= col1; ++col) {
                std::vector<int>& cell = mCells[std::size_t(row) * std::size_t(mColumns) + std::size_t(col)];
                if (cell.empty() || cell.back() != index) cell.push_back(index);
            }
    }

    /** The smallest distance(p, item) over all items, +infinity when there are none. */
    template <typename Distance>
    double nearest(const cv::Point2d& p, const Distance& distance) const {
        // The query's cell, possibly outside the grid; rings nearer than the grid are empty, so start at the grid.
        const long col = long(std::floor((p.x - mOrigin.x) / mCellSize));
        const long row = long(std::floor((p.y - mOrigin.y) / mCellSize));
        const long outside = std::max({0L, -col, col - (mColumns - 1), -row, row - (mRows - 1)});
        const long lastRing = std::max({col, mColumns - 1 - col, row, mRows - 1 - row});
        double best = kInfinity;
        auto visit = [&](long r, long c) {
            if (r < 0 || r >= mRows || c < 0 || c >= mColumns) return;
            for (const int index : mCells[std::size_t(r) * std::size_t(mColumns) + std::size_t(c)])
                best = std::min(best, distance(index));
        };
        for (long ring = outside; ring <= lastRing; ++ring) {
            // p lies in its own cell, so every cell of ring r is at least (r - 1) cells away from it.
            if (ring > 0 && best <= double(ring - 1) * mCellSize) break;
            if (ring == 0) {
                visit(row, col);
                continue;
            }
            const long colLow = std::max(0L, col - ring), colHigh = std::min(long(mColumns) - 1, col + ring);
            for (long c = colLow; c <= colHigh; ++c) {
                visit(row - ring, c);
                visit(row + ring, c);
            }
            const long rowLow = std::max(0L, row - ring + 1), rowHigh = std::min(long(mRows) - 1, row + ring - 1);
            for (long r = rowLow; r <= rowHigh; ++r) {
                visit(r, col - ring);
                visit(r, col + ring);
            }
        }
        return best;
    }

private:
    int columnOf(double x) const { return std::clamp(int(std::floor((x - mOrigin.x) / mCellSize)), 0, mColumns - 1); }
    int rowOf(double y) const { return std::clamp(int(std::floor((y - mOrigin.y) / mCellSize)), 0, mRows - 1); }

    cv::Point2d mOrigin;
    double mCellSize = 1.0;
    int mColumns = 1;
    int mRows = 1;
    std::vector<std::vector<int>> mCells;
};

cv::Rect2d boundsOf(const std::vector<cv::Point2d>& points) {
    cv::Point2d low(kInfinity, kInfinity), high(-kInfinity, -kInfinity);
    for (const cv::Point2d& p : points) {
        low = {std::min(low.x, p.x), std::min(low.y, p.y)};
        high = {std::max(high.x, p.x), std::max(high.y, p.y)};
    }
    return {low, high};
}

/** A distance with the length of truth it stands for (0 for samples that only enter the maximum). */
struct WeightedDistance {
    double distance;
    double weight;
};

/** The value below which `fraction` of the total weight lies (the smallest distance reaching it). */
double weightedPercentile(std::vector<WeightedDistance> values, double fraction) {
    if (values.empty()) return 0.0;
    std::sort(values.begin(), values.end(),
              [](const WeightedDistance& a, const WeightedDistance& b) { return a.distance < b.distance; });
    double total = 0.0;
    for (const WeightedDistance& value : values) total += value.weight;
    if (!(total > 0.0)) return values.back().distance;
    double reached = 0.0;
    for (const WeightedDistance& value : values) {
        reached += value.weight;
        if (reached >= fraction * total) return value.distance;
    }
    return values.back().distance;
}

/** Fills every field from the two sets of distances. `predictedDistances`: one per predicted point;
 *  `truthDistances`: weighted by length; `truthLength`: their total weight. */
LineAccuracy summarise(double tolerance, const std::vector<double>& predictedDistances,
                       std::vector<WeightedDistance> truthDistances, double truthLength, bool hasTruth) {
    LineAccuracy accuracy;
    accuracy.tolerancePixels = tolerance;
    accuracy.predictedCount = predictedDistances.size();
    accuracy.truthSampleCount = truthDistances.size();
    accuracy.truthLength = truthLength;
    const bool hasPrediction = !predictedDistances.empty();

    if (hasPrediction) {
        double sum = 0.0;
        for (const double distance : predictedDistances) {
            accuracy.predictedWithinTolerance += distance <= tolerance;
            sum += distance;
            accuracy.predictedToTruthMax = std::max(accuracy.predictedToTruthMax, distance);
        }
        accuracy.predictedToTruthMean = sum / double(predictedDistances.size());
        std::vector<WeightedDistance> weighted;
        weighted.reserve(predictedDistances.size());
        for (const double distance : predictedDistances) weighted.push_back({distance, 1.0});
        accuracy.predictedToTruthP95 = weightedPercentile(std::move(weighted), 0.95);
    }
    accuracy.spuriousCount = accuracy.predictedCount - accuracy.predictedWithinTolerance;

    if (hasTruth) {
        // Only isolated points (length 0): each counts the same.
        const bool byCount = !(truthLength > 0.0);
        double total = 0.0;
        double sum = 0.0;
        for (WeightedDistance& sample : truthDistances) {
            if (byCount) sample.weight = 1.0;
            total += sample.weight;
            if (sample.weight > 0.0) sum += sample.weight * sample.distance;
            if (sample.distance <= tolerance) accuracy.truthLengthWithinTolerance += sample.weight;
            accuracy.truthToPredictedMax = std::max(accuracy.truthToPredictedMax, sample.distance);
        }
        accuracy.truthToPredictedMean = hasPrediction ? sum / total : kInfinity;
        accuracy.recall = accuracy.truthLengthWithinTolerance / total;
        if (byCount)
            accuracy.truthLengthWithinTolerance = 0.0;
        else
            accuracy.truthLengthWithinTolerance = std::min(accuracy.truthLengthWithinTolerance, truthLength);
        accuracy.truthToPredictedP95 = weightedPercentile(std::move(truthDistances), 0.95);
    } else {
        accuracy.recall = 1.0;
    }
    // The empty cases of the header: nothing drawn is nothing wrong, nothing to find is all found.
    accuracy.precision = !hasPrediction ? 1.0
                         : hasTruth     ? double(accuracy.predictedWithinTolerance) / double(accuracy.predictedCount)
                                        : 0.0;
    const double sumPR = accuracy.precision + accuracy.recall;
    accuracy.f1 = sumPR > 0.0 ? 2.0 * accuracy.precision * accuracy.recall / sumPR : 0.0;
    accuracy.hausdorff = std::max(accuracy.predictedToTruthMax, accuracy.truthToPredictedMax);
    accuracy.chamferMean = 0.5 * (accuracy.predictedToTruthMean + accuracy.truthToPredictedMean);
    return accuracy;
}

void checkTolerance(const char* function, double tolerancePixels) {
    if (!(tolerancePixels >= 0.0) || !std::isfinite(tolerancePixels))
        throw std::invalid_argument(std::string(function) + ": 'tolerancePixels' must be finite and >= 0, got " +
                                    std::to_string(tolerancePixels));
}

bool isFinite(const cv::Point2d& p) { return std::isfinite(p.x) && std::isfinite(p.y); }

void checkLineMask(const char* function, const cv::Mat& mask, const char* name) {
    if (mask.empty() || mask.type() != CV_8UC1)
        throw std::invalid_argument(std::string(function) + ": '" + name + "' must be a non-empty CV_8UC1 mask");
}

} // namespace

LineAccuracy scoreLinePoints(const std::vector<cv::Point2d>& predicted, const std::vector<LinePolyline>& truth,
                             double tolerancePixels) {
    checkTolerance("scoreLinePoints()", tolerancePixels);
    for (const cv::Point2d& p : predicted)
        if (!isFinite(p)) throw std::invalid_argument("scoreLinePoints(): 'predicted' holds a non-finite point");

    // The truth as segments (an isolated point as a segment of length 0), and its samples with their lengths.
    std::vector<Segment> segments;
    std::vector<cv::Point2d> truthPoints;
    std::vector<cv::Point2d> samples;
    std::vector<double> sampleWeights;
    double truthLength = 0.0;
    for (const LinePolyline& polyline : truth) {
        const std::size_t count = polyline.points.size();
        if (count == 0) continue;
        for (const cv::Point2d& p : polyline.points) {
            if (!isFinite(p)) throw std::invalid_argument("scoreLinePoints(): 'truth' holds a non-finite point");
            truthPoints.push_back(p);
            // Vertices enter the maximum only, so line ends are measured.
            samples.push_back(p);
            sampleWeights.push_back(0.0);
        }
        const std::size_t segmentCount = count == 1 ? 1 : (polyline.closed && count > 2 ? count : count - 1);
        for (std::size_t index = 0; index < segmentCount; ++index) {
            const Segment segment{polyline.points[index], polyline.points[(index + 1) % count]};
            segments.push_back(segment);
            const double length = distanceBetween(segment.a, segment.b);
            truthLength += length;
            if (!(length > 0.0)) continue;
            // Midpoints of equal pieces at most kTruthSpacing long, each weighing its piece's length.
            const int pieces = int(std::ceil(length / kTruthSpacing));
            for (int piece = 0; piece < pieces; ++piece) {
                const double t = (piece + 0.5) / pieces;
                samples.push_back(segment.a + t * (segment.b - segment.a));
                sampleWeights.push_back(length / pieces);
            }
        }
    }
    const bool hasTruth = !segments.empty();

    std::vector<double> predictedDistances(predicted.size(), kInfinity);
    if (hasTruth && !predicted.empty()) {
        UniformGrid grid(boundsOf(truthPoints), segments.size());
        for (int index = 0; index < int(segments.size()); ++index) {
            // Long segments go in piece by piece, so they fill the cells along them, not their whole bounding box.
            const Segment& segment = segments[std::size_t(index)];
            const int pieces = std::max(1, int(std::ceil(distanceBetween(segment.a, segment.b) / 2.0)));
            for (int piece = 0; piece < pieces; ++piece) {
                const cv::Point2d a = segment.a + (double(piece) / pieces) * (segment.b - segment.a);
                const cv::Point2d b = segment.a + (double(piece + 1) / pieces) * (segment.b - segment.a);
                grid.insert(index, {std::min(a.x, b.x), std::min(a.y, b.y)}, {std::max(a.x, b.x), std::max(a.y, b.y)});
            }
        }
        cv::parallel_for_(cv::Range(0, int(predicted.size())), [&](const cv::Range& range) {
            for (int index = range.start; index < range.end; ++index) {
                const cv::Point2d& p = predicted[std::size_t(index)];
                predictedDistances[std::size_t(index)] =
                    grid.nearest(p, [&](int segment) { return distanceToSegment(p, segments[std::size_t(segment)]); });
            }
        });
    }

    std::vector<WeightedDistance> truthDistances(samples.size(), WeightedDistance{kInfinity, 0.0});
    for (std::size_t index = 0; index < samples.size(); ++index) truthDistances[index].weight = sampleWeights[index];
    if (hasTruth && !predicted.empty()) {
        UniformGrid grid(boundsOf(predicted), predicted.size());
        for (int index = 0; index < int(predicted.size()); ++index)
            grid.insert(index, predicted[std::size_t(index)], predicted[std::size_t(index)]);
        cv::parallel_for_(cv::Range(0, int(samples.size())), [&](const cv::Range& range) {
            for (int index = range.start; index < range.end; ++index) {
                const cv::Point2d& q = samples[std::size_t(index)];
                truthDistances[std::size_t(index)].distance =
                    grid.nearest(q, [&](int point) { return distanceBetween(q, predicted[std::size_t(point)]); });
            }
        });
    }
    if (!hasTruth) truthDistances.clear();
    return summarise(tolerancePixels, predictedDistances, std::move(truthDistances), truthLength, hasTruth);
}

LineAccuracy scoreLineMasks(const cv::Mat& predicted, const cv::Mat& truth, double tolerancePixels) {
    checkLineMask("scoreLineMasks()", predicted, "predicted");
    checkLineMask("scoreLineMasks()", truth, "truth");
    if (predicted.size() != truth.size())
        throw std::invalid_argument("scoreLineMasks(): 'predicted' and 'truth' must have the same size");
    checkTolerance("scoreLineMasks()", tolerancePixels);

    const cv::Mat predictedSkeleton = thinLines(predicted);
    const cv::Mat truthSkeleton = thinLines(truth);
    std::vector<cv::Point> predictedPixels, truthPixels;
    cv::findNonZero(predictedSkeleton, predictedPixels);
    cv::findNonZero(truthSkeleton, truthPixels);

    // distanceTransform measures to the nearest zero pixel: zeros on the other skeleton.
    auto distancesTo = [](const cv::Mat& skeleton, const std::vector<cv::Point>& from) {
        cv::Mat distance;
        cv::distanceTransform(skeleton == 0, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
        std::vector<double> distances;
        distances.reserve(from.size());
        for (const cv::Point& pixel : from) distances.push_back(distance.at<float>(pixel));
        return distances;
    };
    const bool hasTruth = !truthPixels.empty();
    const bool hasPrediction = !predictedPixels.empty();
    std::vector<double> predictedDistances =
        hasTruth ? distancesTo(truthSkeleton, predictedPixels) : std::vector<double>(predictedPixels.size(), kInfinity);
    std::vector<WeightedDistance> truthDistances;
    if (hasTruth) {
        const std::vector<double> distances = hasPrediction ? distancesTo(predictedSkeleton, truthPixels)
                                                            : std::vector<double>(truthPixels.size(), kInfinity);
        for (const double distance : distances) truthDistances.push_back({distance, 1.0});
    }
    return summarise(tolerancePixels, predictedDistances, std::move(truthDistances), double(truthPixels.size()),
                     hasTruth);
}

cv::Mat thinLines(const cv::Mat& mask) {
    checkLineMask("thinLines()", mask, "mask");
    // One pixel of unset border, so the neighbourhood of every pixel lies in the image.
    cv::Mat set = cv::Mat::zeros(mask.rows + 2, mask.cols + 2, CV_8UC1);
    set(cv::Rect(1, 1, mask.cols, mask.rows)).setTo(1, mask != 0);

    std::vector<cv::Point> candidates;
    cv::findNonZero(set, candidates);
    std::vector<cv::Point> removals;
    bool changed = true;
    while (changed) {
        changed = false;
        for (const int subPass : {0, 1}) {
            removals.clear();
            for (const cv::Point& pixel : candidates) {
                const int x = pixel.x, y = pixel.y;
                if (!set.at<uchar>(y, x)) continue;
                // Neighbours P2..P9 clockwise from north.
                const int p[8] = {set.at<uchar>(y - 1, x),     set.at<uchar>(y - 1, x + 1), set.at<uchar>(y, x + 1),
                                  set.at<uchar>(y + 1, x + 1), set.at<uchar>(y + 1, x),     set.at<uchar>(y + 1, x - 1),
                                  set.at<uchar>(y, x - 1),     set.at<uchar>(y - 1, x - 1)};
                const int neighbours = std::accumulate(p, p + 8, 0);
                if (neighbours < 2 || neighbours > 6) continue;
                int transitions = 0; // 0 -> 1 steps around the ring: 1 means removing keeps it connected
                for (int index = 0; index < 8; ++index) transitions += p[index] == 0 && p[(index + 1) % 8] == 1;
                if (transitions != 1) continue;
                // P2, P4, P6, P8 = p[0], p[2], p[4], p[6]: first pass peels south-east, the second north-west.
                const bool keep = subPass == 0 ? (p[0] * p[2] * p[4] != 0 || p[2] * p[4] * p[6] != 0)
                                               : (p[0] * p[2] * p[6] != 0 || p[0] * p[4] * p[6] != 0);
                if (!keep) removals.push_back(pixel);
            }
            // Removed together after the scan, as the method requires.
            for (const cv::Point& pixel : removals) set.at<uchar>(pixel) = 0;
            changed = changed || !removals.empty();
        }
        std::erase_if(candidates, [&](const cv::Point& pixel) { return set.at<uchar>(pixel) == 0; });
    }
    cv::Mat skeleton = set(cv::Rect(1, 1, mask.cols, mask.rows)) != 0;
    return skeleton;
}

std::vector<cv::Point2d> outputPixelPositions(const LineSkeleton& skeleton, int supersample) {
    if (supersample < 1)
        throw std::invalid_argument("outputPixelPositions(): 'supersample' must be >= 1, got " +
                                    std::to_string(supersample));
    std::vector<cv::Point2d> positions;
    positions.reserve(skeleton.points.size());
    const double scale = 1.0 / supersample;
    for (const LinePoint& point : skeleton.points)
        positions.emplace_back((point.position.x + 0.5) * scale - 0.5, (point.position.y + 0.5) * scale - 0.5);
    return positions;
}

} // namespace inkgraph
