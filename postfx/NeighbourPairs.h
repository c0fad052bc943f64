#pragma once
/** @file Internal to the postfx line kernels: one pass over every 4-neighbour pair of a depth buffer that marks the
 *  nearer pixel of each depth break and lets a kernel mark pairs on one surface (a sign change, a crease).
 *
 *  Speed: nearly every pair of a frame is plain background or plain surface. Each row is therefore cut into blocks
 *  of `blockWidth` + 1 columns, summarised once per row with SIMD (OpenCV's universal intrinsics); a block whose two
 *  rows are all background, or all one surface on which the kernel's summary says nothing can fire, is skipped.
 *  Only the remaining blocks are classified pair by pair (a fixed-width loop the compiler vectorises), and only the
 *  pairs flagged there take the scalar path that writes the skeleton. */

#include "postfx/LineSkeleton.h"

#include <opencv2/core/hal/intrin.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

namespace inkgraph::detail {

/** What a kernel decides about a flagged pair (a, b) on one surface, b being a's right or lower neighbour. */
struct PairMark {
    enum Pixel : unsigned char { None, A, B };
    Pixel pixel = None; ///< which pixel is marked
    float along = 0.5f; ///< the point at a + along x (b - a), along in [0, 1]
};

/** Throws std::invalid_argument "<function>(): '<name>' must be finite and non-negative" unless it is. */
inline void requireFiniteNonNegative(float value, const char* function, const char* name) {
    if (!std::isfinite(value) || value < 0.0f)
        throw std::invalid_argument(std::string(function) + "(): '" + name + "' must be finite and non-negative");
}

enum class DepthBreaks { Mark, Skip };

/** A pair's class, branch-free: bit 0 = a depth break (exactly isDepthBreak()), bit 1 = both pixels on one surface
 *  and the kernel's cheap test `surfaceEvent` fired. */
inline unsigned char classifyPair(float depthA, float depthB, float relativeJump, bool surfaceEvent) {
    const bool coveredA = depthA > 0.0f;
    const bool coveredB = depthB > 0.0f;
    const bool both = coveredA & coveredB;
    const bool jump = std::abs(depthA - depthB) > relativeJump * std::min(depthA, depthB);
    const bool depthBreak = (coveredA ^ coveredB) | (both & jump);
    return static_cast<unsigned char>(depthBreak | ((both & !depthBreak & surfaceEvent) << 1));
}

/** A block covers columns col .. col + blockWidth of a row: its pairs are (c, c + 1) and (c, c below) for c from
 *  col to col + blockWidth - 1, so neighbouring blocks share one column. Four SIMD vectors of four floats. */
constexpr int blockWidth = 16;

/** The depths of one row's block. */
struct DepthSummary {
    float lowest = 0.0f;
    float highest = 0.0f;
    // Words rather than bools: two byte stores read back as one word stall store forwarding on x86.
    std::uint32_t covered = 0; ///< every value > 0 (so none is background, negative or NaN)
    std::uint32_t blank = 0;   ///< every value is +0 (background)
};

/** Summarises `depths[0 .. blockWidth]` into `summary`. */
inline void summarizeDepths(const float* depths, DepthSummary& summary) {
    const cv::v_float32x4 zero = cv::v_setzero_f32();
    cv::v_float32x4 lowest = cv::v_load(depths);
    cv::v_float32x4 highest = lowest;
    cv::v_float32x4 covered = lowest > zero; // false for NaN, which min and max would drop
    cv::v_uint32x4 bits = cv::v_reinterpret_as_u32(lowest);
    for (int offset = 4; offset < blockWidth; offset += 4) {
        const cv::v_float32x4 values = cv::v_load(depths + offset);
        lowest = cv::v_min(lowest, values);
        highest = cv::v_max(highest, values);
        covered = covered & (values > zero);
        bits = bits | cv::v_reinterpret_as_u32(values);
    }
    const float last = depths[blockWidth];
    summary.blank = !cv::v_check_any(bits != cv::v_setzero_u32()) && std::bit_cast<std::uint32_t>(last) == 0;
    summary.covered = cv::v_check_all(covered) && last > 0.0f;
    if (!summary.covered) return; // the range is only read for covered blocks
    summary.lowest = std::min(cv::v_reduce_min(lowest), last);
    summary.highest = std::max(cv::v_reduce_max(highest), last);
}

/** True when no two depths of the two rows' block make a depth break: all are surface and highest - lowest <=
 *  relativeJump x lowest, which bounds every pair's |a - b| by relativeJump x min(a, b). Rounding is monotonic, so
 *  the bound holds for the float test in classifyPair too; an infinite depth fails it. */
inline bool isOneSurface(const DepthSummary& upper, const DepthSummary& lower, float relativeJump) {
    if (!upper.covered || !lower.covered) return false;
    const float lowest = std::min(upper.lowest, lower.lowest);
    const float highest = std::max(upper.highest, lower.highest);
    return highest - lowest <= relativeJump * lowest;
}

/** Visits every 4-neighbour pair once, row by row and, within a row, column by column: (row, col) with
 *  (row, col + 1), then (row, col) with (row + 1, col). A depth break (isDepthBreak) marks the nearer pixel with the
 *  point at the pair's midpoint, or is passed over with DepthBreaks::Skip. A pair on one surface (no break, both
 *  covered) is offered to the kernel, which provides:
 *  - `BlockSummary summarize(int row, int col) const`: its data over columns col .. col + blockWidth of `row`,
 *    asked only for blocks whose depths are all surface;
 *  - `bool isQuiet(const BlockSummary& upper, const BlockSummary& lower) const`: true only if no pair of the block
 *    on those two rows can fire;
 *  - `void beginRow(int row)`: before the pairs of `row` (and `row + 1` below it, when there is one);
 *  - `void blockEvents(int col, unsigned char* rightEvents, unsigned char* belowEvents) const`: for k < blockWidth, 1
 * where the cheap branch-free test fires on the pair (col + k, right neighbour), resp. (col + k, the pixel below), else
 * 0;
 *  - `bool rightEvent(int col) const`, `bool belowEvent(int col) const`: the same test for one pair;
 *  - `PairMark mark(int row, int col, int otherRow, int otherCol) const`: the exact decision for a pair that fired.
 *  `depth` is CV_32FC1 and `skeleton.mask` CV_8UC1 of its size (the caller checks both). */
template <typename Kernel>
void markNeighbourPairs(const cv::Mat& depth, float relativeJump, DepthBreaks depthBreaks, LineSkeleton& skeleton,
                        Kernel& kernel) {
    using BlockSummary = typename Kernel::BlockSummary;
    const int rows = depth.rows;
    const int cols = depth.cols;
    std::vector<LinePoint>& points = skeleton.points;
    // Per column of a block: bits 0-1 classify the pair with the right neighbour, bits 2-3 the pair below.
    unsigned char flags[blockWidth];
    unsigned char rightEvents[blockWidth];
    unsigned char belowEvents[blockWidth];

    auto handle = [&](unsigned char flag, int row, int col, int otherRow, int otherCol) {
        uchar& maskA = skeleton.mask.ptr<uchar>(row)[col];
        uchar& maskB = skeleton.mask.ptr<uchar>(otherRow)[otherCol];
        if (flag & 1) {
            if (depthBreaks == DepthBreaks::Skip) return;
            const float depthA = depth.ptr<float>(row)[col];
            const float depthB = depth.ptr<float>(otherRow)[otherCol];
            // Written so that a NaN depth, which isDepthBreak takes for background, is never the nearer one.
            const bool aNearer = !(depthB > 0.0f) || (depthA > 0.0f && depthA < depthB);
            (aNearer ? maskA : maskB) = 255;
            points.push_back(
                {{0.5f * static_cast<float>(col + otherCol), 0.5f * static_cast<float>(row + otherRow)}, 1.0f});
            return;
        }
        const PairMark mark = kernel.mark(row, col, otherRow, otherCol);
        if (mark.pixel == PairMark::None) return;
        (mark.pixel == PairMark::A ? maskA : maskB) = 255;
        points.push_back({{static_cast<float>(col) + mark.along * static_cast<float>(otherCol - col),
                           static_cast<float>(row) + mark.along * static_cast<float>(otherRow - row)},
                          1.0f});
    };

    // Summaries of the blocks of two rows at a time; the lower row's become the upper row's on the next row.
    const int blockCount = (cols - 1) / blockWidth;
    std::vector<DepthSummary> upperDepths(blockCount), lowerDepths(blockCount);
    std::vector<BlockSummary> upperKernel(blockCount), lowerKernel(blockCount);
    auto summarizeRow = [&](int row, std::vector<DepthSummary>& depths, std::vector<BlockSummary>& kernelSummaries) {
        const float* values = depth.ptr<float>(row);
        for (int block = 0; block < blockCount; ++block) {
            summarizeDepths(values + block * blockWidth, depths[block]);
            if (depths[block].covered) kernelSummaries[block] = kernel.summarize(row, block * blockWidth);
        }
    };
    if (rows > 1) summarizeRow(0, upperDepths, upperKernel);

    auto handleColumn = [&](unsigned char flag, int row, int col) {
        if (flag & 3) handle(flag & 3, row, col, row, col + 1);
        if (flag >> 2) handle(flag >> 2, row, col, row + 1, col);
    };
    for (int row = 0; row < rows; ++row) {
        kernel.beginRow(row);
        const float* here = depth.ptr<float>(row);
        if (row + 1 == rows) { // the last row has right neighbours only
            for (int col = 0; col + 1 < cols; ++col) {
                const unsigned char flag = classifyPair(here[col], here[col + 1], relativeJump, kernel.rightEvent(col));
                if (flag != 0) handleColumn(flag, row, col);
            }
            break;
        }
        summarizeRow(row + 1, lowerDepths, lowerKernel);
        const float* below = depth.ptr<float>(row + 1);
        auto classify = [&](int col, bool rightEvent, bool belowEvent) {
            return static_cast<unsigned char>(classifyPair(here[col], here[col + 1], relativeJump, rightEvent) |
                                              (classifyPair(here[col], below[col], relativeJump, belowEvent) << 2));
        };
        for (int block = 0; block < blockCount; ++block) {
            if (upperDepths[block].blank && lowerDepths[block].blank) continue;
            if (isOneSurface(upperDepths[block], lowerDepths[block], relativeJump) &&
                kernel.isQuiet(upperKernel[block], lowerKernel[block]))
                continue;
            const int firstCol = block * blockWidth;
            kernel.blockEvents(firstCol, rightEvents, belowEvents);
            std::uint64_t anyFlag = 0;
            for (int offset = 0; offset < blockWidth; ++offset) {
                flags[offset] = classify(firstCol + offset, rightEvents[offset], belowEvents[offset]);
                anyFlag |= flags[offset];
            }
            if (anyFlag == 0) continue;
            for (int offset = 0; offset < blockWidth; ++offset)
                if (flags[offset] != 0) handleColumn(flags[offset], row, firstCol + offset);
        }
        for (int col = blockCount * blockWidth; col + 1 < cols; ++col) {
            const unsigned char flag = classify(col, kernel.rightEvent(col), kernel.belowEvent(col));
            if (flag != 0) handleColumn(flag, row, col);
        }
        const int lastCol = cols - 1;
        const unsigned char lastFlag = static_cast<unsigned char>(
            classifyPair(here[lastCol], below[lastCol], relativeJump, kernel.belowEvent(lastCol)) << 2);
        if (lastFlag != 0) handleColumn(lastFlag, row, lastCol);
        std::swap(upperDepths, lowerDepths);
        std::swap(upperKernel, lowerKernel);
    }
}

/** A kernel that marks depth breaks only. */
struct NoSurfaceEvents {
    struct BlockSummary {};
    BlockSummary summarize(int, int) const { return {}; }
    bool isQuiet(const BlockSummary&, const BlockSummary&) const { return true; }
    void beginRow(int) {}
    void blockEvents(int, unsigned char* rightEvents, unsigned char* belowEvents) const {
        std::memset(rightEvents, 0, blockWidth);
        std::memset(belowEvents, 0, blockWidth);
    }
    bool rightEvent(int) const { return false; }
    bool belowEvent(int) const { return false; }
    PairMark mark(int, int, int, int) const { return {}; }
};

} // namespace inkgraph::detail
