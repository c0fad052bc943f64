#include "postfx/Contour.h"

#include "postfx/NeighbourPairs.h"

#include <bit>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace inkgraph {
namespace {

void requireSkeletonMaskFor(const cv::Mat& depth, LineSkeleton& skeleton, const char* function) {
    if (skeleton.mask.empty()) {
        skeleton.mask = cv::Mat::zeros(depth.size(), CV_8UC1);
        return;
    }
    if (skeleton.mask.type() != CV_8UC1 || skeleton.mask.size() != depth.size())
        throw std::invalid_argument(std::string(function) +
                                    "(): 'skeleton.mask' must be empty or CV_8UC1 of the size of 'depth'");
}

/** n.v changing sign between neighbours on one surface (0 counts as front-facing). */
struct SignChanges {
    const cv::Mat& nDotV;
    const float* here = nullptr;
    const float* below = nullptr;

    void beginRow(int row) {
        here = nDotV.ptr<float>(row);
        below = row + 1 < nDotV.rows ? nDotV.ptr<float>(row + 1) : nullptr;
    }
    /** Whether a block's n.v all have their sign bit set, or none has. */
    struct BlockSummary {
        bool allNegative = false;
        bool noneNegative = false;
    };
    BlockSummary summarize(int row, int col) const {
        const float* values = nDotV.ptr<float>(row) + col;
        cv::v_uint32x4 allBits = cv::v_reinterpret_as_u32(cv::v_load(values));
        cv::v_uint32x4 anyBits = allBits;
        for (int offset = 4; offset < detail::blockWidth; offset += 4) {
            const cv::v_uint32x4 bits = cv::v_reinterpret_as_u32(cv::v_load(values + offset));
            allBits = allBits & bits;
            anyBits = anyBits | bits;
        }
        const std::uint32_t last = std::bit_cast<std::uint32_t>(values[detail::blockWidth]);
        constexpr std::uint32_t signBit = 0x80000000u;
        const cv::v_uint32x4 signMask = cv::v_setall_u32(signBit);
        return {(cv::v_reduce_min(allBits & signMask) & last & signBit) != 0,
                ((cv::v_reduce_max(anyBits & signMask) | last) & signBit) == 0};
    }
    // Quiet when every n.v of both rows has the same sign bit. A -0 (which counts as front-facing) among positive
    // values only sends the block to the exact test; a NaN gives no crossing either way.
    bool isQuiet(const BlockSummary& upper, const BlockSummary& lower) const {
        return (upper.allNegative && lower.allNegative) || (upper.noneNegative && lower.noneNegative);
    }
    void blockEvents(int col, unsigned char* rightEvents, unsigned char* belowEvents) const {
        for (int offset = 0; offset < detail::blockWidth; ++offset) {
            rightEvents[offset] = rightEvent(col + offset);
            belowEvents[offset] = belowEvent(col + offset);
        }
    }
    bool rightEvent(int col) const { return (here[col] >= 0.0f) != (here[col + 1] >= 0.0f); }
    bool belowEvent(int col) const { return (here[col] >= 0.0f) != (below[col] >= 0.0f); }
    detail::PairMark mark(int row, int col, int otherRow, int otherCol) const {
        const float a = nDotV.ptr<float>(row)[col];
        const float b = nDotV.ptr<float>(otherRow)[otherCol];
        detail::PairMark result;
        const float along = a / (a - b);                      // the linear zero crossing
        if (!(along >= 0.0f && along <= 1.0f)) return result; // a NaN or two infinities: no crossing to place
        result.pixel = std::abs(a) <= std::abs(b) ? detail::PairMark::A : detail::PairMark::B;
        result.along = along;
        return result;
    }
};

} // namespace

LineSkeleton extractContours(const cv::Mat& nDotV, const cv::Mat& depth, const ContourSettings& settings) {
    if (nDotV.empty() || nDotV.type() != CV_32FC1)
        throw std::invalid_argument("extractContours(): 'nDotV' must be a non-empty CV_32FC1");
    if (depth.type() != CV_32FC1 || depth.size() != nDotV.size())
        throw std::invalid_argument("extractContours(): 'depth' must be CV_32FC1 of the size of 'nDotV'");
    detail::requireFiniteNonNegative(settings.depthJump, "extractContours", "settings.depthJump");

    LineSkeleton skeleton;
    skeleton.mask = cv::Mat::zeros(depth.size(), CV_8UC1);
    skeleton.points.reserve(expectedSkeletonPoints(depth.size()));
    SignChanges signChanges{nDotV};
    detail::markNeighbourPairs(depth, settings.depthJump, detail::DepthBreaks::Mark, skeleton, signChanges);
    return skeleton;
}

void appendDepthBreaks(const cv::Mat& depth, float relativeJump, LineSkeleton& skeleton) {
    if (depth.empty() || depth.type() != CV_32FC1)
        throw std::invalid_argument("appendDepthBreaks(): 'depth' must be a non-empty CV_32FC1");
    detail::requireFiniteNonNegative(relativeJump, "appendDepthBreaks", "relativeJump");
    requireSkeletonMaskFor(depth, skeleton, "appendDepthBreaks");
    if (skeleton.points.capacity() == 0) skeleton.points.reserve(expectedSkeletonPoints(depth.size()));
    detail::NoSurfaceEvents noSurfaceEvents;
    detail::markNeighbourPairs(depth, relativeJump, detail::DepthBreaks::Mark, skeleton, noSurfaceEvents);
}

} // namespace inkgraph
