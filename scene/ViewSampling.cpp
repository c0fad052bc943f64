#include "scene/ViewSampling.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace inkgraph {
namespace {

constexpr std::size_t kMaxViews = 100000;
/** --orbit's elevation bound: at +-90 degrees the view would be parallel to up. */
constexpr double kMaxElevationDegrees = 89.9;
constexpr double kMaxElevationDeviation = 180.0;
constexpr double kMaxDistanceJitter = 0.9;
constexpr double kMaxLightJitterDegrees = 180.0;
constexpr double kAngleQuantum = 1e6; ///< angles are whole multiples of 1e-6 degree
constexpr double kScaleQuantum = 1e9; ///< the distance scale and the light's components of 1e-9

constexpr std::uint64_t kFnvOffset = 0xcbf29ce484222325ull;
constexpr std::uint64_t kFnvPrime = 0x100000001b3ull;

std::uint64_t fnvBytes(std::uint64_t hash, const unsigned char* bytes, std::size_t size) {
    for (std::size_t i = 0; i < size; ++i) hash = (hash ^ bytes[i]) * kFnvPrime;
    return hash;
}

/** The 8 bytes of `value`, least significant first, whatever the machine's byte order. */
std::uint64_t fnvLittleEndian(std::uint64_t hash, std::uint64_t value) {
    unsigned char bytes[8];
    for (int i = 0; i < 8; ++i) bytes[i] = static_cast<unsigned char>(value >> (8 * i));
    return fnvBytes(hash, bytes, 8);
}

double quantized(double value, double quantum) { return std::round(value * quantum) / quantum; }

void require(bool holds, const std::string& message) {
    if (!holds) throw std::invalid_argument("sampleView(): " + message);
}

void checkSampling(const ViewSampling& sampling) {
    require(sampling.count >= 1 && sampling.count <= kMaxViews,
            "'count' must lie in [1, 100000], got " + std::to_string(sampling.count));
    const auto inElevationRange = [](double degrees) {
        return std::isfinite(degrees) && std::abs(degrees) <= kMaxElevationDegrees;
    };
    require(inElevationRange(sampling.elevationMean) && inElevationRange(sampling.elevationLow) &&
                inElevationRange(sampling.elevationHigh),
            "the elevation's mean, low and high must lie in [-89.9, 89.9] degrees");
    require(sampling.elevationLow <= sampling.elevationHigh, "the elevation's low must not exceed its high");
    require(std::isfinite(sampling.elevationDeviation) && sampling.elevationDeviation >= 0.0 &&
                sampling.elevationDeviation <= kMaxElevationDeviation,
            "the elevation's standard deviation must lie in [0, 180] degrees");
    require(std::isfinite(sampling.distanceJitter) && sampling.distanceJitter >= 0.0 &&
                sampling.distanceJitter <= kMaxDistanceJitter,
            "'distanceJitter' must lie in [0, 0.9]");
    require(std::isfinite(sampling.lightJitterDegrees) && sampling.lightJitterDegrees >= 0.0 &&
                sampling.lightJitterDegrees <= kMaxLightJitterDegrees,
            "'lightJitterDegrees' must lie in [0, 180]");
    if (sampling.lightJitterDegrees > 0.0) {
        require(sampling.light.has_value(), "a light jitter needs the 'light' it turns");
        const glm::dvec3 light = *sampling.light;
        require(std::isfinite(light.x + light.y + light.z) && light != glm::dvec3(0.0),
                "'light' must be a finite, non-zero direction");
    }
}

/** `direction` made unit length as --light makes it: scaled by its largest component first. */
glm::dvec3 unitDirection(const glm::dvec3& direction) {
    const double largest = std::max({std::abs(direction.x), std::abs(direction.y), std::abs(direction.z)});
    return glm::normalize(direction / largest);
}

/** `axis` turned by the angle whose cosine is `cosTurn`, toward the direction at `around` radians about it. */
glm::dvec3 turned(const glm::dvec3& axis, double cosTurn, double around) {
    // Any unit vector not parallel to the axis spans the plane perpendicular to it: the world axis along the axis's
    // smallest component.
    const glm::dvec3 magnitude = glm::abs(axis);
    const glm::dvec3 helper = magnitude.x <= magnitude.y && magnitude.x <= magnitude.z ? glm::dvec3(1, 0, 0)
                              : magnitude.y <= magnitude.z                             ? glm::dvec3(0, 1, 0)
                                                                                       : glm::dvec3(0, 0, 1);
    const glm::dvec3 first = glm::normalize(glm::cross(axis, helper));
    const glm::dvec3 second = glm::cross(axis, first);
    const double sinTurn = std::sqrt(std::max(0.0, 1.0 - cosTurn * cosTurn));
    return cosTurn * axis + sinTurn * (std::cos(around) * first + std::sin(around) * second);
}

} // namespace

ViewRandom::ViewRandom(std::uint64_t seed, const std::string& modelKey, std::uint64_t index) {
    std::uint64_t hash = fnvLittleEndian(kFnvOffset, seed);
    hash = fnvBytes(hash, reinterpret_cast<const unsigned char*>(modelKey.data()), modelKey.size());
    mState = fnvLittleEndian(hash, index);
}

std::uint64_t ViewRandom::next() {
    // splitmix64 (Steele, Lea and Flood 2014): a Weyl sequence through a bijective mix; every 64-bit state is fine.
    std::uint64_t z = (mState += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

double ViewRandom::uniform() { return double(next() >> 11) * 0x1.0p-53; }

ViewSample sampleView(const ViewSampling& sampling, const std::string& modelKey, std::size_t index) {
    checkSampling(sampling);
    require(index < sampling.count,
            "view index " + std::to_string(index) + " is not below the count " + std::to_string(sampling.count));
    ViewRandom random(sampling.seed, modelKey, index);
    // Eight draws, always, in this order: a setting that is off still takes its draws.
    const double azimuthDraw = random.uniform();
    const double normalRadiusDraw = random.uniform();
    const double normalAngleDraw = random.uniform();
    const double distanceDraw = random.uniform();
    const double capHeightDraw = random.uniform();
    const double capAngleDraw = random.uniform();
    const double expressionDraw = random.uniform();
    const double poseDraw = random.uniform();

    constexpr double kTwoPi = 2.0 * std::numbers::pi;
    ViewSample sample;
    sample.index = index;
    sample.azimuthDegrees = quantized(360.0 * azimuthDraw, kAngleQuantum);
    if (sample.azimuthDegrees >= 360.0) sample.azimuthDegrees = 0.0; // a draw within 5e-7 of 360 rounds up to it
    // Box-Muller: 1 - u lies in (0, 1], so the logarithm is finite.
    const double normal = std::sqrt(-2.0 * std::log(1.0 - normalRadiusDraw)) * std::cos(kTwoPi * normalAngleDraw);
    sample.elevationDegrees =
        std::clamp(quantized(sampling.elevationMean + sampling.elevationDeviation * normal, kAngleQuantum),
                   sampling.elevationLow, sampling.elevationHigh);
    sample.distanceScale = quantized(1.0 + sampling.distanceJitter * (2.0 * distanceDraw - 1.0), kScaleQuantum);
    if (sampling.lightJitterDegrees > 0.0) {
        // Uniform on the cap: the cosine of the turn is uniform in [cos radius, 1] (Archimedes' hat-box theorem).
        const double cosRadius = std::cos(glm::radians(sampling.lightJitterDegrees));
        const double cosTurn = 1.0 - capHeightDraw * (1.0 - cosRadius);
        const glm::dvec3 light = turned(unitDirection(*sampling.light), cosTurn, kTwoPi * capAngleDraw);
        sample.towardLight = glm::dvec3(quantized(light.x, kScaleQuantum), quantized(light.y, kScaleQuantum),
                                        quantized(light.z, kScaleQuantum));
    }
    const auto choice = [](double draw, std::size_t count) {
        return std::min(static_cast<std::size_t>(draw * double(count)), count - 1);
    };
    if (!sampling.expressionChoices.empty())
        sample.expressions = sampling.expressionChoices[choice(expressionDraw, sampling.expressionChoices.size())];
    if (!sampling.poseChoices.empty())
        sample.pose = sampling.poseChoices[choice(poseDraw, sampling.poseChoices.size())];
    return sample;
}

std::vector<ViewSample> sampleViews(const ViewSampling& sampling, const std::string& modelKey) {
    checkSampling(sampling);
    std::vector<ViewSample> samples;
    samples.reserve(sampling.count);
    for (std::size_t index = 0; index < sampling.count; ++index)
        samples.push_back(sampleView(sampling, modelKey, index));
    return samples;
}

std::string expressionSetText(const std::vector<ExpressionWeight>& expressions) {
    if (expressions.empty()) return "none";
    std::string text;
    for (const ExpressionWeight& expression : expressions) {
        // The shortest text that reads back as the same double: 0.5, not 0.50000000000000000.
        char weight[32];
        const auto written = std::to_chars(weight, weight + sizeof weight, expression.weight);
        text += (text.empty() ? "" : ",") + expression.name + "=" + std::string(weight, written.ptr);
    }
    return text;
}

} // namespace inkgraph
