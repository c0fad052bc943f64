#include "postfx/SuggestiveContours.h"

#include <opencv2/core/hal/intrin.hpp>
#include <opencv2/core.hpp>
#include <opencv2/core/utility.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace inkgraph {
namespace {

// Channels of the radial buffer.
constexpr int kNormalDistance = 0; // n.(c - p)
constexpr int kImageWX = 1;        // (J w).x
constexpr int kImageWY = 2;        // (J w).y
constexpr int kWLengthSquared = 3; // |w|^2

std::string sizeText(cv::Size size) { return std::to_string(size.width) + "x" + std::to_string(size.height); }

bool isFiniteAtLeast(float value, float lowest) { return std::isfinite(value) && value >= lowest; }

void checkInputs(const std::string& function, const cv::Mat& radial, const cv::Mat& depth,
                 const SuggestiveSettings& settings) {
    if (radial.type() != CV_32FC4 || radial.empty())
        throw std::invalid_argument(function + ": 'radial' must be a non-empty CV_32FC4 image");
    if (depth.type() != CV_32FC1 || depth.size() != radial.size())
        throw std::invalid_argument(function + ": 'depth' must be CV_32FC1 of " + sizeText(radial.size()));
    if (!(isFiniteAtLeast(settings.minSinTheta, 0.0f) && settings.minSinTheta < 1.0f))
        throw std::invalid_argument(function + ": 'minSinTheta' must lie in [0, 1)");
    if (!(isFiniteAtLeast(settings.featureSize, 0.0f) && settings.featureSize > 0.0f))
        throw std::invalid_argument(function + ": 'featureSize' must be positive and finite");
    if (!isFiniteAtLeast(settings.threshold, 0.0f))
        throw std::invalid_argument(function + ": 'threshold' must be finite and >= 0");
    if (!isFiniteAtLeast(settings.fade, 0.0f))
        throw std::invalid_argument(function + ": 'fade' must be finite and >= 0");
    if (!(isFiniteAtLeast(settings.depthJump, 0.0f) && settings.depthJump > 0.0f))
        throw std::invalid_argument(function + ": 'depthJump' must be positive and finite");
    if (!isFiniteAtLeast(settings.smoothing, 0.0f))
        throw std::invalid_argument(function + ": 'smoothing' must be finite and >= 0");
    if (settings.smoothing > 0.0f && !(isFiniteAtLeast(settings.focalPixels, 0.0f) && settings.focalPixels > 0.0f))
        throw std::invalid_argument(function + ": 'focalPixels' must be positive and finite when smoothing");
}

/** Columns [begin, end) of one row; the rows' spans bound their covered pixels, so work skips the background. */
struct Span {
    int begin = 0;
    int end = 0;
};

#if CV_SIMD128
using cv::v_float32x4;
#endif

/** From the first to the last covered pixel of a depth row (covered: depth > 0, as isDepthBreak() has it). */
Span coveredSpan(const float* depth, int cols) {
    int begin = 0;
    int end = cols;
#if CV_SIMD128
    const v_float32x4 zero = cv::v_setzero_f32();
    while (begin + 4 <= cols && !cv::v_check_any(cv::v_load(depth + begin) > zero)) begin += 4;
    while (end - 4 >= begin && !cv::v_check_any(cv::v_load(depth + end - 4) > zero)) end -= 4;
#endif
    while (begin < end && !(depth[begin] > 0.0f)) ++begin;
    while (end > begin && !(depth[end - 1] > 0.0f)) --end;
    return {begin, end};
}

/** Copies n.(c - p) and J w of one row's span into contiguous arrays, which the differences then read 4 at a time. */
void splitRadialRow(const cv::Vec4f* radial, Span span, float* normalDistance, float* imageWX, float* imageWY) {
    int col = span.begin;
#if CV_SIMD128
    for (; col + 4 <= span.end; col += 4) {
        v_float32x4 distance, wx, wy, wSquared;
        cv::v_load_deinterleave(radial[col].val, distance, wx, wy, wSquared);
        cv::v_store(normalDistance + col, distance);
        cv::v_store(imageWX + col, wx);
        cv::v_store(imageWY + col, wy);
    }
#endif
    for (; col < span.end; ++col) {
        normalDistance[col] = radial[col][kNormalDistance];
        imageWX[col] = radial[col][kImageWX];
        imageWY[col] = radial[col][kImageWY];
    }
}

/** !isDepthBreak(depth, neighbourDepth, depthJump) for a covered pixel (depth > 0), in a form with a vector twin. */
inline bool joinsNeighbour(float depth, float neighbourDepth, float depthJump) {
    return neighbourDepth > 0.0f && std::abs(depth - neighbourDepth) <= depthJump * std::min(depth, neighbourDepth);
}

#if CV_SIMD128
inline v_float32x4 joinsNeighbour(const v_float32x4& depth, const v_float32x4& neighbourDepth,
                                  const v_float32x4& depthJump) {
    return (neighbourDepth > cv::v_setzero_f32()) &
           (cv::v_abs(depth - neighbourDepth) <= depthJump * cv::v_min(depth, neighbourDepth));
}
#endif

/** One row's inputs to differentiateAlongW(): linear depth of the row and its neighbours, n.(c - p) likewise, and
 *  J w of the row, each indexed by column. */
struct RowInputs {
    const float* depthAbove;
    const float* depth;
    const float* depthBelow;
    const float* normalDistanceAbove;
    const float* normalDistance;
    const float* normalDistanceBelow;
    const float* imageWX;
    const float* imageWY;
};

/** D_w(n.v) over columns [begin, end) of an interior row: the central differences of n.(c - p) dotted with J w,
 *  defined (1) where the pixel and its four neighbours lie on one surface, which keeps background out too; dw = 0
 *  and defined = 0 elsewhere. Four columns at a time by selects: an entry not selected may have read stale
 *  neighbours, which never reach the result. */
void differentiateAlongW(const RowInputs& in, int begin, int end, float depthJump, float* dw, float* defined) {
    int col = begin;
#if CV_SIMD128
    const v_float32x4 zero = cv::v_setzero_f32();
    const v_float32x4 one = cv::v_setall_f32(1.0f);
    const v_float32x4 half = cv::v_setall_f32(0.5f);
    const v_float32x4 jump = cv::v_setall_f32(depthJump);
    for (; col + 4 <= end; col += 4) {
        const v_float32x4 z = cv::v_load(in.depth + col);
        const v_float32x4 onOneSurface = (z > zero) & joinsNeighbour(z, cv::v_load(in.depth + col - 1), jump) &
                                         joinsNeighbour(z, cv::v_load(in.depth + col + 1), jump) &
                                         joinsNeighbour(z, cv::v_load(in.depthAbove + col), jump) &
                                         joinsNeighbour(z, cv::v_load(in.depthBelow + col), jump);
        const v_float32x4 gradientX = cv::v_load(in.normalDistance + col + 1) - cv::v_load(in.normalDistance + col - 1);
        const v_float32x4 gradientY =
            cv::v_load(in.normalDistanceBelow + col) - cv::v_load(in.normalDistanceAbove + col);
        const v_float32x4 derivative =
            half * (gradientX * cv::v_load(in.imageWX + col) + gradientY * cv::v_load(in.imageWY + col));
        cv::v_store(dw + col, cv::v_select(onOneSurface, derivative, zero));
        cv::v_store(defined + col, cv::v_select(onOneSurface, one, zero));
    }
#endif
    for (; col < end; ++col) {
        const float z = in.depth[col];
        const bool onOneSurface = z > 0.0f && joinsNeighbour(z, in.depth[col - 1], depthJump) &&
                                  joinsNeighbour(z, in.depth[col + 1], depthJump) &&
                                  joinsNeighbour(z, in.depthAbove[col], depthJump) &&
                                  joinsNeighbour(z, in.depthBelow[col], depthJump);
        const float gradientX = in.normalDistance[col + 1] - in.normalDistance[col - 1];
        const float gradientY = in.normalDistanceBelow[col] - in.normalDistanceAbove[col];
        dw[col] = onOneSurface ? 0.5f * (gradientX * in.imageWX[col] + gradientY * in.imageWY[col]) : 0.0f;
        defined[col] = onOneSurface ? 1.0f : 0.0f;
    }
}

/** n.v > 0 and sin(theta) >= the cut-off: where a second derivative along w is taken. */
inline bool facesAwayFromFrontal(const cv::Vec4f& radial, float minSinThetaSquared) {
    const float normalDistance = radial[kNormalDistance];
    const float wSquared = radial[kWLengthSquared];
    // sin^2 = |w|^2 / |v|^2 with |v|^2 = |w|^2 + (n.v)^2, compared without a division.
    return normalDistance > 0.0f && wSquared >= minSinThetaSquared * (wSquared + normalDistance * normalDistance);
}

/** D_w D_w(n.v) at one pixel from the D_w(n.v) rows above, at and below it, or nothing where it is invalid: a
 *  neighbour's D_w undefined (so every difference involved stays on the pixel's surface), n.v <= 0, or sin(theta)
 *  below the cut-off. The caller keeps the pixel off the image's edges. */
std::optional<float> secondDerivativeAt(const cv::Vec4f& radial, int col, const float* dwAbove, const float* dw,
                                        const float* dwBelow, const float* definedAbove, const float* defined,
                                        const float* definedBelow, float minSinThetaSquared) {
    if (!(defined[col - 1] > 0.0f && defined[col + 1] > 0.0f && definedAbove[col] > 0.0f && definedBelow[col] > 0.0f))
        return std::nullopt;
    if (!facesAwayFromFrontal(radial, minSinThetaSquared)) return std::nullopt;
    const float gradientX = dw[col + 1] - dw[col - 1];
    const float gradientY = dwBelow[col] - dwAbove[col];
    return 0.5f * (gradientX * radial[kImageWX] + gradientY * radial[kImageWY]);
}

/** A sign change, counting a zero once: as the non-negative side, so - 0 + is one crossing, between - and 0. */
inline bool changesSign(float a, float b) { return (a < 0.0f) != (b < 0.0f); }

/** The strength rule of a crossing: rtsc's q = fs^2 D_w D_w(n.v) / (|w|^2 n.v), its threshold and fade. */
struct StrengthRule {
    float featureSizeSquared;
    float threshold;
    float fade;
};

/** A kept crossing between neighbouring pixels a and b: where it lies from a (0..1), its alpha, and which pixel is
 *  marked. */
struct Crossing {
    float t;
    float alpha;
    bool marksA;
};

/** The crossing of D_w(n.v) between valid pixels a and b (given D_w, D_w D_w and radial at each), kept where
 *  D_w D_w(n.v) > 0 and the strength passes the threshold, both interpolated to the crossing so the test does not jump
 *  with which pixel lies nearer. The pixel with the smaller |D_w(n.v)| is marked. */
std::optional<Crossing> keptCrossing(float dwA, float dwB, float dwdwA, float dwdwB, const cv::Vec4f& radialA,
                                     const cv::Vec4f& radialB, const StrengthRule& rule) {
    if (!changesSign(dwA, dwB)) return std::nullopt;
    const float t = dwA / (dwA - dwB);
    const float dwdw = dwdwA + t * (dwdwB - dwdwA);
    if (!(dwdw > 0.0f)) return std::nullopt;
    const float wSquared = radialA[kWLengthSquared] + t * (radialB[kWLengthSquared] - radialA[kWLengthSquared]);
    const float normalDistance = radialA[kNormalDistance] + t * (radialB[kNormalDistance] - radialA[kNormalDistance]);
    const float denominator = wSquared * normalDistance;
    if (!(denominator > 0.0f)) return std::nullopt;
    const float strength = rule.featureSizeSquared * dwdw / denominator;
    if (!(strength > rule.threshold)) return std::nullopt;
    // rtsc's fade of the excess over the threshold: a line grows in from nothing as a view change makes it stronger,
    // instead of popping in at a fixed strength.
    const float excess = strength - rule.threshold;
    return Crossing{t, rule.fade > 0.0f ? excess / (excess + rule.fade) : 1.0f, std::abs(dwA) <= std::abs(dwB)};
}

/** The point of a crossing between (colA, rowA) and its neighbour to the right, or below when `downward`. */
cv::Point2f crossingPosition(int rowA, int colA, bool downward, float t) {
    return {float(colA) + (downward ? 0.0f : t), float(rowA) + (downward ? t : 0.0f)};
}

/** What one band of rows found. Marks in the row above the band belong to the band above, so they wait here until
 *  the bands have joined instead of being written concurrently. */
struct BandResult {
    std::vector<LinePoint> points;
    std::vector<cv::Point> marksAboveBand;
};

/** Finds the suggestive-contour crossings owned by rows [firstRow, endRow): the horizontal pairs in each row and the
 *  vertical pairs between it and the row above, so no two bands find the same crossing and their points, joined in
 *  band order, are those of one band over the whole image.
 *
 *  One pass down the rows over a ring: split the newest row, D_w(n.v) of the row above it, and the crossings of the
 *  row above that, whose validity needs D_w one row further up and down. D_w and its defined flag are written over
 *  each row's covered span and kept zero outside it, as if computed everywhere: a slot taking a new row clears what
 *  the old row left outside the new span. */
class BandScanner {
public:
    BandScanner(const cv::Mat& radial, const cv::Mat& depth, const SuggestiveSettings& settings, cv::Mat& mask,
                int firstRow, int endRow)
        : mRadial(radial), mDepth(depth), mMask(mask), mDepthJump(settings.depthJump),
          mMinSinThetaSquared(settings.minSinTheta * settings.minSinTheta), mRule{settings.featureSize *
                                                                                      settings.featureSize,
                                                                                  settings.threshold, settings.fade},
          mRows(radial.rows), mCols(radial.cols), mFirstRow(firstRow), mEndRow(endRow),
          mFirstLoaded(std::max(firstRow - 3, 0)), mSpans(size_t(std::min(endRow + 2, mRows) - mFirstLoaded)),
          mNormalDistance(kRingRows * size_t(mCols), 0.0f), mImageWX(kRingRows * size_t(mCols), 0.0f),
          mImageWY(kRingRows * size_t(mCols), 0.0f), mDw(kRingRows * size_t(mCols), 0.0f),
          mDefined(kRingRows * size_t(mCols), 0.0f) {}

    BandResult scan() {
        const int loadEnd = std::min(mEndRow + 2, mRows);
        const int differentiateBegin = std::max(mFirstRow - 2, 0);
        const int differentiateEnd = std::min(mEndRow + 1, mRows);
        for (int newest = mFirstLoaded; newest - 2 < mEndRow; ++newest) {
            if (newest < loadEnd) load(newest);
            if (newest - 1 >= differentiateBegin && newest - 1 < differentiateEnd) differentiate(newest - 1);
            if (newest - 2 >= mFirstRow) findCrossings(newest - 2);
        }
        return std::move(mResult);
    }

private:
    static constexpr int kRingRows = 8;

    size_t slotOf(int row) const { return size_t(row % kRingRows) * size_t(mCols); }
    Span spanOf(int row) const { return mSpans[size_t(row - mFirstLoaded)]; }

    void load(int row) {
        const Span span = coveredSpan(mDepth.ptr<float>(row), mCols);
        mSpans[size_t(row - mFirstLoaded)] = span;
        const size_t slot = slotOf(row);
        splitRadialRow(mRadial.ptr<cv::Vec4f>(row), span, &mNormalDistance[slot], &mImageWX[slot], &mImageWY[slot]);
    }

    void resetDerivatives(size_t slot, int begin, int end) {
        if (begin >= end) return;
        std::fill(mDw.begin() + std::ptrdiff_t(slot) + begin, mDw.begin() + std::ptrdiff_t(slot) + end, 0.0f);
        std::fill(mDefined.begin() + std::ptrdiff_t(slot) + begin, mDefined.begin() + std::ptrdiff_t(slot) + end, 0.0f);
    }

    void differentiate(int row) {
        const Span span = spanOf(row);
        const size_t slot = slotOf(row);
        Span& held = mDerivativeSpans[size_t(row % kRingRows)];
        resetDerivatives(slot, held.begin, std::min(held.end, span.begin));
        resetDerivatives(slot, std::max(held.begin, span.end), held.end);
        held = span;
        // D_w needs a neighbour on every side: none in the first and last rows and columns.
        const bool interiorRow = row > 0 && row < mRows - 1;
        const int begin = interiorRow ? std::max(span.begin, 1) : span.end;
        const int end = interiorRow ? std::min(span.end, mCols - 1) : span.end;
        resetDerivatives(slot, span.begin, begin);
        resetDerivatives(slot, std::max(begin, end), span.end);
        if (begin >= end) return;
        const RowInputs in{mDepth.ptr<float>(row - 1),
                           mDepth.ptr<float>(row),
                           mDepth.ptr<float>(row + 1),
                           &mNormalDistance[slotOf(row - 1)],
                           &mNormalDistance[slot],
                           &mNormalDistance[slotOf(row + 1)],
                           &mImageWX[slot],
                           &mImageWY[slot]};
        differentiateAlongW(in, begin, end, mDepthJump, &mDw[slot], &mDefined[slot]);
    }

    std::optional<float> secondDerivative(int row, int col) const {
        return secondDerivativeAt(mRadial.ptr<cv::Vec4f>(row)[col], col, &mDw[slotOf(row - 1)], &mDw[slotOf(row)],
                                  &mDw[slotOf(row + 1)], &mDefined[slotOf(row - 1)], &mDefined[slotOf(row)],
                                  &mDefined[slotOf(row + 1)], mMinSinThetaSquared);
    }

    /** Crossings of the pairs (row, col)-(row, col + 1) and (row - 1, col)-(row, col), col in the row's span. Crossings
     *  are rare, so four columns are tested at once and only groups holding one are visited. */
    void findCrossings(int row) {
        // Valid pixels need a neighbour on every side, so the first and last rows and columns have none.
        if (row <= 0 || row >= mRows - 1) return;
        const Span span = spanOf(row);
        const int begin = std::max(span.begin, 1);
        const int end = std::min(span.end, mCols - 1);
        const float* dw = &mDw[slotOf(row)];
        const float* defined = &mDefined[slotOf(row)];
        const float* dwAbove = &mDw[slotOf(row - 1)];
        const float* definedAbove = &mDefined[slotOf(row - 1)];
        // Column end is always undefined (outside the span, or the last column), so the pairs reaching it are
        // tested harmlessly.
        int col = begin;
#if CV_SIMD128
        const v_float32x4 zero = cv::v_setzero_f32();
        for (; col + 4 <= end; col += 4) {
            const v_float32x4 centre = cv::v_load(dw + col);
            const v_float32x4 centreDefined = cv::v_load(defined + col) > zero;
            const v_float32x4 centreNegative = centre < zero;
            const v_float32x4 horizontal = centreDefined & (cv::v_load(defined + col + 1) > zero) &
                                           (centreNegative ^ (cv::v_load(dw + col + 1) < zero));
            const v_float32x4 vertical = centreDefined & (cv::v_load(definedAbove + col) > zero) &
                                         (centreNegative ^ (cv::v_load(dwAbove + col) < zero));
            if (cv::v_check_any(horizontal))
                for (int lane = 0; lane < 4; ++lane) considerPair(row, col + lane, false);
            if (cv::v_check_any(vertical))
                for (int lane = 0; lane < 4; ++lane) considerPair(row - 1, col + lane, true);
        }
#endif
        for (; col < end; ++col) {
            considerPair(row, col, false);
            considerPair(row - 1, col, true);
        }
    }

    /** Pixel a = (rowA, colA) and its neighbour b one step right, or down when `downward`. */
    void considerPair(int rowA, int colA, bool downward) {
        const int rowB = downward ? rowA + 1 : rowA;
        const int colB = downward ? colA : colA + 1;
        const float dwA = mDw[slotOf(rowA) + size_t(colA)];
        const float dwB = mDw[slotOf(rowB) + size_t(colB)];
        if (!(mDefined[slotOf(rowA) + size_t(colA)] > 0.0f && mDefined[slotOf(rowB) + size_t(colB)] > 0.0f) ||
            !changesSign(dwA, dwB))
            return; // most pairs: skip the second derivatives
        const auto dwdwA = secondDerivative(rowA, colA);
        const auto dwdwB = secondDerivative(rowB, colB);
        if (!dwdwA || !dwdwB) return;
        const std::optional<Crossing> crossing = keptCrossing(
            dwA, dwB, *dwdwA, *dwdwB, mRadial.ptr<cv::Vec4f>(rowA)[colA], mRadial.ptr<cv::Vec4f>(rowB)[colB], mRule);
        if (!crossing) return;
        const cv::Point marked = crossing->marksA ? cv::Point(colA, rowA) : cv::Point(colB, rowB);
        if (marked.y < mFirstRow)
            mResult.marksAboveBand.push_back(marked);
        else
            mMask.ptr<uchar>(marked.y)[marked.x] = 255;
        mResult.points.push_back({crossingPosition(rowA, colA, downward, crossing->t), crossing->alpha});
    }

    const cv::Mat& mRadial;
    const cv::Mat& mDepth;
    cv::Mat& mMask;
    float mDepthJump;
    float mMinSinThetaSquared;
    StrengthRule mRule;
    int mRows;
    int mCols;
    int mFirstRow;
    int mEndRow;
    int mFirstLoaded;
    std::vector<Span> mSpans;                       ///< of rows mFirstLoaded onwards
    std::array<Span, kRingRows> mDerivativeSpans{}; ///< the span each slot's D_w was last written over
    std::vector<float> mNormalDistance;
    std::vector<float> mImageWX;
    std::vector<float> mImageWY;
    std::vector<float> mDw;
    std::vector<float> mDefined;
    BandResult mResult;
};

/** Weights of the fourth-order central difference at offsets -2, -1, +1, +2 (the centre weighs 0). */
constexpr std::array<int, 4> kWideOffsets = {-2, -1, 1, 2};
constexpr std::array<float, 4> kWideWeights = {1.0f / 12.0f, -8.0f / 12.0f, 8.0f / 12.0f, -1.0f / 12.0f};

/** The derivative of `field` along the image vector (wx, wy) at (row, col) by the five-point stencil, or nothing
 *  where a stencil pixel is not `usable`. The caller keeps (row, col) two pixels off the image's edges. */
template <typename Usable>
std::optional<float> wideDerivative(const cv::Mat& field, int row, int col, float wx, float wy, Usable usable) {
    float gradientX = 0.0f;
    float gradientY = 0.0f;
    for (size_t i = 0; i < kWideOffsets.size(); ++i) {
        const int offset = kWideOffsets[i];
        if (!usable(row, col + offset) || !usable(row + offset, col)) return std::nullopt;
        gradientX += kWideWeights[i] * field.at<float>(row, col + offset);
        gradientY += kWideWeights[i] * field.at<float>(row + offset, col);
    }
    return gradientX * wx + gradientY * wy;
}

/** computeRadialDerivatives() with DifferenceStencil::Central5: a plain per-pixel loop over full-image maps. */
RadialDerivatives wideRadialDerivatives(const cv::Mat& radial, const cv::Mat& depth,
                                        const SuggestiveSettings& settings) {
    const int rows = radial.rows;
    const int cols = radial.cols;
    cv::Mat normalDistance;
    cv::extractChannel(radial, normalDistance, kNormalDistance);
    RadialDerivatives result;
    result.dw = cv::Mat::zeros(radial.size(), CV_32FC1);
    result.dwdw = cv::Mat::zeros(radial.size(), CV_32FC1);
    result.valid = cv::Mat::zeros(radial.size(), CV_8UC1);
    cv::Mat defined = cv::Mat::zeros(radial.size(), CV_8UC1);
    constexpr int kReach = 2;
    for (int row = kReach; row + kReach < rows; ++row) {
        for (int col = kReach; col + kReach < cols; ++col) {
            const float z = depth.at<float>(row, col);
            if (!(z > 0.0f)) continue;
            const cv::Vec4f& here = radial.at<cv::Vec4f>(row, col);
            const auto sameSurface = [&](int r, int c) {
                return joinsNeighbour(z, depth.at<float>(r, c), settings.depthJump);
            };
            if (const auto dw = wideDerivative(normalDistance, row, col, here[kImageWX], here[kImageWY], sameSurface)) {
                result.dw.at<float>(row, col) = *dw;
                defined.at<uchar>(row, col) = 1;
            }
        }
    }
    const float minSinThetaSquared = settings.minSinTheta * settings.minSinTheta;
    const auto dwDefined = [&](int r, int c) { return defined.at<uchar>(r, c) != 0; };
    for (int row = kReach; row + kReach < rows; ++row) {
        for (int col = kReach; col + kReach < cols; ++col) {
            const cv::Vec4f& here = radial.at<cv::Vec4f>(row, col);
            if (!dwDefined(row, col) || !facesAwayFromFrontal(here, minSinThetaSquared)) continue;
            if (const auto dwdw = wideDerivative(result.dw, row, col, here[kImageWX], here[kImageWY], dwDefined)) {
                result.dwdw.at<float>(row, col) = *dwdw;
                result.valid.at<uchar>(row, col) = 255;
            }
        }
    }
    return result;
}

/** extractSuggestiveContours() over full-image derivative maps: every pair of valid 4-neighbours. */
LineSkeleton crossingsOfMaps(const cv::Mat& radial, const RadialDerivatives& derivatives,
                             const SuggestiveSettings& settings) {
    const StrengthRule rule{settings.featureSize * settings.featureSize, settings.threshold, settings.fade};
    LineSkeleton skeleton;
    skeleton.mask = cv::Mat::zeros(radial.size(), CV_8UC1);
    for (int row = 0; row < radial.rows; ++row) {
        for (int col = 0; col < radial.cols; ++col) {
            if (!derivatives.valid.at<uchar>(row, col)) continue;
            for (const bool downward : {false, true}) {
                const int rowB = downward ? row + 1 : row;
                const int colB = downward ? col : col + 1;
                if (rowB >= radial.rows || colB >= radial.cols || !derivatives.valid.at<uchar>(rowB, colB)) continue;
                const std::optional<Crossing> crossing =
                    keptCrossing(derivatives.dw.at<float>(row, col), derivatives.dw.at<float>(rowB, colB),
                                 derivatives.dwdw.at<float>(row, col), derivatives.dwdw.at<float>(rowB, colB),
                                 radial.at<cv::Vec4f>(row, col), radial.at<cv::Vec4f>(rowB, colB), rule);
                if (!crossing) continue;
                const cv::Point marked = crossing->marksA ? cv::Point(col, row) : cv::Point(colB, rowB);
                skeleton.mask.at<uchar>(marked) = 255;
                skeleton.points.push_back({crossingPosition(row, col, downward, crossing->t), crossing->alpha});
            }
        }
    }
    return skeleton;
}

/** The Gaussian's weights at distances 0..reach for one sigma, reused while the sigma rounds to the same level. */
class GaussianTaps {
public:
    /** Weights for `sigma` pixels (> 0), rounded to a 1% step: neighbouring pixels see nearly the same depth, so the
     *  table is rarely rebuilt, and the rounding moves the Gaussian far less than the smoothing itself does. */
    const std::vector<float>& weightsFor(float sigma) {
        const int level = int(std::lround(std::log(sigma) / std::log(kStep)));
        if (level != mLevel || mWeights.empty()) {
            mLevel = level;
            const double rounded = std::pow(kStep, double(level));
            const int reach = std::min(kMaxSmoothingReach, int(std::ceil(3.0 * rounded)));
            mWeights.resize(size_t(reach) + 1);
            for (int d = 0; d <= reach; ++d) mWeights[size_t(d)] = float(std::exp(-0.5 * d * d / (rounded * rounded)));
            mTotal = mWeights[0];
            for (int d = 1; d <= reach; ++d) mTotal += 2.0f * mWeights[size_t(d)];
        }
        return mWeights;
    }
    /** The sum of the last weightsFor()'s weights over the whole window, both sides. */
    float totalWeight() const { return mTotal; }

private:
    static constexpr double kStep = 1.01;
    int mLevel = 0;
    float mTotal = 0.0f;
    std::vector<float> mWeights;
};

/** The Gaussian mean of the values at centre - reach .. centre + reach (reach = weights.size() - 1), all present. */
cv::Vec4f symmetricMean(const cv::Vec4f* centre, const std::vector<float>& weights, float total) {
    const int reach = int(weights.size()) - 1;
#if CV_SIMD128
    v_float32x4 sum = cv::v_load(centre->val) * cv::v_setall_f32(weights[0]);
    for (int d = 1; d <= reach; ++d)
        sum = cv::v_fma(cv::v_load(centre[d].val) + cv::v_load(centre[-d].val), cv::v_setall_f32(weights[size_t(d)]),
                        sum);
    cv::Vec4f result;
    cv::v_store(result.val, sum * cv::v_setall_f32(1.0f / total));
    return result;
#else
    cv::Vec4f sum = weights[0] * centre[0];
    for (int d = 1; d <= reach; ++d) sum += weights[size_t(d)] * (centre[d] + centre[-d]);
    return sum * (1.0f / total);
#endif
}

/** One line of pixels (a row or a column) as smoothLine() reads it. */
struct PixelLine {
    std::vector<cv::Vec4f> values;
    std::vector<float> sigma;  ///< pixels; <= 0 off the model
    std::vector<int> runEnd;   ///< one past the last pixel of this pixel's run of one surface
    std::vector<int> runBegin; ///< the first pixel of it
    std::vector<cv::Vec4f> out;
    void resize(int n) {
        values.resize(size_t(n));
        sigma.resize(size_t(n));
        runEnd.resize(size_t(n));
        runBegin.resize(size_t(n));
        out.resize(size_t(n));
    }
};

/** Fills runBegin/runEnd from the depths along the line: consecutive covered pixels that join (no depth break) are
 *  one run. */
void findRuns(const float* depth, int n, float depthJump, PixelLine& line) {
    int begin = 0;
    for (int i = 0; i < n; ++i) {
        const float z = depth[i];
        if (i > 0 && !(z > 0.0f && joinsNeighbour(z, depth[i - 1], depthJump))) begin = i;
        line.runBegin[size_t(i)] = begin;
    }
    int end = n;
    for (int i = n; i-- > 0;) {
        const float z = depth[i];
        if (i + 1 < n && !(z > 0.0f && joinsNeighbour(z, depth[i + 1], depthJump))) end = i + 1;
        line.runEnd[size_t(i)] = end;
    }
}

/** Each covered pixel's value replaced by the Gaussian-weighted least-squares line through its run's values within
 *  the reach, evaluated at the pixel: for a symmetric window the plain Gaussian mean; near a run's end the fitted
 *  line, so a linear field stays exact there instead of being pulled toward the inside. */
void smoothLine(PixelLine& line, int n, GaussianTaps& taps) {
    for (int i = 0; i < n; ++i) {
        const float sigma = line.sigma[size_t(i)];
        line.out[size_t(i)] = line.values[size_t(i)];
        if (!(sigma > 0.0f)) continue;
        const std::vector<float>& weights = taps.weightsFor(sigma);
        const int reach = int(weights.size()) - 1;
        const int low = std::max(line.runBegin[size_t(i)], i - reach);
        const int high = std::min(line.runEnd[size_t(i)] - 1, i + reach);
        if (high <= low) continue;
        if (low == i - reach && high == i + reach) {
            // The whole window on the surface, most pixels: symmetric, so the fitted line's value is the plain
            // Gaussian mean, summed in pairs.
            line.out[size_t(i)] = symmetricMean(&line.values[size_t(i)], weights, taps.totalWeight());
            continue;
        }
        float s0 = 0.0f, s1 = 0.0f, s2 = 0.0f;
        cv::Vec4f t0 = cv::Vec4f::all(0.0f), t1 = cv::Vec4f::all(0.0f);
        for (int j = low; j <= high; ++j) {
            const int d = j - i;
            const float g = weights[size_t(std::abs(d))];
            const float gd = g * float(d);
            s0 += g;
            s1 += gd;
            s2 += gd * float(d);
            const cv::Vec4f& v = line.values[size_t(j)];
            t0 += g * v;
            t1 += gd * v;
        }
        // The line a + b d fitted at d = 0: a = (s2 t0 - s1 t1) / (s0 s2 - s1^2); with a window of one pixel (or a
        // degenerate one) the weighted mean, which is then the pixel itself.
        const float determinant = s0 * s2 - s1 * s1;
        if (determinant > 1e-6f * s0 * s2)
            line.out[size_t(i)] = (s2 * t0 - s1 * t1) * (1.0f / determinant);
        else
            line.out[size_t(i)] = t0 * (1.0f / s0);
    }
}

/** Per pixel the smoothing's sigma in pixels: the model-space sigma seen at its depth; 0 off the model. */
cv::Mat smoothingSigmas(const cv::Mat& depth, const SuggestiveSettings& settings) {
    cv::Mat sigma(depth.size(), CV_32FC1);
    const float scale = settings.smoothing * settings.focalPixels;
    for (int row = 0; row < depth.rows; ++row) {
        const float* z = depth.ptr<float>(row);
        float* out = sigma.ptr<float>(row);
        for (int col = 0; col < depth.cols; ++col) out[col] = z[col] > 0.0f ? scale / z[col] : 0.0f;
    }
    return sigma;
}

/** One 1-D pass of smoothRadialField() along every row, rows split over threads. The column pass runs this on the
 *  transposed images, so both read memory in order. */
void smoothRows(const cv::Mat& source, cv::Mat& target, const cv::Mat& depth, const cv::Mat& sigma, float depthJump) {
    const int n = source.cols;
    cv::parallel_for_(cv::Range(0, source.rows), [&](const cv::Range& range) {
        PixelLine line;
        line.resize(n);
        GaussianTaps taps;
        for (int row = range.start; row < range.end; ++row) {
            const cv::Vec4f* in = source.ptr<cv::Vec4f>(row);
            std::copy(in, in + n, line.values.begin());
            const float* s = sigma.ptr<float>(row);
            std::copy(s, s + n, line.sigma.begin());
            findRuns(depth.ptr<float>(row), n, depthJump, line);
            smoothLine(line, n, taps);
            std::copy(line.out.begin(), line.out.end(), target.ptr<cv::Vec4f>(row));
        }
    });
}

/** The separable same-surface local-linear Gaussian of smoothRadialField() at the given per-pixel sigmas. */
cv::Mat gaussianOnSurface(const cv::Mat& radial, const cv::Mat& depth, const cv::Mat& depthTransposed,
                          const cv::Mat& sigma, float depthJump) {
    cv::Mat alongRows(radial.size(), CV_32FC4);
    smoothRows(radial, alongRows, depth, sigma, depthJump);
    cv::Mat transposed, sigmaTransposed;
    cv::transpose(alongRows, transposed);
    cv::transpose(sigma, sigmaTransposed);
    cv::Mat alongColumns(transposed.size(), CV_32FC4);
    smoothRows(transposed, alongColumns, depthTransposed, sigmaTransposed, depthJump);
    cv::Mat smoothed;
    cv::transpose(alongColumns, smoothed);
    return smoothed;
}
} // namespace

cv::Mat smoothRadialField(const cv::Mat& radial, const cv::Mat& depth, const SuggestiveSettings& settings) {
    checkInputs("smoothRadialField()", radial, depth, settings);
    if (!(settings.smoothing > 0.0f)) return radial.clone();
    const cv::Mat sigma = smoothingSigmas(depth, settings);
    cv::Mat depthTransposed;
    cv::transpose(depth, depthTransposed);
    // The shape's own lines move by O(sigma^2) (on the test torus at 512^2: a mean 0.025 px at 0.5% of the radius,
    // 0.095 px at 1%, 0.40 px at 2%). Twicing, 2 G(sigma) - G(sqrt(2) sigma), cut that to 0.14 px at 2% but made
    // spurious lines near the silhouettes at 2048^2, so it is not used.
    return gaussianOnSurface(radial, depth, depthTransposed, sigma, settings.depthJump);
}

RadialDerivatives computeRadialDerivatives(const cv::Mat& radialInput, const cv::Mat& depth,
                                           const SuggestiveSettings& settings) {
    checkInputs("computeRadialDerivatives()", radialInput, depth, settings);
    const cv::Mat radial = settings.smoothing > 0.0f ? smoothRadialField(radialInput, depth, settings) : radialInput;
    if (settings.stencil == DifferenceStencil::Central5) return wideRadialDerivatives(radial, depth, settings);
    const int rows = radial.rows;
    const int cols = radial.cols;
    cv::Mat normalDistance(radial.size(), CV_32FC1);
    cv::Mat imageWX(radial.size(), CV_32FC1);
    cv::Mat imageWY(radial.size(), CV_32FC1);
    for (int row = 0; row < rows; ++row)
        splitRadialRow(radial.ptr<cv::Vec4f>(row), Span{0, cols}, normalDistance.ptr<float>(row),
                       imageWX.ptr<float>(row), imageWY.ptr<float>(row));

    RadialDerivatives result;
    result.dw = cv::Mat::zeros(radial.size(), CV_32FC1);
    result.dwdw = cv::Mat::zeros(radial.size(), CV_32FC1);
    result.valid = cv::Mat::zeros(radial.size(), CV_8UC1);
    cv::Mat defined = cv::Mat::zeros(radial.size(), CV_32FC1);
    for (int row = 1; row + 1 < rows; ++row) {
        const RowInputs in{depth.ptr<float>(row - 1),      depth.ptr<float>(row),
                           depth.ptr<float>(row + 1),      normalDistance.ptr<float>(row - 1),
                           normalDistance.ptr<float>(row), normalDistance.ptr<float>(row + 1),
                           imageWX.ptr<float>(row),        imageWY.ptr<float>(row)};
        differentiateAlongW(in, 1, cols - 1, settings.depthJump, result.dw.ptr<float>(row), defined.ptr<float>(row));
    }
    const float minSinThetaSquared = settings.minSinTheta * settings.minSinTheta;
    for (int row = 1; row + 1 < rows; ++row) {
        const auto* radialRow = radial.ptr<cv::Vec4f>(row);
        for (int col = 1; col + 1 < cols; ++col) {
            const auto dwdw =
                secondDerivativeAt(radialRow[col], col, result.dw.ptr<float>(row - 1), result.dw.ptr<float>(row),
                                   result.dw.ptr<float>(row + 1), defined.ptr<float>(row - 1), defined.ptr<float>(row),
                                   defined.ptr<float>(row + 1), minSinThetaSquared);
            if (!dwdw) continue;
            result.dwdw.at<float>(row, col) = *dwdw;
            result.valid.at<uchar>(row, col) = 255;
        }
    }
    return result;
}

LineSkeleton extractSuggestiveContours(const cv::Mat& radialInput, const cv::Mat& depth,
                                       const SuggestiveSettings& settings) {
    checkInputs("extractSuggestiveContours()", radialInput, depth, settings);
    const cv::Mat radial = settings.smoothing > 0.0f ? smoothRadialField(radialInput, depth, settings) : radialInput;
    if (settings.stencil == DifferenceStencil::Central5)
        return crossingsOfMaps(radial, wideRadialDerivatives(radial, depth, settings), settings);
    LineSkeleton skeleton;
    skeleton.mask = cv::Mat::zeros(radial.size(), CV_8UC1);

    // Bands of at least kMinBandRows rows, one per thread: each re-reads three rows above it, so thin bands cost more
    // than they save. The result does not depend on the band count.
    constexpr int kMinBandRows = 128;
    const int bandCount = std::max(1, std::min(cv::getNumThreads(), radial.rows / kMinBandRows));
    std::vector<BandResult> bands(static_cast<size_t>(bandCount));
    const auto scanBands = [&](const cv::Range& range) {
        for (int band = range.start; band < range.end; ++band) {
            const int firstRow = int(int64_t(radial.rows) * band / bandCount);
            const int endRow = int(int64_t(radial.rows) * (band + 1) / bandCount);
            bands[size_t(band)] = BandScanner(radial, depth, settings, skeleton.mask, firstRow, endRow).scan();
        }
    };
    if (bandCount == 1)
        scanBands(cv::Range(0, 1));
    else
        cv::parallel_for_(cv::Range(0, bandCount), scanBands, bandCount);

    for (const BandResult& band : bands) {
        skeleton.points.insert(skeleton.points.end(), band.points.begin(), band.points.end());
        for (const cv::Point& marked : band.marksAboveBand) skeleton.mask.ptr<uchar>(marked.y)[marked.x] = 255;
    }
    return skeleton;
}

} // namespace inkgraph
