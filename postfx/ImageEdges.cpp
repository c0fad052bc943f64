#include "postfx/ImageEdges.h"

#include "postfx/Contour.h"
#include "postfx/NeighbourPairs.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace inkgraph {
namespace {

/** Neighbours whose normals are further apart than the crease angle; the left or upper pixel is marked. */
struct Creases {
    const cv::Mat& normal;
    float cosCreaseSigned;  ///< cos(crease) |cos(crease)|
    float sinCreaseSquared; ///< sin(crease)^2
    bool zeroCrease;        ///< every pair of different directions is a crease
    /** For unit normals |a - b|^2 = 4 sin^2(angle / 2), and no pair in a block differs by more than the block's
     *  per-component spans: a block whose squared spans sum to less than this holds no crease. The margin covers
     *  normals that are unit only to float precision. */
    float quietSpanSquared;
    const float* here = nullptr;
    const float* below = nullptr;

    void beginRow(int row) {
        here = normal.ptr<float>(row);
        below = row + 1 < normal.rows ? normal.ptr<float>(row + 1) : nullptr;
    }
    // atan2(|a x b|, a . b) > crease  <=>  |a x b| cos(crease) > (a . b) sin(crease) for a crease in [0, pi], since
    // the angle lies there too: the same well-conditioned test without atan2. Squared with its sign (x |x| is
    // increasing), it needs no square root either. Both sides scale with |a|^2 |b|^2, so normals need not be exactly
    // unit, and a zero normal never makes a crease. Written once for scalars and for SIMD vectors of four pairs.
    template <typename Value, typename Condition>
    static Condition isCrease(Value ax, Value ay, Value az, Value bx, Value by, Value bz, Value cosCreaseSigned,
                              Value sinCreaseSquared, Condition zeroCrease, Value zero) {
        const Value crossX = ay * bz - az * by;
        const Value crossY = az * bx - ax * bz;
        const Value crossZ = ax * by - ay * bx;
        const Value sineSquared = crossX * crossX + crossY * crossY + crossZ * crossZ;
        const Value cosine = ax * bx + ay * by + az * bz;
        const Value cosineSigned = cosine * absolute(cosine);
        // The one case the sine form misses: opposite normals (angle pi) at a zero crease angle.
        return (sineSquared * cosCreaseSigned > cosineSigned * sinCreaseSquared) | (zeroCrease & (cosine < zero));
    }
    static float absolute(float value) { return std::abs(value); }
    static cv::v_float32x4 absolute(const cv::v_float32x4& value) { return cv::v_abs(value); }
    bool isCrease(const float* a, const float* b) const {
        return isCrease(a[0], a[1], a[2], b[0], b[1], b[2], cosCreaseSigned, sinCreaseSquared, zeroCrease, 0.0f);
    }
    /** Per-channel range of a block's normals; one pixel is one SIMD vector (x, y, z, alpha). */
    struct BlockSummary {
        cv::v_float32x4 lowest;
        cv::v_float32x4 highest;
        bool ordered = false; ///< no NaN, which min and max would drop
    };
    BlockSummary summarize(int row, int col) const {
        const float* pixels = normal.ptr<float>(row) + 4 * col;
        BlockSummary summary;
        summary.lowest = cv::v_load(pixels);
        summary.highest = summary.lowest;
        cv::v_float32x4 ordered = summary.lowest == summary.lowest;
        for (int offset = 1; offset <= detail::blockWidth; ++offset) {
            const cv::v_float32x4 value = cv::v_load(pixels + 4 * offset);
            summary.lowest = cv::v_min(summary.lowest, value);
            summary.highest = cv::v_max(summary.highest, value);
            ordered = ordered & (value == value);
        }
        summary.ordered = cv::v_check_all(ordered);
        return summary;
    }
    bool isQuiet(const BlockSummary& upper, const BlockSummary& lower) const {
        if (!upper.ordered || !lower.ordered) return false;
        float spans[4];
        cv::v_store(spans, cv::v_max(upper.highest, lower.highest) - cv::v_min(upper.lowest, lower.lowest));
        return spans[0] * spans[0] + spans[1] * spans[1] + spans[2] * spans[2] < quietSpanSquared;
    }
    void blockEvents(int col, unsigned char* rightEvents, unsigned char* belowEvents) const {
        const cv::v_float32x4 zero = cv::v_setzero_f32();
        const cv::v_float32x4 cosSigned = cv::v_setall_f32(cosCreaseSigned);
        const cv::v_float32x4 sinSquared = cv::v_setall_f32(sinCreaseSquared);
        const cv::v_float32x4 zeroCreaseMask = cv::v_reinterpret_as_f32(cv::v_setall_u32(zeroCrease ? ~0u : 0u));
        for (int offset = 0; offset < detail::blockWidth; offset += 4) {
            const float* pixel = here + 4 * (col + offset);
            cv::v_float32x4 ax, ay, az, aw, rx, ry, rz, rw, bx, by, bz, bw;
            cv::v_load_deinterleave(pixel, ax, ay, az, aw);
            cv::v_load_deinterleave(pixel + 4, rx, ry, rz, rw);
            cv::v_load_deinterleave(below + 4 * (col + offset), bx, by, bz, bw);
            const int right =
                cv::v_signmask(isCrease(ax, ay, az, rx, ry, rz, cosSigned, sinSquared, zeroCreaseMask, zero));
            const int down =
                cv::v_signmask(isCrease(ax, ay, az, bx, by, bz, cosSigned, sinSquared, zeroCreaseMask, zero));
            for (int lane = 0; lane < 4; ++lane) {
                rightEvents[offset + lane] = static_cast<unsigned char>((right >> lane) & 1);
                belowEvents[offset + lane] = static_cast<unsigned char>((down >> lane) & 1);
            }
        }
    }
    bool rightEvent(int col) const { return isCrease(here + 4 * col, here + 4 * (col + 1)); }
    bool belowEvent(int col) const { return isCrease(here + 4 * col, below + 4 * col); }
    detail::PairMark mark(int, int, int, int) const { return {detail::PairMark::A, 0.5f}; }
};

} // namespace

LineSkeleton extractDepthEdges(const cv::Mat& depth, const DepthEdgeSettings& settings) {
    if (depth.empty() || depth.type() != CV_32FC1)
        throw std::invalid_argument("extractDepthEdges(): 'depth' must be a non-empty CV_32FC1");
    detail::requireFiniteNonNegative(settings.relativeJump, "extractDepthEdges", "settings.relativeJump");
    LineSkeleton skeleton;
    skeleton.mask = cv::Mat::zeros(depth.size(), CV_8UC1);
    skeleton.points.reserve(expectedSkeletonPoints(depth.size()));
    appendDepthBreaks(depth, settings.relativeJump, skeleton);
    return skeleton;
}

LineSkeleton extractNormalEdges(const cv::Mat& normal, const cv::Mat& depth, const NormalEdgeSettings& settings) {
    if (normal.empty() || normal.type() != CV_32FC4)
        throw std::invalid_argument("extractNormalEdges(): 'normal' must be a non-empty CV_32FC4");
    if (depth.type() != CV_32FC1 || depth.size() != normal.size())
        throw std::invalid_argument("extractNormalEdges(): 'depth' must be CV_32FC1 of the size of 'normal'");
    if (!(settings.creaseAngleDegrees >= 0.0f && settings.creaseAngleDegrees <= 180.0f))
        throw std::invalid_argument("extractNormalEdges(): 'settings.creaseAngleDegrees' must lie in [0, 180]");
    detail::requireFiniteNonNegative(settings.depthJump, "extractNormalEdges", "settings.depthJump");

    const double crease = static_cast<double>(settings.creaseAngleDegrees) * std::numbers::pi / 180.0;
    const float cosCrease = static_cast<float>(std::cos(crease));
    // sin(pi) rounds to 1e-16, which would make opposite normals a crease at 180 degrees; nothing exceeds 180.
    const float sinCrease = settings.creaseAngleDegrees >= 180.0f ? 0.0f : static_cast<float>(std::sin(crease));

    LineSkeleton skeleton;
    skeleton.mask = cv::Mat::zeros(depth.size(), CV_8UC1);
    skeleton.points.reserve(expectedSkeletonPoints(depth.size()));
    const float halfSine = static_cast<float>(std::sin(0.5 * crease));
    Creases creases{normal, cosCrease * std::abs(cosCrease), sinCrease * sinCrease, settings.creaseAngleDegrees == 0.0f,
                    4.0f * halfSine * halfSine * 0.999f};
    detail::markNeighbourPairs(depth, settings.depthJump, detail::DepthBreaks::Skip, skeleton, creases);
    return skeleton;
}

} // namespace inkgraph
