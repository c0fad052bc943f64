#include "postfx/SuggestiveContours.h"
#include "postfx/SizeText.h"

#include <opencv2/core/hal/intrin.hpp>
#include <opencv2/core.hpp>
#include <opencv2/core/utility.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
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

bool isFiniteAtLeast(float value, float lowest) { return std::isfinite(value) && value >= lowest; }

void checkInputs(const std::string& function, const cv::Mat& radial, const cv::Mat& depth, const cv::Mat& surface,
                 const SuggestiveSettings& settings) {
    if (radial.type() != CV_32FC4 || radial.empty())
        throw std::invalid_argument(function + ": 'radial' must be a non-empty CV_32FC4 image");
    if (depth.type() != CV_32FC1 || depth.size() != radial.size())
        throw std::invalid_argument(function + ": 'depth' must be CV_32FC1 of " + sizeText(radial.size()));
    if (!surface.empty() && (surface.type() != CV_32FC1 || surface.size() != radial.size()))
        throw std::invalid_argument(function + ": 'surface' must be empty or CV_32FC1 of " + sizeText(radial.size()));
    if (!(isFiniteAtLeast(settings.minSinTheta, 0.0f) && settings.minSinTheta < 1.0f))
        throw std::invalid_argument(function + ": 'minSinTheta' must lie in [0, 1)");
    if (!(isFiniteAtLeast(settings.featureSize, 0.0f) && settings.featureSize > 0.0f))
        throw std::invalid_argument(function + ": 'featureSize' must be positive and finite");
    if (!isFiniteAtLeast(settings.threshold, 0.0f))
        throw std::invalid_argument(function + ": 'threshold' must be finite and >= 0");
    if (!isFiniteAtLeast(settings.fade, 0.0f))
        throw std::invalid_argument(function + ": 'fade' must be finite and >= 0");
    if (!(isFiniteAtLeast(settings.minAngleToW, 0.0f) && settings.minAngleToW < 90.0f))
        throw std::invalid_argument(function + ": 'minAngleToW' must be at least 0 and below 90 degrees");
    if (!(isFiniteAtLeast(settings.depthJump, 0.0f) && settings.depthJump > 0.0f))
        throw std::invalid_argument(function + ": 'depthJump' must be positive and finite");
    if (!isFiniteAtLeast(settings.smoothing, 0.0f))
        throw std::invalid_argument(function + ": 'smoothing' must be finite and >= 0");
    if (!isFiniteAtLeast(settings.breakClearance, 0.0f))
        throw std::invalid_argument(function + ": 'breakClearance' must be finite and >= 0");
    if (!isFiniteAtLeast(settings.patchClearance, 0.0f))
        throw std::invalid_argument(function + ": 'patchClearance' must be finite and >= 0");
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

/** Whether a pixel of depth `depth` and its four neighbours lie on one surface: it is covered and joins each
 *  (joinsNeighbour()). Where not, a central difference there would read across the surface's end. */
inline bool joinsFourNeighbours(float depth, float left, float right, float above, float below, float depthJump) {
    return depth > 0.0f && joinsNeighbour(depth, left, depthJump) && joinsNeighbour(depth, right, depthJump) &&
           joinsNeighbour(depth, above, depthJump) && joinsNeighbour(depth, below, depthJump);
}

#if CV_SIMD128
inline v_float32x4 joinsNeighbour(const v_float32x4& depth, const v_float32x4& neighbourDepth,
                                  const v_float32x4& depthJump) {
    return (neighbourDepth > cv::v_setzero_f32()) &
           (cv::v_abs(depth - neighbourDepth) <= depthJump * cv::v_min(depth, neighbourDepth));
}
#endif

/** Row `row` of the surface ids, or null without ids (every pixel then of one surface as far as ids tell). */
inline const float* surfaceRow(const cv::Mat& surface, int row) {
    return surface.empty() ? nullptr : surface.ptr<float>(row);
}

/** Whether two pixels carry the same surface id: rows from surfaceRow(), both null or neither. */
inline bool sameSurfaceId(const float* idsA, int colA, const float* idsB, int colB) {
    return idsA == nullptr || idsA[colA] == idsB[colB];
}

/** One row's inputs to differentiateAlongW(): linear depth of the row and its neighbours, n.(c - p) likewise, and
 *  J w of the row, each indexed by column. */
struct RowInputs {
    const float* depthAbove;
    const float* depth;
    const float* depthBelow;
    /** The surface ids of the same rows (surfaceRow()), or all three null. */
    const float* surfaceAbove;
    const float* surface;
    const float* surfaceBelow;
    const float* normalDistanceAbove;
    const float* normalDistance;
    const float* normalDistanceBelow;
    const float* imageWX;
    const float* imageWY;
};

/** D_w(n.v) over columns [begin, end) of an interior row: the central differences of n.(c - p) dotted with J w,
 *  defined (1) where the pixel and its four neighbours lie on one surface (no depth break, and the same surface id
 *  where there are ids), which keeps background out too; dw = 0
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
        const v_float32x4 onOneDepthRun = (z > zero) & joinsNeighbour(z, cv::v_load(in.depth + col - 1), jump) &
                                          joinsNeighbour(z, cv::v_load(in.depth + col + 1), jump) &
                                          joinsNeighbour(z, cv::v_load(in.depthAbove + col), jump) &
                                          joinsNeighbour(z, cv::v_load(in.depthBelow + col), jump);
        v_float32x4 onOneSurface = onOneDepthRun;
        if (in.surface != nullptr) {
            const v_float32x4 id = cv::v_load(in.surface + col);
            onOneSurface = onOneSurface & (id == cv::v_load(in.surface + col - 1)) &
                           (id == cv::v_load(in.surface + col + 1)) & (id == cv::v_load(in.surfaceAbove + col)) &
                           (id == cv::v_load(in.surfaceBelow + col));
        }
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
        const bool onOneSurface =
            joinsFourNeighbours(in.depth[col], in.depth[col - 1], in.depth[col + 1], in.depthAbove[col],
                                in.depthBelow[col], depthJump) &&
            (in.surface == nullptr ||
             (in.surface[col] == in.surface[col - 1] && in.surface[col] == in.surface[col + 1] &&
              in.surface[col] == in.surfaceAbove[col] && in.surface[col] == in.surfaceBelow[col]));
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

constexpr double kRadiansPerDegree = 3.14159265358979323846 / 180.0;

/** sin^2 of SuggestiveSettings::minAngleToW, the bound wellConditioned() compares with. */
float minSinAngleToWSquared(const SuggestiveSettings& settings) {
    const float sine = float(std::sin(double(settings.minAngleToW) * kRadiansPerDegree));
    return sine * sine;
}

/** Whether the sign of D_w D_w(n.v) = gradient . J w, from differences of D_w(n.v), can be trusted: the gradient of
 *  D_w(n.v) (a line's normal, where D_w(n.v) = 0) is at least the angle asin(sqrt(minSinAngleSquared)) away from
 *  perpendicular to J w, i.e. a line there crosses w at least at that angle, and D_w D_w(n.v) > 0. Where a line
 *  runs nearly along w, D_w D_w(n.v) is a small difference of large terms that the differences' error decides: a
 *  valley of D_w(n.v) two pixels wide flips its sign with the sub-pixel phase at 1024 rows and not at 2048
 *  (docs/strokes.md). 0 admits every pixel, the plain test of DeCarlo et al. */
inline bool wellConditioned(float gradientX, float gradientY, float wx, float wy, float minSinAngleSquared) {
    if (!(minSinAngleSquared > 0.0f)) return true;
    const float along = gradientX * wx + gradientY * wy;
    return along > 0.0f &&
           along * along >= minSinAngleSquared * (gradientX * gradientX + gradientY * gradientY) * (wx * wx + wy * wy);
}

/** D_w D_w(n.v) at one pixel from the D_w(n.v) rows above, at and below it, or nothing where it is invalid: a
 *  neighbour's D_w undefined (so every difference involved stays on the pixel's surface), n.v <= 0, sin(theta)
 *  below the cut-off, or its sign not to be trusted (wellConditioned()). The caller keeps the pixel off the image's
 *  edges. */
std::optional<float> secondDerivativeAt(const cv::Vec4f& radial, int col, const float* dwAbove, const float* dw,
                                        const float* dwBelow, const float* definedAbove, const float* defined,
                                        const float* definedBelow, float minSinThetaSquared, float minSinAngleSquared) {
    if (!(defined[col - 1] > 0.0f && defined[col + 1] > 0.0f && definedAbove[col] > 0.0f && definedBelow[col] > 0.0f))
        return std::nullopt;
    if (!facesAwayFromFrontal(radial, minSinThetaSquared)) return std::nullopt;
    const float gradientX = dw[col + 1] - dw[col - 1];
    const float gradientY = dwBelow[col] - dwAbove[col];
    if (!wellConditioned(gradientX, gradientY, radial[kImageWX], radial[kImageWY], minSinAngleSquared))
        return std::nullopt;
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
    // instead of popping in at a fixed strength. A denominator that is positive but tiny (a few pixels of a small
    // model, where w and n.(c - p) nearly vanish together) overflows the strength to infinity, whose fade is 1, not
    // infinity over infinity.
    const float excess = strength - rule.threshold;
    const float alpha = rule.fade > 0.0f && std::isfinite(excess) ? excess / (excess + rule.fade) : 1.0f;
    return Crossing{t, alpha, std::abs(dwA) <= std::abs(dwB)};
}

/** The point of a crossing between (colA, rowA) and its neighbour to the right, or below when `downward`. */
cv::Point2f crossingPosition(int rowA, int colA, bool downward, float t) {
    return {float(colA) + (downward ? 0.0f : t), float(rowA) + (downward ? t : 0.0f)};
}

/** The Gaussian's weights at distances 0..reach of one sigma level, and their sum over the whole window. */
struct GaussianWindow {
    std::vector<float> weights;
    int reach = 0;
    float total = 0.0f;

    /** The weights' moments over a cut window d = -low .. high: (sum g, sum g d, sum g d^2), summed in that order of
     *  d, as smoothPixel() once summed them per pixel. They depend on the cut alone, so a pass reuses them for every
     *  pixel cut alike: kept for windows up to kMomentTableReach (a table of (reach + 1)^2 cuts, filled as met). */
    std::array<float, 3> momentsOf(int low, int high) const {
        if (reach > kMomentTableReach) return sumMoments(low, high);
        if (mMoments.empty()) mMoments.assign(size_t(reach + 1) * size_t(reach + 1), {-1.0f, 0.0f, 0.0f});
        std::array<float, 3>& moments = mMoments[size_t(low) * size_t(reach + 1) + size_t(high)];
        if (moments[0] < 0.0f) moments = sumMoments(low, high);
        return moments;
    }

private:
    static constexpr int kMomentTableReach = 32;

    std::array<float, 3> sumMoments(int low, int high) const {
        float s0 = 0.0f, s1 = 0.0f, s2 = 0.0f;
        for (int d = -low; d <= high; ++d) {
            const float g = weights[size_t(std::abs(d))];
            const float gd = g * float(d);
            s0 += g;
            s1 += gd;
            s2 += gd * float(d);
        }
        return {s0, s1, s2};
    }

    mutable std::vector<std::array<float, 3>> mMoments; ///< momentsOf()'s table; s0 < 0: not summed yet
};

/** Sigmas are rounded to levels a 1% step apart: neighbouring pixels see nearly the same depth, so few windows are
 *  built, and the rounding moves the Gaussian far less than the smoothing itself does. */
constexpr double kSigmaStep = 1.01;

/** Marks a pixel smoothRadialField() leaves as it is (off the model) among the sigma levels. */
constexpr int16_t kUnsmoothed = std::numeric_limits<int16_t>::min();

/** The level of `sigma` pixels (> 0). Every finite float's level fits in int16 (|level| < 10500); infinity takes the
 *  largest, whose window is the widest allowed. */
int16_t sigmaLevel(float sigma) {
    if (!(sigma < std::numeric_limits<float>::infinity())) return std::numeric_limits<int16_t>::max();
    // std::lround() without its library call: the integer part, then the fraction (exact: x - trunc(x) is
    // representable) rounded half away from zero.
    const double exact = std::log(sigma) / std::log(kSigmaStep);
    int level = int(exact);
    const double fraction = exact - double(level);
    if (fraction >= 0.5) ++level;
    if (fraction <= -0.5) --level;
    return int16_t(level);
}

/** The variance in px^2 of the blur a stencil's first difference adds along its axis: (f(x+1) - f(x-1)) / 2 answers
 *  a wave of frequency k (radians per pixel) with sin(k) / k = 1 - k^2 / 6 + ..., as a Gaussian of variance 1/3 does;
 *  the 5-point difference's error has no k^2 term. */
double differenceVariance(DifferenceStencil stencil) {
    return stencil == DifferenceStencil::Central3 ? 1.0 / 3.0 : 0.0;
}

/** The narrowest window smoothRadialField() applies, in px^2 of variance: a quarter pixel's sigma, whose weight a pixel
 *  away is 3e-4, so a pixel whose sigma is under the differences' own blur is left nearly as it is. */
constexpr double kLeastWindowVariance = 1.0 / 16.0;

/** The window of one level with `subtractedVariance` px^2 taken off its variance (no less than
 *  kLeastWindowVariance): 3 of its sigmas wide, at most kMaxSmoothingReach. */
GaussianWindow gaussianWindow(int level, double subtractedVariance) {
    GaussianWindow window;
    const double nominal = std::pow(kSigmaStep, double(level));
    const double sigma = std::sqrt(std::max(nominal * nominal - subtractedVariance, kLeastWindowVariance));
    window.reach = int(std::min(double(kMaxSmoothingReach), std::ceil(3.0 * sigma)));
    window.weights.resize(size_t(window.reach) + 1);
    for (int d = 0; d <= window.reach; ++d) window.weights[size_t(d)] = float(std::exp(-0.5 * d * d / (sigma * sigma)));
    window.total = window.weights[0];
    for (int d = 1; d <= window.reach; ++d) window.total += 2.0f * window.weights[size_t(d)];
    return window;
}

/** The windows of the levels met so far, built on first use; one per thread, so none is shared. Indexed by level from
 *  the lowest met: an image's levels lie within a few hundred of each other, and a lookup per pixel by hash showed
 *  in profiles. */
class GaussianWindows {
public:
    /** `subtractedVariance`: gaussianWindow()'s. */
    explicit GaussianWindows(double subtractedVariance) : mSubtractedVariance(subtractedVariance) {}

    const GaussianWindow& forLevel(int level) {
        if (mWindows.empty()) mFirstLevel = level;
        if (level < mFirstLevel) {
            std::vector<std::unique_ptr<GaussianWindow>> grown(std::size_t(mFirstLevel - level) + mWindows.size());
            std::move(mWindows.begin(), mWindows.end(), grown.end() - std::ptrdiff_t(mWindows.size()));
            mWindows = std::move(grown);
            mFirstLevel = level;
        }
        const std::size_t index = std::size_t(level - mFirstLevel);
        if (index >= mWindows.size()) mWindows.resize(index + 1);
        std::unique_ptr<GaussianWindow>& window = mWindows[index];
        if (!window) window = std::make_unique<GaussianWindow>(gaussianWindow(level, mSubtractedVariance));
        return *window;
    }

private:
    std::vector<std::unique_ptr<GaussianWindow>> mWindows; // mWindows[i]: level mFirstLevel + i, or not built yet
    int mFirstLevel = 0;
    double mSubtractedVariance;
};

/** sigmaLevel() for runs of pixels of nearly one sigma: the last level with the sigmas well inside its rounding
 *  interval, where the level is that one without a logarithm. The margin (1e-4 of a level) is far wider than the
 *  logarithm's rounding error, so every level is the one sigmaLevel() gives. */
class SigmaLevels {
public:
    int16_t levelOf(float sigma) {
        if (double(sigma) >= mLowest && double(sigma) <= mHighest) return mLevel;
        mLevel = sigmaLevel(sigma);
        if (mLevel == std::numeric_limits<int16_t>::max() || mLevel == std::numeric_limits<int16_t>::min()) {
            mLowest = 1.0; // the extremes are never cached: an empty interval
            mHighest = 0.0;
            return mLevel;
        }
        constexpr double kMargin = 1e-4;
        const double logStep = std::log(kSigmaStep);
        mLowest = std::exp((double(mLevel) - 0.5 + kMargin) * logStep);
        mHighest = std::exp((double(mLevel) + 0.5 - kMargin) * logStep);
        return mLevel;
    }

private:
    int16_t mLevel = 0;
    double mLowest = 1.0;
    double mHighest = 0.0;
};

/** One pixel of a 1-D pass of smoothRadialField(): the Gaussian-weighted least-squares line through the pixels
 *  `at(d)` (4 floats each) for d = -before .. after (its run of one surface, cut to the window), at d = 0. For a whole
 *  window it is the plain Gaussian mean, summed in pairs; near a run's end the fitted line, so a linear field stays
 *  exact there instead of being pulled toward the inside. */
template <typename Neighbour>
void smoothPixel(Neighbour at, int before, int after, const GaussianWindow& window, float* out) {
    const int low = std::min(before, window.reach);
    const int high = std::min(after, window.reach);
    const float* weights = window.weights.data();
    if (low == window.reach && high == window.reach) {
#if CV_SIMD128
        v_float32x4 sum = cv::v_load(at(0)) * cv::v_setall_f32(weights[0]);
        for (int d = 1; d <= window.reach; ++d)
            sum = cv::v_fma(cv::v_load(at(d)) + cv::v_load(at(-d)), cv::v_setall_f32(weights[d]), sum);
        cv::v_store(out, sum * cv::v_setall_f32(1.0f / window.total));
#else
        for (int c = 0; c < 4; ++c) {
            float sum = at(0)[c] * weights[0];
            for (int d = 1; d <= window.reach; ++d) sum += (at(d)[c] + at(-d)[c]) * weights[d];
            out[c] = sum * (1.0f / window.total);
        }
#endif
        return;
    }
    if (low + high == 0) {
        std::copy(at(0), at(0) + 4, out);
        return;
    }
    const auto [s0, s1, s2] = window.momentsOf(low, high);
    // The line a + b d fitted at d = 0: a = (s2 t0 - s1 t1) / (s0 s2 - s1^2); with a degenerate window the weighted
    // mean. t0 and t1 are summed per channel as mul then add, in the order of d.
    const float determinant = s0 * s2 - s1 * s1;
    const bool fitsALine = determinant > 1e-6f * s0 * s2;
#if CV_SIMD128
    v_float32x4 t0 = cv::v_setzero_f32(), t1 = cv::v_setzero_f32();
    for (int d = -low; d <= high; ++d) {
        const float g = weights[std::abs(d)];
        const v_float32x4 v = cv::v_load(at(d));
        t0 = t0 + cv::v_setall_f32(g) * v;
        t1 = t1 + cv::v_setall_f32(g * float(d)) * v;
    }
    const v_float32x4 value =
        fitsALine ? (cv::v_setall_f32(s2) * t0 - cv::v_setall_f32(s1) * t1) * cv::v_setall_f32(1.0f / determinant)
                  : t0 * cv::v_setall_f32(1.0f / s0);
    cv::v_store(out, value);
#else
    cv::Vec4f t0 = cv::Vec4f::all(0.0f), t1 = cv::Vec4f::all(0.0f);
    for (int d = -low; d <= high; ++d) {
        const float g = weights[std::abs(d)];
        const cv::Vec4f v(at(d));
        t0 += g * v;
        t1 += (g * float(d)) * v;
    }
    const cv::Vec4f value = fitsALine ? (s2 * t0 - s1 * t1) * (1.0f / determinant) : t0 * (1.0f / s0);
    std::copy(value.val, value.val + 4, out);
#endif
}

#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
#define INKGRAPH_AVX2_DISPATCH 1
#endif

/** Eight floats as one value (GCC's vector extension): two pixels of the radial field. Built for the baseline target
 *  it is two SSE registers; inside an AVX2 function, one. */
typedef float EightFloats __attribute__((vector_size(32)));

/** The whole-window sums of eight neighbouring pixels of one sigma level: taps[reach + d] points at the first
 *  pixel's neighbour d along the pass, and the other seven pixels' neighbours follow it, 4 floats each. Every float
 *  is summed with the operations, in the order, of smoothPixels()'s four-pixel block and of smoothPixel() (the
 *  centre times its weight, then (ahead + behind) x weight added for d = 1 .. reach, then times 1 / total; no fused
 *  multiply-add: x86-64's baseline has none, and the AVX2 target below enables none), so on x86-64 the result is the
 *  same to the bit whichever block or instruction set computes it. Four independent sums of two pixels each keep
 *  twice the work in flight that the four-pixel block does. */
__attribute__((always_inline)) inline void sumEightWholeWindowsBody(const float* const* taps, int reach,
                                                                    const float* weights, float scale, float* out) {
    const EightFloats zero = {};
    const float* centre = taps[reach];
    EightFloats sum0, sum1, sum2, sum3;
    std::memcpy(&sum0, centre, sizeof sum0);
    std::memcpy(&sum1, centre + 8, sizeof sum1);
    std::memcpy(&sum2, centre + 16, sizeof sum2);
    std::memcpy(&sum3, centre + 24, sizeof sum3);
    const EightFloats centreWeight = zero + weights[0];
    sum0 *= centreWeight;
    sum1 *= centreWeight;
    sum2 *= centreWeight;
    sum3 *= centreWeight;
    for (int d = 1; d <= reach; ++d) {
        const float* ahead = taps[reach + d];
        const float* behind = taps[reach - d];
        const EightFloats weight = zero + weights[d];
        EightFloats a0, a1, a2, a3, b0, b1, b2, b3;
        std::memcpy(&a0, ahead, sizeof a0);
        std::memcpy(&a1, ahead + 8, sizeof a1);
        std::memcpy(&a2, ahead + 16, sizeof a2);
        std::memcpy(&a3, ahead + 24, sizeof a3);
        std::memcpy(&b0, behind, sizeof b0);
        std::memcpy(&b1, behind + 8, sizeof b1);
        std::memcpy(&b2, behind + 16, sizeof b2);
        std::memcpy(&b3, behind + 24, sizeof b3);
        sum0 = (a0 + b0) * weight + sum0;
        sum1 = (a1 + b1) * weight + sum1;
        sum2 = (a2 + b2) * weight + sum2;
        sum3 = (a3 + b3) * weight + sum3;
    }
    const EightFloats scale8 = zero + scale;
    sum0 *= scale8;
    sum1 *= scale8;
    sum2 *= scale8;
    sum3 *= scale8;
    std::memcpy(out, &sum0, sizeof sum0);
    std::memcpy(out + 8, &sum1, sizeof sum1);
    std::memcpy(out + 16, &sum2, sizeof sum2);
    std::memcpy(out + 24, &sum3, sizeof sum3);
}

void sumEightWholeWindowsBaseline(const float* const* taps, int reach, const float* weights, float scale, float* out) {
    sumEightWholeWindowsBody(taps, reach, weights, scale, out);
}

#ifdef INKGRAPH_AVX2_DISPATCH
// AVX2 without FMA: the target's only new operations are wider registers, so nothing is fused or reordered.
__attribute__((target("avx2"))) void sumEightWholeWindowsAvx2(const float* const* taps, int reach, const float* weights,
                                                              float scale, float* out) {
    sumEightWholeWindowsBody(taps, reach, weights, scale, out);
}
#endif

/** sumEightWholeWindowsBody() with the widest registers this CPU has: the smoothing is the largest kernel of a comic
 *  still (docs/performance.md), and Debian's builds target the baseline x86-64, whose vectors hold one pixel. */
void sumEightWholeWindows(const float* const* taps, int reach, const float* weights, float scale, float* out) {
#ifdef INKGRAPH_AVX2_DISPATCH
    static const bool hasAvx2 = (__builtin_cpu_init(), __builtin_cpu_supports("avx2") != 0);
    if (hasAvx2) {
        sumEightWholeWindowsAvx2(taps, reach, weights, scale, out);
        return;
    }
#endif
    sumEightWholeWindowsBaseline(taps, reach, weights, scale, out);
}

/** Pixels [begin, end) of one line of a pass: pixel i's neighbour d along the pass is at(i, d) (4 floats), its sigma
 *  level levels[i] (kUnsmoothed: copied), its run before[i] and after[i] pixels either side. Four neighbouring pixels
 *  of one level with whole windows are summed together, each in its own register, so their sums do not wait on each
 *  other; each sum is formed as smoothPixel() forms it. */
template <typename Neighbour>
void smoothPixels(int begin, int end, const int16_t* levels, const int* before, const int* after, Neighbour at,
                  GaussianWindows& windows, cv::Vec4f* out) {
    for (int i = begin; i < end;) {
        const int level = levels[i];
        if (level == kUnsmoothed) {
            std::copy(at(i, 0), at(i, 0) + 4, out[i].val);
            ++i;
            continue;
        }
        const GaussianWindow& window = windows.forLevel(level);
        const int reach = window.reach;
        if (i + 8 <= end && std::all_of(levels + i + 1, levels + i + 8, [level](int16_t l) { return l == level; }) &&
            *std::min_element(before + i, before + i + 8) >= reach &&
            *std::min_element(after + i, after + i + 8) >= reach) {
            // at(i + k, d) is at(i, d) + 4 k, as below.
            std::array<const float*, 2 * kMaxSmoothingReach + 1> taps;
            for (int d = -reach; d <= reach; ++d) taps[size_t(reach + d)] = at(i, d);
            sumEightWholeWindows(taps.data(), reach, window.weights.data(), 1.0f / window.total, out[i].val);
            i += 8;
            continue;
        }
#if CV_SIMD128
        if (i + 4 <= end && levels[i + 1] == level && levels[i + 2] == level && levels[i + 3] == level &&
            std::min({before[i], before[i + 1], before[i + 2], before[i + 3]}) >= reach &&
            std::min({after[i], after[i + 1], after[i + 2], after[i + 3]}) >= reach) {
            // at(i + k, d) is at(i, d) + 4 k: the four pixels lie side by side in every row the window reads.
            const float* weights = window.weights.data();
            const v_float32x4 centreWeight = cv::v_setall_f32(weights[0]);
            const float* centre = at(i, 0);
            v_float32x4 sum0 = cv::v_load(centre) * centreWeight;
            v_float32x4 sum1 = cv::v_load(centre + 4) * centreWeight;
            v_float32x4 sum2 = cv::v_load(centre + 8) * centreWeight;
            v_float32x4 sum3 = cv::v_load(centre + 12) * centreWeight;
            for (int d = 1; d <= reach; ++d) {
                const float* ahead = at(i, d);
                const float* behind = at(i, -d);
                const v_float32x4 weight = cv::v_setall_f32(weights[d]);
                sum0 = cv::v_fma(cv::v_load(ahead) + cv::v_load(behind), weight, sum0);
                sum1 = cv::v_fma(cv::v_load(ahead + 4) + cv::v_load(behind + 4), weight, sum1);
                sum2 = cv::v_fma(cv::v_load(ahead + 8) + cv::v_load(behind + 8), weight, sum2);
                sum3 = cv::v_fma(cv::v_load(ahead + 12) + cv::v_load(behind + 12), weight, sum3);
            }
            const v_float32x4 scale = cv::v_setall_f32(1.0f / window.total);
            cv::v_store(out[i].val, sum0 * scale);
            cv::v_store(out[i + 1].val, sum1 * scale);
            cv::v_store(out[i + 2].val, sum2 * scale);
            cv::v_store(out[i + 3].val, sum3 * scale);
            i += 4;
            continue;
        }
#endif
        smoothPixel([&](int d) { return at(i, d); }, before[i], after[i], window, out[i].val);
        ++i;
    }
}

/** Whether pixel `depth` and the next one along a line are of one run of one surface: both covered, no depth break
 *  (as isDepthBreak() has it; the relation is symmetric). */
inline bool joinsNext(float depth, float nextDepth, float depthJump) {
    return depth > 0.0f && joinsNeighbour(depth, nextDepth, depthJump);
}

/** How far from where its surface ends (`breakDepth`, `marginPixels`) or its smooth patch meets another
 *  (`patchDepth`) a crossing must lie. A depth is a band's width in pixels times the depth: settings' clearance x the
 *  smoothing's sigma x the focal length, so the band is `depth / z` pixels at depth z. */
struct EndBands {
    float breakDepth = 0.0f;   ///< settings.breakClearance's band; 0 without smoothing
    float marginPixels = 0.0f; ///< sizeMarginPixels()
    float patchDepth = 0.0f;   ///< settings.patchClearance's band; 0 without smoothing or surface ids
    bool any() const { return breakDepth > 0.0f || marginPixels > 0.0f || patchDepth > 0.0f; }
};

/** Above this many data rows a crossing keeps the second difference's reach at this many rows (two pixels for the
 *  3-point stencil, four for the 5-point one) from where its surface ends, as the same share of the height. */
constexpr int kStencilReferenceRows = 1024;

/** The margin from a surface end of an image `rows` high, in pixels: 0 up to kStencilReferenceRows rows, where the
 *  stencil's own reach is the margin; above, that reach x rows / kStencilReferenceRows. At 2048^2 the stencil alone
 *  leaves crossings 2-4 pixels from an end, where the smoothing's window sees one side only and that strip of surface
 *  is as wide as 1-2 pixels at 1024^2: the lines there came and went with the size (docs/strokes.md). */
float sizeMarginPixels(const SuggestiveSettings& settings, int rows) {
    if (rows <= kStencilReferenceRows) return 0.0f;
    const float reach = settings.stencil == DifferenceStencil::Central5 ? 4.0f : 2.0f;
    return reach * float(rows) / float(kStencilReferenceRows);
}

/** The bands of an image `rows` high; the patches' only with surface ids. */
EndBands endBandsOf(const SuggestiveSettings& settings, int rows, const cv::Mat& surface) {
    EndBands bands;
    const float sigmaDepth = settings.smoothing > 0.0f ? settings.smoothing * settings.focalPixels : 0.0f;
    bands.breakDepth = settings.breakClearance * sigmaDepth;
    bands.marginPixels = sizeMarginPixels(settings, rows);
    if (!surface.empty()) bands.patchDepth = settings.patchClearance * sigmaDepth;
    return bands;
}

/** Whether the surface ends at pixel (row, col): it is off the image or the model, or a 4-neighbour is, or lies
 *  across a depth break or on another surface (`surface`'s ids, when not empty). */
bool surfaceEndsAt(const cv::Mat& depth, const cv::Mat& surface, int row, int col, float depthJump) {
    if (row < 1 || col < 1 || row + 1 >= depth.rows || col + 1 >= depth.cols) return true;
    const float* z = depth.ptr<float>(row);
    if (!joinsFourNeighbours(z[col], z[col - 1], z[col + 1], depth.ptr<float>(row - 1)[col],
                             depth.ptr<float>(row + 1)[col], depthJump))
        return true;
    const float* ids = surfaceRow(surface, row);
    return !(sameSurfaceId(ids, col, ids, col - 1) && sameSurfaceId(ids, col, ids, col + 1) &&
             sameSurfaceId(ids, col, surfaceRow(surface, row - 1), col) &&
             sameSurfaceId(ids, col, surfaceRow(surface, row + 1), col));
}

/** Whether covered pixel (row, col) lies where its smooth patch meets another: a covered 4-neighbour carries
 *  another surface id. The background and the image's edge are not patches. */
bool meetsAnotherPatchAt(const cv::Mat& depth, const cv::Mat& surface, int row, int col) {
    if (row < 1 || col < 1 || row + 1 >= depth.rows || col + 1 >= depth.cols || depth.at<float>(row, col) <= 0.0f)
        return false;
    const float* ids = surfaceRow(surface, row);
    const auto other = [&](int neighbourRow, int neighbourCol) {
        return depth.at<float>(neighbourRow, neighbourCol) > 0.0f &&
               !sameSurfaceId(ids, col, surfaceRow(surface, neighbourRow), neighbourCol);
    };
    return other(row, col - 1) || other(row, col + 1) || other(row - 1, col) || other(row + 1, col);
}

/** Whether covered pixel (row, col) lies within a band of where its surface ends or its patch meets another
 *  (EndBands): along its row, its column or a diagonal (a diagonal step counts sqrt(2)), a pixel within the band's
 *  distance where the surface ends (surfaceEndsAt(); its band is the larger of breakDepth / depth and marginPixels)
 *  or where the patch meets another (meetsAnotherPatchAt(); patchDepth / depth). A pixel's four neighbours are read,
 *  so a fold whose depth breaks only every few pixels (a surface turning away at a contour, where neighbouring
 *  pixels' depths differ by about the break test's limit) ends the surface as a whole break does. Each band is capped
 *  at kMaxSmoothingReach, as the smoothing's window is. */
bool nearSurfaceEnd(const cv::Mat& depth, const cv::Mat& surface, int row, int col, const EndBands& bands,
                    float depthJump) {
    const double z = double(depth.at<float>(row, col));
    const double reach = double(kMaxSmoothingReach);
    const double endBand = std::min(std::max(double(bands.breakDepth) / z, double(bands.marginPixels)), reach);
    const double patchBand = std::min(double(bands.patchDepth) / z, reach);
    for (int rowStep = -1; rowStep <= 1; ++rowStep) {
        for (int colStep = -1; colStep <= 1; ++colStep) {
            if (rowStep == 0 && colStep == 0) continue;
            const double stepLength = rowStep != 0 && colStep != 0 ? std::sqrt(2.0) : 1.0;
            const int endSteps = int(endBand / stepLength), patchSteps = int(patchBand / stepLength);
            for (int step = 1; step <= std::max(endSteps, patchSteps); ++step) {
                const int r = row + step * rowStep, c = col + step * colStep;
                if (step <= endSteps && surfaceEndsAt(depth, surface, r, c, depthJump)) return true;
                if (step <= patchSteps && meetsAnotherPatchAt(depth, surface, r, c)) return true;
            }
        }
    }
    return false;
}

/** Each row's covered span (coveredSpan()), found once for the smoother, the scanner and the bands. */
std::vector<Span> coveredSpans(const cv::Mat& depth) {
    std::vector<Span> spans(size_t(depth.rows));
    for (int row = 0; row < depth.rows; ++row) spans[size_t(row)] = coveredSpan(depth.ptr<float>(row), depth.cols);
    return spans;
}

/** The widest window any pixel of the image gets: that of the nearest covered depth, before the differences' variance
 *  is taken off (so it bounds every window). 0 when nothing is covered. */
int widestReach(const cv::Mat& depth, const std::vector<Span>& spans, float sigmaDepth) {
    const float infinity = std::numeric_limits<float>::infinity();
    float nearest = infinity;
    for (int row = 0; row < depth.rows; ++row) {
        const float* z = depth.ptr<float>(row);
        const Span span = spans[size_t(row)];
        int col = span.begin;
#if CV_SIMD128
        v_float32x4 nearest4 = cv::v_setall_f32(infinity);
        for (; col + 4 <= span.end; col += 4) {
            const v_float32x4 depth4 = cv::v_load(z + col);
            nearest4 = cv::v_min(nearest4, cv::v_select(depth4 > cv::v_setzero_f32(), depth4, nearest4));
        }
        nearest = std::min(nearest, cv::v_reduce_min(nearest4));
#endif
        for (; col < span.end; ++col)
            if (z[col] > 0.0f) nearest = std::min(nearest, z[col]);
    }
    const float sigma = nearest < infinity ? sigmaDepth / nearest : 0.0f;
    return sigma > 0.0f ? gaussianWindow(sigmaLevel(sigma), 0.0).reach : 0;
}

/** smoothRadialField() one row at a time, down a band of rows: the row pass fills a ring of the rows the column pass
 *  reaches (reach above and below the row it smooths), and the column pass reads them there, so neither pass needs
 *  an image of its own or a transpose. The runs along each column are counted as the rows go by: how many pixels of
 *  the run lie above and below the current row, capped at the widest reach. Only covered spans are worked on; the
 *  rest of a row is copied from the input. */
class SurfaceSmoother {
public:
    /** `sigmaDepth`: the smoothing's sigma times the focal length in pixels (a pixel's sigma is this over its depth);
     *  `surface`: the surface ids or empty (runs also end where the id changes); `spans`: coveredSpans(); `reach`:
     *  widestReach(); `subtractedVariance`: what each window's variance loses (gaussianWindow()). Rows are then asked
     *  for in order from `firstRow`. */
    SurfaceSmoother(const cv::Mat& radial, const cv::Mat& depth, const cv::Mat& surface, const std::vector<Span>& spans,
                    float sigmaDepth, float depthJump, int reach, double subtractedVariance, int firstRow)
        : mRadial(radial), mDepth(depth), mSurface(surface), mSpans(spans), mSigmaDepth(sigmaDepth),
          mDepthJump(depthJump), mReach(reach), mSlots(2 * reach + 1), mRows(radial.rows), mCols(radial.cols),
          mNextRow(firstRow), mRowPass(size_t(mSlots) * size_t(mCols)), mLevels(size_t(mSlots) * size_t(mCols)),
          mAbove(size_t(mCols), 0), mBelow(size_t(mCols), 0), mLeft(size_t(mCols), 0), mRight(size_t(mCols), 0),
          mWindowRows(size_t(mSlots)), mWindows(subtractedVariance) {
        for (int row = std::max(0, firstRow - reach); row < std::min(mRows, firstRow + reach); ++row)
            smoothAlongRow(row);
    }

    /** What next() writes beyond the row's covered span, where the field is not smoothed. */
    enum class Uncovered {
        Copied, ///< the input's pixels: `out` holds the whole smoothed row
        Skipped ///< nothing: for a reader of the span alone (BandScanner), spared copying most of each row
    };

    /** The next row of the smoothed field, written to `out` (cols pixels). */
    void next(cv::Vec4f* out, Uncovered uncovered = Uncovered::Copied) {
        const int row = mNextRow++;
        if (row + mReach < mRows) smoothAlongRow(row + mReach);
        if (mCounted)
            countColumnRuns(row);
        else
            countColumnRunsAfresh(row);
        mCounted = true;
        const Span span = mSpans[size_t(row)];
        const cv::Vec4f* in = mRadial.ptr<cv::Vec4f>(row);
        if (uncovered == Uncovered::Copied) {
            std::copy(in, in + span.begin, out);
            std::copy(in + span.end, in + mCols, out + span.end);
        }
        for (int d = -mReach; d <= mReach; ++d)
            mWindowRows[size_t(d + mReach)] = row + d >= 0 && row + d < mRows ? &mRowPass[slotOf(row + d)] : nullptr;
        const cv::Vec4f* const* rows = &mWindowRows[size_t(mReach)];
        smoothPixels(
            span.begin, span.end, &mLevels[slotOf(row)], mAbove.data(), mBelow.data(),
            [rows](int col, int d) { return rows[d][col].val; }, mWindows, out);
    }

private:
    size_t slotOf(int row) const { return size_t(row % mSlots) * size_t(mCols); }

    /** Whether pixel (upperRow, col) and the one below it are of one run (joinsNext(), and one surface id). */
    bool joinsBelow(int upperRow, int col) const {
        return joinsNext(mDepth.ptr<float>(upperRow)[col], mDepth.ptr<float>(upperRow + 1)[col], mDepthJump) &&
               sameSurfaceId(surfaceRow(mSurface, upperRow), col, surfaceRow(mSurface, upperRow + 1), col);
    }

    /** The row pass of `row`'s span into its slot, with each pixel's sigma level (kUnsmoothed off the model). */
    void smoothAlongRow(int row) {
        const Span span = mSpans[size_t(row)];
        if (span.begin >= span.end) return;
        const float* z = mDepth.ptr<float>(row);
        const float* ids = surfaceRow(mSurface, row);
        const cv::Vec4f* in = mRadial.ptr<cv::Vec4f>(row);
        cv::Vec4f* out = &mRowPass[slotOf(row)];
        int16_t* level = &mLevels[slotOf(row)];
        // The pixels beyond the span are not covered, so no run crosses its ends.
        mLeft[size_t(span.begin)] = 0;
        for (int col = span.begin + 1; col < span.end; ++col)
            mLeft[size_t(col)] = joinsNext(z[col], z[col - 1], mDepthJump) && sameSurfaceId(ids, col, ids, col - 1)
                                     ? std::min(mLeft[size_t(col - 1)] + 1, mReach)
                                     : 0;
        mRight[size_t(span.end - 1)] = 0;
        for (int col = span.end - 1; col-- > span.begin;)
            mRight[size_t(col)] = joinsNext(z[col], z[col + 1], mDepthJump) && sameSurfaceId(ids, col, ids, col + 1)
                                      ? std::min(mRight[size_t(col + 1)] + 1, mReach)
                                      : 0;
        for (int col = span.begin; col < span.end; ++col) {
            const float sigma = z[col] > 0.0f ? mSigmaDepth / z[col] : 0.0f;
            level[col] = sigma > 0.0f ? mSigmaLevels.levelOf(sigma) : kUnsmoothed;
        }
        smoothPixels(
            span.begin, span.end, level, mLeft.data(), mRight.data(), [in](int col, int d) { return in[col + d].val; },
            mWindows, out);
    }

    /** Run pixels below (row, col), counted up to the widest reach. */
    int countBelow(int row, int col) const {
        int below = 0;
        while (below < mReach && row + below + 1 < mRows && joinsBelow(row + below, col)) ++below;
        return below;
    }

    /** mAbove and mBelow over the first row's span. */
    void countColumnRunsAfresh(int row) {
        const Span span = mSpans[size_t(row)];
        for (int col = span.begin; col < span.end; ++col) {
            int above = 0;
            while (above < mReach && row - above > 0 && joinsBelow(row - above - 1, col)) ++above;
            mAbove[size_t(col)] = above;
            mBelow[size_t(col)] = countBelow(row, col);
        }
    }

    /** mAbove and mBelow over `row`'s span from their values for the row above: one more above where the pair above
     *  joins, one fewer below, unless the run was cut at the widest reach (then the pair at the window's far end
     *  decides) or had ended (then a new run is counted). Off a row's span nothing is covered, so both are 0 there
     *  and only the span's counts are kept. */
    void countColumnRuns(int row) {
        const Span span = mSpans[size_t(row)];
        const Span spanAbove = mSpans[size_t(row - 1)];
        const float* depthAbove = mDepth.ptr<float>(row - 1);
        const float* depth = mDepth.ptr<float>(row);
        const float* idsAbove = surfaceRow(mSurface, row - 1);
        const float* ids = surfaceRow(mSurface, row);
        const int farRow = row + mReach;
        const bool farPairInside = mReach > 0 && farRow < mRows;
        const float* depthFarAbove = farPairInside ? mDepth.ptr<float>(farRow - 1) : nullptr;
        const float* depthFar = farPairInside ? mDepth.ptr<float>(farRow) : nullptr;
        const float* idsFarAbove = farPairInside ? surfaceRow(mSurface, farRow - 1) : nullptr;
        const float* idsFar = farPairInside ? surfaceRow(mSurface, farRow) : nullptr;
        for (int col = span.begin; col < span.end; ++col) {
            const bool aboveCounted = col >= spanAbove.begin && col < spanAbove.end;
            const int aboveBefore = aboveCounted ? mAbove[size_t(col)] : 0;
            const int belowBefore = aboveCounted ? mBelow[size_t(col)] : 0;
            int& above = mAbove[size_t(col)];
            int& below = mBelow[size_t(col)];
            above = joinsNext(depthAbove[col], depth[col], mDepthJump) && sameSurfaceId(idsAbove, col, ids, col)
                        ? std::min(aboveBefore + 1, mReach)
                        : 0;
            if (belowBefore == 0)
                below = countBelow(row, col);
            else if (belowBefore < mReach)
                below = belowBefore - 1;
            else
                below = farPairInside && joinsNext(depthFarAbove[col], depthFar[col], mDepthJump) &&
                                sameSurfaceId(idsFarAbove, col, idsFar, col)
                            ? mReach
                            : mReach - 1;
        }
    }

    const cv::Mat& mRadial;
    const cv::Mat& mDepth;
    const cv::Mat& mSurface;
    const std::vector<Span>& mSpans;
    float mSigmaDepth;
    float mDepthJump;
    int mReach;
    int mSlots;
    int mRows;
    int mCols;
    int mNextRow;
    bool mCounted = false;
    /** The row pass of rows row - reach .. row + reach over their spans, row r at slotOf(r). */
    std::vector<cv::Vec4f> mRowPass;
    std::vector<int16_t> mLevels;    ///< their pixels' sigma levels, likewise
    std::vector<int> mAbove, mBelow; ///< per column, the current row's run pixels above and below it (its span)
    std::vector<int> mLeft, mRight;  ///< per column, the row pass's run pixels left and right of it (its span)
    std::vector<const cv::Vec4f*> mWindowRows; ///< the rows of mRowPass the current row's windows reach
    GaussianWindows mWindows;
    SigmaLevels mSigmaLevels;
};

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
    /** `spans`: coveredSpans(). With settings.smoothing > 0 the rows are smoothed on the way in (SurfaceSmoother,
     *  `reach` its widestReach()). */
    BandScanner(const cv::Mat& radial, const cv::Mat& depth, const cv::Mat& surface, const std::vector<Span>& spans,
                const SuggestiveSettings& settings, int reach, cv::Mat& mask, int firstRow, int endRow)
        : mRadial(radial), mDepth(depth), mSurface(surface), mSpans(spans), mMask(mask), mDepthJump(settings.depthJump),
          mEndBands(endBandsOf(settings, radial.rows, surface)),
          mMinSinThetaSquared(settings.minSinTheta * settings.minSinTheta),
          mMinSinAngleSquared(minSinAngleToWSquared(settings)), mRule{settings.featureSize * settings.featureSize,
                                                                      settings.threshold, settings.fade},
          mRows(radial.rows), mCols(radial.cols), mFirstRow(firstRow), mEndRow(endRow),
          mFirstLoaded(std::max(firstRow - 3, 0)), mNormalDistance(kRingRows * size_t(mCols), 0.0f),
          mImageWX(kRingRows * size_t(mCols), 0.0f), mImageWY(kRingRows * size_t(mCols), 0.0f),
          mDw(kRingRows * size_t(mCols), 0.0f), mDefined(kRingRows * size_t(mCols), 0.0f) {
        if (settings.smoothing > 0.0f) {
            mSmoother.emplace(radial, depth, surface, spans, settings.smoothing * settings.focalPixels,
                              settings.depthJump, reach, differenceVariance(settings.stencil), mFirstLoaded);
            mSmoothed.resize(kRingRows * size_t(mCols));
        }
    }

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
    Span spanOf(int row) const { return mSpans[size_t(row)]; }

    /** The radial field's row, smoothed or not; rows up to three above the newest loaded one. Smoothed rows hold
     *  their covered span only: every read is of a pixel there (split over the span; D_w D_w and the crossings only
     *  where D_w is defined, which is inside the span). */
    const cv::Vec4f* radialRow(int row) const {
        return mSmoother ? &mSmoothed[slotOf(row)] : mRadial.ptr<cv::Vec4f>(row);
    }

    void load(int row) {
        const Span span = spanOf(row);
        const size_t slot = slotOf(row);
        if (mSmoother) mSmoother->next(&mSmoothed[slot], SurfaceSmoother::Uncovered::Skipped);
        splitRadialRow(radialRow(row), span, &mNormalDistance[slot], &mImageWX[slot], &mImageWY[slot]);
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
                           surfaceRow(mSurface, row - 1),
                           surfaceRow(mSurface, row),
                           surfaceRow(mSurface, row + 1),
                           &mNormalDistance[slotOf(row - 1)],
                           &mNormalDistance[slot],
                           &mNormalDistance[slotOf(row + 1)],
                           &mImageWX[slot],
                           &mImageWY[slot]};
        differentiateAlongW(in, begin, end, mDepthJump, &mDw[slot], &mDefined[slot]);
    }

    std::optional<float> secondDerivative(int row, int col) const {
        return secondDerivativeAt(radialRow(row)[col], col, &mDw[slotOf(row - 1)], &mDw[slotOf(row)],
                                  &mDw[slotOf(row + 1)], &mDefined[slotOf(row - 1)], &mDefined[slotOf(row)],
                                  &mDefined[slotOf(row + 1)], mMinSinThetaSquared, mMinSinAngleSquared);
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
        const std::optional<Crossing> crossing =
            keptCrossing(dwA, dwB, *dwdwA, *dwdwB, radialRow(rowA)[colA], radialRow(rowB)[colB], mRule);
        if (!crossing) return;
        const cv::Point marked = crossing->marksA ? cv::Point(colA, rowA) : cv::Point(colB, rowB);
        if (mEndBands.any() && nearSurfaceEnd(mDepth, mSurface, marked.y, marked.x, mEndBands, mDepthJump)) return;
        if (marked.y < mFirstRow)
            mResult.marksAboveBand.push_back(marked);
        else
            mMask.ptr<uchar>(marked.y)[marked.x] = 255;
        mResult.points.push_back({crossingPosition(rowA, colA, downward, crossing->t), crossing->alpha});
    }

    const cv::Mat& mRadial;
    const cv::Mat& mDepth;
    const cv::Mat& mSurface;
    const std::vector<Span>& mSpans;
    cv::Mat& mMask;
    float mDepthJump;
    EndBands mEndBands; ///< endBandsOf()
    float mMinSinThetaSquared;
    float mMinSinAngleSquared; ///< minSinAngleToWSquared(): wellConditioned()'s bound
    StrengthRule mRule;
    int mRows;
    int mCols;
    int mFirstRow;
    int mEndRow;
    int mFirstLoaded;
    std::array<Span, kRingRows> mDerivativeSpans{}; ///< the span each slot's D_w was last written over
    std::vector<float> mNormalDistance;
    std::vector<float> mImageWX;
    std::vector<float> mImageWY;
    std::vector<float> mDw;
    std::vector<float> mDefined;
    std::optional<SurfaceSmoother> mSmoother;
    std::vector<cv::Vec4f> mSmoothed; ///< with mSmoother, the smoothed rows, in the ring
    BandResult mResult;
};

/** Weights of the fourth-order central difference at offsets -2, -1, +1, +2 (the centre weighs 0). */
constexpr std::array<int, 4> kWideOffsets = {-2, -1, 1, 2};
constexpr std::array<float, 4> kWideWeights = {1.0f / 12.0f, -8.0f / 12.0f, 8.0f / 12.0f, -1.0f / 12.0f};

/** The gradient of `field` at (row, col) by the five-point stencil, or nothing where a stencil pixel is not
 *  `usable`. The caller keeps (row, col) two pixels off the image's edges. */
template <typename Usable>
std::optional<cv::Vec2f> wideGradient(const cv::Mat& field, int row, int col, Usable usable) {
    float gradientX = 0.0f;
    float gradientY = 0.0f;
    for (size_t i = 0; i < kWideOffsets.size(); ++i) {
        const int offset = kWideOffsets[i];
        if (!usable(row, col + offset) || !usable(row + offset, col)) return std::nullopt;
        gradientX += kWideWeights[i] * field.at<float>(row, col + offset);
        gradientY += kWideWeights[i] * field.at<float>(row + offset, col);
    }
    return cv::Vec2f(gradientX, gradientY);
}

/** computeRadialDerivatives() with DifferenceStencil::Central5: a plain per-pixel loop over full-image maps. */
RadialDerivatives wideRadialDerivatives(const cv::Mat& radial, const cv::Mat& depth, const cv::Mat& surface,
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
            const float* ids = surfaceRow(surface, row);
            const auto sameSurface = [&](int r, int c) {
                return joinsNeighbour(z, depth.at<float>(r, c), settings.depthJump) &&
                       sameSurfaceId(ids, col, surfaceRow(surface, r), c);
            };
            if (const auto gradient = wideGradient(normalDistance, row, col, sameSurface)) {
                result.dw.at<float>(row, col) = (*gradient)[0] * here[kImageWX] + (*gradient)[1] * here[kImageWY];
                defined.at<uchar>(row, col) = 1;
            }
        }
    }
    const float minSinThetaSquared = settings.minSinTheta * settings.minSinTheta;
    const float minSinAngle = minSinAngleToWSquared(settings);
    const auto dwDefined = [&](int r, int c) { return defined.at<uchar>(r, c) != 0; };
    for (int row = kReach; row + kReach < rows; ++row) {
        for (int col = kReach; col + kReach < cols; ++col) {
            const cv::Vec4f& here = radial.at<cv::Vec4f>(row, col);
            if (!dwDefined(row, col) || !facesAwayFromFrontal(here, minSinThetaSquared)) continue;
            const auto gradient = wideGradient(result.dw, row, col, dwDefined);
            if (!gradient ||
                !wellConditioned((*gradient)[0], (*gradient)[1], here[kImageWX], here[kImageWY], minSinAngle))
                continue;
            result.dwdw.at<float>(row, col) = (*gradient)[0] * here[kImageWX] + (*gradient)[1] * here[kImageWY];
            result.valid.at<uchar>(row, col) = 255;
        }
    }
    return result;
}

/** extractSuggestiveContours() over full-image derivative maps: every pair of valid 4-neighbours. */
LineSkeleton crossingsOfMaps(const cv::Mat& radial, const cv::Mat& depth, const cv::Mat& surface,
                             const RadialDerivatives& derivatives, const SuggestiveSettings& settings) {
    const StrengthRule rule{settings.featureSize * settings.featureSize, settings.threshold, settings.fade};
    const EndBands bands = endBandsOf(settings, radial.rows, surface);
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
                if (bands.any() && nearSurfaceEnd(depth, surface, marked.y, marked.x, bands, settings.depthJump))
                    continue;
                skeleton.mask.at<uchar>(marked) = 255;
                skeleton.points.push_back({crossingPosition(row, col, downward, crossing->t), crossing->alpha});
            }
        }
    }
    return skeleton;
}

/** Bands of rows, one per thread, of about equal work (a row costs its covered span and a little more), as the
 *  first row of each and then the image's end: each band re-reads rows around it (three for the scanner, the
 *  smoothing's reach for the smoother), so there are no more than the threads and none under kMinBandRows on
 *  average. The results never depend on the bands. */
std::vector<int> bandBounds(const std::vector<Span>& spans) {
    const int rows = int(spans.size());
    constexpr int kMinBandRows = 128;
    constexpr int64_t kRowCost = 32; // pixels' worth: the row's own work besides its covered pixels
    const int count = std::max(1, std::min(cv::getNumThreads(), rows / kMinBandRows));
    std::vector<int64_t> costUpTo(size_t(rows) + 1, 0);
    for (int row = 0; row < rows; ++row) {
        const Span span = spans[size_t(row)];
        costUpTo[size_t(row) + 1] = costUpTo[size_t(row)] + kRowCost + (span.end - span.begin);
    }
    std::vector<int> bounds{0};
    for (int band = 1; band < count; ++band) {
        const int64_t target = costUpTo.back() * band / count;
        const int row = int(std::lower_bound(costUpTo.begin(), costUpTo.end(), target) - costUpTo.begin());
        bounds.push_back(std::clamp(row, bounds.back() + 1, rows - (count - band)));
    }
    bounds.push_back(rows);
    return bounds;
}

/** Runs work(band, firstRow, endRow) for each band of `bounds` (bandBounds()), in parallel. */
template <typename Work>
void forEachBand(const std::vector<int>& bounds, Work work) {
    const int count = int(bounds.size()) - 1;
    const auto run = [&](const cv::Range& range) {
        for (int band = range.start; band < range.end; ++band)
            work(size_t(band), bounds[size_t(band)], bounds[size_t(band) + 1]);
    };
    if (count == 1)
        run(cv::Range(0, 1));
    else
        cv::parallel_for_(cv::Range(0, count), run, count);
}

} // namespace

cv::Mat smoothRadialField(const cv::Mat& radial, const cv::Mat& depth, const SuggestiveSettings& settings,
                          const cv::Mat& surface) {
    checkInputs("smoothRadialField()", radial, depth, surface, settings);
    if (!(settings.smoothing > 0.0f)) return radial.clone();
    // The shape's own lines move by O(sigma^2) (on the test torus at 512^2: a mean 0.025 px at 0.5% of the radius,
    // 0.095 px at 1%, 0.40 px at 2%). Twicing, 2 G(sigma) - G(sqrt(2) sigma), cut that to 0.14 px at 2% but made
    // spurious lines near the silhouettes at 2048^2, so it is not used.
    const float sigmaDepth = settings.smoothing * settings.focalPixels;
    const std::vector<Span> spans = coveredSpans(depth);
    const int reach = widestReach(depth, spans, sigmaDepth);
    cv::Mat smoothed(radial.size(), CV_32FC4);
    forEachBand(bandBounds(spans), [&](size_t, int firstRow, int endRow) {
        SurfaceSmoother smoother(radial, depth, surface, spans, sigmaDepth, settings.depthJump, reach,
                                 differenceVariance(settings.stencil), firstRow);
        for (int row = firstRow; row < endRow; ++row) smoother.next(smoothed.ptr<cv::Vec4f>(row));
    });
    return smoothed;
}

RadialDerivatives computeRadialDerivatives(const cv::Mat& radialInput, const cv::Mat& depth,
                                           const SuggestiveSettings& settings, const cv::Mat& surface) {
    checkInputs("computeRadialDerivatives()", radialInput, depth, surface, settings);
    const cv::Mat radial =
        settings.smoothing > 0.0f ? smoothRadialField(radialInput, depth, settings, surface) : radialInput;
    if (settings.stencil == DifferenceStencil::Central5) return wideRadialDerivatives(radial, depth, surface, settings);
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
        const RowInputs in{depth.ptr<float>(row - 1),
                           depth.ptr<float>(row),
                           depth.ptr<float>(row + 1),
                           surfaceRow(surface, row - 1),
                           surfaceRow(surface, row),
                           surfaceRow(surface, row + 1),
                           normalDistance.ptr<float>(row - 1),
                           normalDistance.ptr<float>(row),
                           normalDistance.ptr<float>(row + 1),
                           imageWX.ptr<float>(row),
                           imageWY.ptr<float>(row)};
        differentiateAlongW(in, 1, cols - 1, settings.depthJump, result.dw.ptr<float>(row), defined.ptr<float>(row));
    }
    const float minSinThetaSquared = settings.minSinTheta * settings.minSinTheta;
    const float minSinAngle = minSinAngleToWSquared(settings);
    for (int row = 1; row + 1 < rows; ++row) {
        const auto* radialRow = radial.ptr<cv::Vec4f>(row);
        for (int col = 1; col + 1 < cols; ++col) {
            const auto dwdw =
                secondDerivativeAt(radialRow[col], col, result.dw.ptr<float>(row - 1), result.dw.ptr<float>(row),
                                   result.dw.ptr<float>(row + 1), defined.ptr<float>(row - 1), defined.ptr<float>(row),
                                   defined.ptr<float>(row + 1), minSinThetaSquared, minSinAngle);
            if (!dwdw) continue;
            result.dwdw.at<float>(row, col) = *dwdw;
            result.valid.at<uchar>(row, col) = 255;
        }
    }
    return result;
}

LineSkeleton extractSuggestiveContours(const cv::Mat& radial, const cv::Mat& depth, const SuggestiveSettings& settings,
                                       const cv::Mat& surface) {
    checkInputs("extractSuggestiveContours()", radial, depth, surface, settings);
    if (settings.stencil == DifferenceStencil::Central5) {
        const cv::Mat field = settings.smoothing > 0.0f ? smoothRadialField(radial, depth, settings, surface) : radial;
        return crossingsOfMaps(field, depth, surface, wideRadialDerivatives(field, depth, surface, settings), settings);
    }
    LineSkeleton skeleton;
    skeleton.mask = cv::Mat::zeros(radial.size(), CV_8UC1);
    // With smoothing, each band smooths the rows it scans as it goes (BandScanner), so the smoothed field is never
    // held whole.
    const std::vector<Span> spans = coveredSpans(depth);
    const int reach =
        settings.smoothing > 0.0f ? widestReach(depth, spans, settings.smoothing * settings.focalPixels) : 0;
    const std::vector<int> bounds = bandBounds(spans);
    std::vector<BandResult> bands(bounds.size() - 1);
    forEachBand(bounds, [&](size_t band, int firstRow, int endRow) {
        bands[band] =
            BandScanner(radial, depth, surface, spans, settings, reach, skeleton.mask, firstRow, endRow).scan();
    });
    for (const BandResult& band : bands) {
        skeleton.points.insert(skeleton.points.end(), band.points.begin(), band.points.end());
        for (const cv::Point& marked : band.marksAboveBand) skeleton.mask.ptr<uchar>(marked.y)[marked.x] = 255;
    }
    return skeleton;
}

} // namespace inkgraph
