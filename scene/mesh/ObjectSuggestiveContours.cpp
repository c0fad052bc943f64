#include "scene/mesh/ObjectSuggestiveContours.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace inkgraph {
namespace {

/** Below this sin^2(theta) the view is frontal: w^ has no direction and the numerator is taken as its bounded 0. */
constexpr double kFrontalSinSquared = 1e-20;

void requireFiniteEye(const char* function, const glm::dvec3& eye) {
    if (!(std::isfinite(eye.x) && std::isfinite(eye.y) && std::isfinite(eye.z)))
        throw std::invalid_argument(std::string(function) + ": 'eye' must be finite");
}

void requireFeatureSize(const char* function, double featureSize) {
    if (!(std::isfinite(featureSize) && featureSize > 0.0))
        throw std::invalid_argument(std::string(function) + ": 'featureSize' must be positive and finite, got " +
                                    std::to_string(featureSize));
}

/** Linear interpolation of everything a crossing carries. */
struct CrossingPoint {
    glm::dvec3 position;
    double numerator;
    double denominator;
};

CrossingPoint mix(const CrossingPoint& a, const CrossingPoint& b, double t) {
    return {a.position + t * (b.position - a.position), a.numerator + t * (b.numerator - a.numerator),
            a.denominator + t * (b.denominator - a.denominator)};
}

/** Where a linear function with values `a` at 0 and `b` at 1 crosses zero strictly inside (0, 1), if it does. */
void addRoot(double a, double b, std::vector<double>& roots) {
    if ((a > 0.0 && b < 0.0) || (a < 0.0 && b > 0.0)) roots.push_back(a / (a - b));
}

} // namespace

SuggestiveViewField computeSuggestiveViewField(const MeshCurvature& curvature, const glm::dvec3& eye,
                                               double featureSize) {
    requireFiniteEye("computeSuggestiveViewField()", eye);
    requireFeatureSize("computeSuggestiveViewField()", featureSize);
    const std::size_t vertexCount = curvature.positions.size();
    SuggestiveViewField field;
    field.radialCurvature.resize(vertexCount);
    field.numerator.resize(vertexCount);
    field.denominator.resize(vertexCount);
    const double featureSizeSquared = featureSize * featureSize;
    for (std::size_t vertex = 0; vertex < vertexCount; ++vertex) {
        const glm::dvec3 toEye = eye - curvature.positions[vertex];
        const double distance = glm::length(toEye);
        const glm::dvec3 view = distance > 0.0 ? toEye / distance : glm::dvec3(0.0);
        const double u = glm::dot(view, curvature.direction1[vertex]);
        const double v = glm::dot(view, curvature.direction2[vertex]);
        const double k1 = curvature.curvature1[vertex], k2 = curvature.curvature2[vertex];
        const double sinSquared = u * u + v * v;
        const double cosine = glm::dot(view, curvature.normals[vertex]);
        field.radialCurvature[vertex] = k1 * u * u + k2 * v * v;
        field.denominator[vertex] = cosine;
        double numerator = 0.0;
        if (sinSquared >= kFrontalSinSquared) {
            // sin C(w^,w^,w^) = C(u,v,...) / sin^2 with C along the unnormalised (u, v); tau_r sin^2 = (k2 - k1) u v.
            const double tauTimesSinSquared = (k2 - k1) * u * v;
            numerator = curvature.derivativeAlong(vertex, u, v) / sinSquared -
                        2.0 * cosine * tauTimesSinSquared * tauTimesSinSquared / (sinSquared * sinSquared);
        }
        field.numerator[vertex] = featureSizeSquared * numerator;
    }
    return field;
}

std::vector<SuggestiveSegment> extractObjectSuggestiveContours(const MeshCurvature& curvature, const glm::dvec3& eye,
                                                               const ObjectSuggestiveSettings& settings) {
    const char* function = "extractObjectSuggestiveContours()";
    requireFiniteEye(function, eye);
    requireFeatureSize(function, settings.featureSize);
    if (!(std::isfinite(settings.threshold) && settings.threshold >= 0.0))
        throw std::invalid_argument(std::string(function) + ": 'threshold' must be finite and >= 0, got " +
                                    std::to_string(settings.threshold));
    if (!(std::isfinite(settings.fade) && settings.fade >= 0.0))
        throw std::invalid_argument(std::string(function) + ": 'fade' must be finite and >= 0, got " +
                                    std::to_string(settings.fade));

    const SuggestiveViewField field = computeSuggestiveViewField(curvature, eye, settings.featureSize);
    const double threshold = settings.threshold, fade = settings.fade;
    // alpha = (q - T) / (q - T + F) with q = num / den, multiplied through by den > 0 so it stays finite as den -> 0
    // (a line running into a contour, where q -> Inf and alpha -> 1).
    auto strengthAt = [&](const CrossingPoint& point) {
        if (fade == 0.0) return 1.0;
        const double excess = point.numerator - threshold * point.denominator;
        const double total = excess + fade * point.denominator;
        return total > 0.0 ? std::clamp(excess / total, 0.0, 1.0) : 0.0;
    };

    std::vector<SuggestiveSegment> segments;
    std::vector<double> cuts;
    for (std::size_t face = 0; face < curvature.triangles.size(); ++face) {
        const glm::uvec3& corners = curvature.triangles[face];
        std::array<bool, 3> negative;
        for (int i = 0; i < 3; ++i) negative[i] = field.radialCurvature[corners[i]] < 0.0;
        if (negative[0] == negative[1] && negative[1] == negative[2]) continue;
        // The corner on its own side of zero; the crossings lie on its two edges.
        const int lone = negative[0] == negative[1] ? 2 : negative[0] == negative[2] ? 1 : 0;
        auto pointAt = [&](int corner) {
            const std::uint32_t vertex = corners[corner];
            return CrossingPoint{curvature.positions[vertex], field.numerator[vertex], field.denominator[vertex]};
        };
        auto crossing = [&](int other) {
            const double a = field.radialCurvature[corners[lone]], b = field.radialCurvature[corners[other]];
            return mix(pointAt(lone), pointAt(other), a / (a - b)); // a, b of opposite sides: a - b != 0
        };
        const CrossingPoint start = crossing((lone + 1) % 3);
        const CrossingPoint end = crossing((lone + 2) % 3);

        // Cut where the strength crosses the threshold or the surface turns away; keep what passes both.
        cuts.assign({0.0});
        addRoot(start.numerator - threshold * start.denominator, end.numerator - threshold * end.denominator, cuts);
        addRoot(start.denominator, end.denominator, cuts);
        cuts.push_back(1.0);
        std::sort(cuts.begin(), cuts.end());
        for (std::size_t piece = 0; piece + 1 < cuts.size(); ++piece) {
            if (!(cuts[piece + 1] > cuts[piece])) continue;
            const CrossingPoint middle = mix(start, end, 0.5 * (cuts[piece] + cuts[piece + 1]));
            if (!(middle.denominator > 0.0 && middle.numerator - threshold * middle.denominator > 0.0)) continue;
            const CrossingPoint a = mix(start, end, cuts[piece]);
            const CrossingPoint b = mix(start, end, cuts[piece + 1]);
            segments.push_back({{a.position, b.position}, {strengthAt(a), strengthAt(b)}, std::uint32_t(face)});
        }
    }
    return segments;
}

} // namespace inkgraph
