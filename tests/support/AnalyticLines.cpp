#include "tests/support/AnalyticLines.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace inkgraph::test {
namespace {

constexpr double kPi = std::numbers::pi;
/** A point is hidden only by a hit this much (relative) nearer than itself: a contour's eye ray grazes the torus,
 *  and a double root moves by ~sqrt(machine epsilon) ~ 1e-8 under rounding. */
constexpr double kHiddenRelativeGap = 1e-6;

void checkTorus(const char* function, double ringRadius, double tubeRadius) {
    if (!(tubeRadius > 0.0 && tubeRadius < ringRadius) || !std::isfinite(ringRadius))
        throw std::invalid_argument(std::string(function) +
                                    ": need 0 < 'tubeRadius' < 'ringRadius' (a ring torus), both finite");
}

bool isInFront(const SyntheticCamera& camera, const glm::dvec3& worldPoint) {
    return (camera.view() * glm::dvec4(worldPoint, 1.0)).z < 0.0;
}

/** LinePoint coordinates of a world point in front of the camera, if they lie in the image. */
std::optional<cv::Point2d> imagePointOf(const SyntheticCamera& camera, const glm::dvec3& worldPoint) {
    if (!isInFront(camera, worldPoint)) return std::nullopt;
    const glm::dvec2 projected = camera.project(worldPoint);
    const cv::Point2d point(projected.x - 0.5, projected.y - 0.5);
    if (!(point.x >= -0.5 && point.x <= camera.width - 0.5 && point.y >= -0.5 && point.y <= camera.height - 0.5))
        return std::nullopt;
    return point;
}

bool isVisibleOnTorus(const glm::dvec3& eye, const glm::dvec3& worldPoint, const glm::dvec3& center, double ring,
                      double tube) {
    const double distance = glm::length(worldPoint - eye);
    const auto hit = intersectTorus({eye, (worldPoint - eye) / distance}, center, ring, tube);
    return !hit || *hit >= distance * (1.0 - kHiddenRelativeGap);
}

/** A maximal run of joined samples; closed when it is a whole cycle. */
template <typename Sample>
struct SampleRun {
    std::vector<Sample> samples;
    bool closed = false;
};

/** Runs of a cyclic sequence of samples: present samples joined where `linked[i]` joins sample i to i + 1 (mod
 *  count); one closed run when nothing breaks the cycle. Runs of one sample are dropped. */
template <typename Sample>
std::vector<SampleRun<Sample>> runsOfCycle(const std::vector<std::optional<Sample>>& samples,
                                           const std::vector<bool>& linked) {
    const std::size_t count = samples.size();
    auto joins = [&](std::size_t index) { return samples[index] && samples[(index + 1) % count] && linked[index]; };
    std::size_t breakAt = count;
    for (std::size_t index = 0; index < count; ++index)
        if (!joins(index)) {
            breakAt = index;
            break;
        }
    std::vector<SampleRun<Sample>> runs;
    if (breakAt == count) {
        SampleRun<Sample> whole{{}, true};
        for (const auto& sample : samples) whole.samples.push_back(*sample);
        if (whole.samples.size() > 1) runs.push_back(std::move(whole));
        return runs;
    }
    SampleRun<Sample> run;
    for (std::size_t step = 1; step <= count; ++step) {
        const std::size_t index = (breakAt + step) % count;
        if (samples[index]) run.samples.push_back(*samples[index]);
        if (!joins(index)) {
            if (run.samples.size() > 1) runs.push_back(std::move(run));
            run = SampleRun<Sample>{};
        }
    }
    return runs;
}

/** A vertex of a torus curve: where it is on the surface and in the image. */
struct TorusSample {
    glm::dvec2 parameters;
    cv::Point2d image;
};

void appendCurves(const std::vector<SampleRun<TorusSample>>& runs, std::vector<TorusCurve>& curves) {
    for (const SampleRun<TorusSample>& run : runs) {
        TorusCurve curve;
        curve.image.closed = run.closed;
        for (const TorusSample& sample : run.samples) {
            curve.parameters.push_back(sample.parameters);
            curve.image.points.push_back(sample.image);
        }
        curves.push_back(std::move(curve));
    }
}

std::vector<LinePolyline> imagesOf(std::vector<TorusCurve> curves) {
    std::vector<LinePolyline> polylines;
    polylines.reserve(curves.size());
    for (TorusCurve& curve : curves) polylines.push_back(std::move(curve.image));
    return polylines;
}

double wrapAngle(double angle) { return std::remainder(angle, 2.0 * kPi); }

} // namespace

glm::dvec3 TorusGeometry::point(double u, double v) const {
    return {(ring + tube * std::cos(v)) * std::cos(u), (ring + tube * std::cos(v)) * std::sin(u), tube * std::sin(v)};
}

glm::dvec3 TorusGeometry::normal(double u, double v) const {
    return {std::cos(v) * std::cos(u), std::cos(v) * std::sin(u), std::sin(v)};
}

glm::dvec3 TorusGeometry::tangentU(double u) const { return {-std::sin(u), std::cos(u), 0.0}; }

glm::dvec3 TorusGeometry::tangentV(double u, double v) const {
    return {-std::sin(v) * std::cos(u), -std::sin(v) * std::sin(u), std::cos(v)};
}

double TorusGeometry::curvatureU(double v) const { return std::cos(v) / (ring + tube * std::cos(v)); }

double TorusGeometry::curvatureV() const { return 1.0 / tube; }

glm::dvec2 TorusGeometry::parameters(const glm::dvec3& p) const {
    return {std::atan2(p.y, p.x), std::atan2(p.z, std::hypot(p.x, p.y) - ring)};
}

double TorusGeometry::wSquaredRadialCurvature(const glm::dvec3& eye, double u, double v) const {
    // w = v - (n.v) n differs from v by a multiple of n, which is orthogonal to both tangents.
    const glm::dvec3 toEye = eye - point(u, v);
    const double alongU = glm::dot(toEye, tangentU(u));
    const double alongV = glm::dot(toEye, tangentV(u, v));
    return curvatureU(v) * alongU * alongU + curvatureV() * alongV * alongV;
}

double TorusGeometry::radialCurvature(const glm::dvec3& eye, double u, double v) const {
    const glm::dvec3 toEye = eye - point(u, v);
    const double alongU = glm::dot(toEye, tangentU(u));
    const double alongV = glm::dot(toEye, tangentV(u, v));
    return wSquaredRadialCurvature(eye, u, v) / (alongU * alongU + alongV * alongV);
}

double TorusGeometry::radialCurvatureDerivative(const glm::dvec3& eye, double u, double v, double step) const {
    const glm::dvec3 toEye = eye - point(u, v);
    const glm::dvec3 n = normal(u, v);
    const glm::dvec3 wHat = glm::normalize(toEye - glm::dot(toEye, n) * n);
    // A unit step along w^ on the surface, in parameters: |dP/du| = R + r cos v, |dP/dv| = r.
    const double du = glm::dot(wHat, tangentU(u)) / (ring + tube * std::cos(v));
    const double dv = glm::dot(wHat, tangentV(u, v)) / tube;
    return (radialCurvature(eye, u + step * du, v + step * dv) - radialCurvature(eye, u - step * du, v - step * dv)) /
           (2.0 * step);
}

std::vector<LinePolyline> sphereSilhouette(const SyntheticCamera& camera, const glm::dvec3& center, double radius,
                                           int samples) {
    camera.check("sphereSilhouette()");
    if (!(radius > 0.0) || !std::isfinite(radius))
        throw std::invalid_argument("sphereSilhouette(): 'radius' must be positive and finite");
    if (samples < 3) throw std::invalid_argument("sphereSilhouette(): 'samples' must be >= 3");
    const glm::dvec3 toCenter = center - camera.eye;
    const double distance2 = glm::dot(toCenter, toCenter);
    if (!(distance2 > radius * radius))
        throw std::invalid_argument("sphereSilhouette(): the eye lies inside the sphere ('center', 'radius')");

    const glm::dvec3 axis = toCenter / std::sqrt(distance2);
    // Any two unit vectors orthogonal to the axis and to each other; start from the coordinate axis least along it.
    const glm::dvec3 helper = std::abs(axis.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    const glm::dvec3 first = glm::normalize(glm::cross(axis, helper));
    const glm::dvec3 second = glm::cross(axis, first);
    const glm::dvec3 circleCenter = camera.eye + toCenter * (1.0 - radius * radius / distance2);
    const double circleRadius = radius * std::sqrt(distance2 - radius * radius) / std::sqrt(distance2);

    std::vector<std::optional<cv::Point2d>> points(static_cast<std::size_t>(samples));
    for (int index = 0; index < samples; ++index) {
        const double angle = 2.0 * kPi * index / samples;
        const glm::dvec3 p = circleCenter + circleRadius * (std::cos(angle) * first + std::sin(angle) * second);
        if (!isInFront(camera, p))
            throw std::invalid_argument("sphereSilhouette(): the silhouette is not wholly in front of the camera");
        points[std::size_t(index)] = imagePointOf(camera, p);
    }
    std::vector<LinePolyline> polylines;
    for (SampleRun<cv::Point2d>& run : runsOfCycle(points, std::vector<bool>(std::size_t(samples), true)))
        polylines.push_back({std::move(run.samples), run.closed});
    return polylines;
}

std::vector<LinePolyline> torusContours(const SyntheticCamera& camera, const glm::dvec3& center, double ringRadius,
                                        double tubeRadius, int uSamples) {
    return imagesOf(torusContourCurves(camera, center, ringRadius, tubeRadius, uSamples));
}

std::vector<TorusCurve> torusContourCurves(const SyntheticCamera& camera, const glm::dvec3& center, double ringRadius,
                                           double tubeRadius, int uSamples) {
    camera.check("torusContours()");
    checkTorus("torusContours()", ringRadius, tubeRadius);
    if (uSamples < 8) throw std::invalid_argument("torusContours(): 'uSamples' must be >= 8");
    const TorusGeometry torus{ringRadius, tubeRadius};
    const glm::dvec3 eye = camera.eye - center;
    // Neighbouring u with v this far apart are not one curve (a branch running through atan2's cut stays smooth in
    // the wrapped difference).
    constexpr double kLargestStepV = 0.2;

    std::vector<TorusCurve> curves;
    for (const double side : {1.0, -1.0}) {
        std::vector<std::optional<TorusSample>> points(static_cast<std::size_t>(uSamples));
        std::vector<std::optional<double>> vs(static_cast<std::size_t>(uSamples));
        for (int index = 0; index < uSamples; ++index) {
            const double u = 2.0 * kPi * index / uSamples;
            const double a = eye.x * std::cos(u) + eye.y * std::sin(u) - ringRadius;
            const double b = eye.z;
            const double length = std::hypot(a, b);
            if (!(length >= tubeRadius)) continue; // the eye's meridian projection is inside the tube: no contour
            const double v = std::atan2(b, a) + side * std::acos(tubeRadius / length);
            vs[std::size_t(index)] = v;
            const glm::dvec3 world = center + torus.point(u, v);
            if (!isVisibleOnTorus(camera.eye, world, center, ringRadius, tubeRadius)) continue;
            if (const auto image = imagePointOf(camera, world))
                points[std::size_t(index)] = TorusSample{{u, v}, *image};
        }
        std::vector<bool> linked(static_cast<std::size_t>(uSamples));
        for (std::size_t index = 0; index < linked.size(); ++index) {
            const auto& here = vs[index];
            const auto& next = vs[(index + 1) % linked.size()];
            linked[index] = here && next && std::abs(wrapAngle(*next - *here)) <= kLargestStepV;
        }
        appendCurves(runsOfCycle(points, linked), curves);
    }
    return curves;
}

std::vector<LinePolyline> torusSuggestiveContours(const SyntheticCamera& camera, const glm::dvec3& center,
                                                  double ringRadius, double tubeRadius,
                                                  const AnalyticSuggestiveSettings& settings, int uSamples,
                                                  int vSamples) {
    return imagesOf(torusSuggestiveContourCurves(camera, center, ringRadius, tubeRadius, settings, uSamples, vSamples));
}

std::vector<TorusCurve> torusSuggestiveContourCurves(const SyntheticCamera& camera, const glm::dvec3& center,
                                                     double ringRadius, double tubeRadius,
                                                     const AnalyticSuggestiveSettings& settings, int uSamples,
                                                     int vSamples) {
    camera.check("torusSuggestiveContours()");
    checkTorus("torusSuggestiveContours()", ringRadius, tubeRadius);
    if (uSamples < 8) throw std::invalid_argument("torusSuggestiveContours(): 'uSamples' must be >= 8");
    if (vSamples < 8) throw std::invalid_argument("torusSuggestiveContours(): 'vSamples' must be >= 8");
    if (!(settings.featureSize > 0.0) || !std::isfinite(settings.featureSize))
        throw std::invalid_argument("torusSuggestiveContours(): 'featureSize' must be positive and finite");
    if (!(settings.threshold >= 0.0) || !std::isfinite(settings.threshold))
        throw std::invalid_argument("torusSuggestiveContours(): 'threshold' must be finite and >= 0");
    if (!(settings.minSinTheta >= 0.0 && settings.minSinTheta < 1.0))
        throw std::invalid_argument("torusSuggestiveContours(): 'minSinTheta' must lie in [0, 1)");

    const TorusGeometry torus{ringRadius, tubeRadius};
    const glm::dvec3 eye = camera.eye - center;
    const double stepU = 2.0 * kPi / uSamples;
    const double stepV = 2.0 * kPi / vSamples;

    // The sign of |w|^2 kappa_r (that of kappa_r sin^2 theta) on the periodic grid; 0 counts as positive.
    std::vector<std::uint8_t> negative(std::size_t(uSamples) * std::size_t(vSamples));
    std::vector<double> cosU(static_cast<std::size_t>(uSamples)), sinU(static_cast<std::size_t>(uSamples));
    for (int i = 0; i < uSamples; ++i) {
        cosU[std::size_t(i)] = std::cos(i * stepU);
        sinU[std::size_t(i)] = std::sin(i * stepU);
    }
    for (int j = 0; j < vSamples; ++j) {
        const double cosV = std::cos(j * stepV), sinV = std::sin(j * stepV);
        const double curvatureU = cosV / (ringRadius + tubeRadius * cosV);
        for (int i = 0; i < uSamples; ++i) {
            const double cu = cosU[std::size_t(i)], su = sinU[std::size_t(i)];
            const double axial = ringRadius + tubeRadius * cosV;
            const glm::dvec3 toEye = eye - glm::dvec3(axial * cu, axial * su, tubeRadius * sinV);
            const double alongU = -toEye.x * su + toEye.y * cu;
            const double alongV = -sinV * (toEye.x * cu + toEye.y * su) + cosV * toEye.z;
            const double value = curvatureU * alongU * alongU + alongV * alongV / tubeRadius;
            negative[std::size_t(j) * std::size_t(uSamples) + std::size_t(i)] = value < 0.0;
        }
    }
    auto isNegative = [&](int i, int j) {
        return negative[std::size_t((j + vSamples) % vSamples) * std::size_t(uSamples) +
                        std::size_t((i + uSamples) % uSamples)] != 0;
    };

    // Grid edges, by id: 2 (j uSamples + i) from (i, j) to (i + 1, j), + 1 for (i, j) to (i, j + 1).
    auto edgeId = [&](int i, int j, bool alongV) {
        const std::int64_t node = std::int64_t((j + vSamples) % vSamples) * uSamples + (i + uSamples) % uSamples;
        return 2 * node + (alongV ? 1 : 0);
    };
    auto crosses = [&](int i, int j, bool alongV) {
        return isNegative(i, j) != (alongV ? isNegative(i, j + 1) : isNegative(i + 1, j));
    };
    // Marching squares: each crossing edge joins the crossings of the two cells it borders, so every crossing has
    // exactly two neighbours and the zero set comes out as cycles.
    std::unordered_map<std::int64_t, std::array<std::int64_t, 2>> neighbours;
    auto join = [&](std::int64_t a, std::int64_t b) {
        for (const auto& [from, to] : {std::pair{a, b}, std::pair{b, a}}) {
            auto [entry, inserted] = neighbours.try_emplace(from, std::array<std::int64_t, 2>{-1, -1});
            (entry->second[0] < 0 ? entry->second[0] : entry->second[1]) = to;
        }
    };
    for (int j = 0; j < vSamples; ++j)
        for (int i = 0; i < uSamples; ++i) {
            const bool bottom = crosses(i, j, false), top = crosses(i, j + 1, false);
            const bool left = crosses(i, j, true), right = crosses(i + 1, j, true);
            const int crossingCount = bottom + top + left + right;
            if (crossingCount == 0) continue;
            const std::int64_t bottomId = edgeId(i, j, false), topId = edgeId(i, j + 1, false);
            const std::int64_t leftId = edgeId(i, j, true), rightId = edgeId(i + 1, j, true);
            if (crossingCount == 2) {
                std::int64_t ends[2];
                int found = 0;
                if (bottom) ends[found++] = bottomId;
                if (right) ends[found++] = rightId;
                if (top) ends[found++] = topId;
                if (left) ends[found++] = leftId;
                join(ends[0], ends[1]);
                continue;
            }
            // A saddle cell: the corners (i, j) and (i + 1, j + 1) share a sign. The value at the cell's centre
            // decides whether their region runs through the middle.
            const double u = (i + 0.5) * stepU, v = (j + 0.5) * stepV;
            const bool centreNegative = torus.wSquaredRadialCurvature(eye, u, v) < 0.0;
            if (centreNegative == isNegative(i, j)) {
                join(bottomId, rightId); // cuts off corner (i + 1, j)
                join(topId, leftId);     // cuts off corner (i, j + 1)
            } else {
                join(bottomId, leftId);
                join(rightId, topId);
            }
        }

    // The zero on one edge, by bisection on |w|^2 kappa_r to double precision.
    auto zeroOnEdge = [&](std::int64_t id) {
        const bool alongV = (id & 1) != 0;
        const std::int64_t node = id / 2;
        const int i = int(node % uSamples), j = int(node / uSamples);
        const double u0 = i * stepU, v0 = j * stepV;
        auto at = [&](double t) { return alongV ? glm::dvec2(u0, v0 + t * stepV) : glm::dvec2(u0 + t * stepU, v0); };
        double low = 0.0, high = 1.0;
        const bool lowNegative = isNegative(i, j);
        for (int halving = 0; halving < 64 && high - low > 1e-17; ++halving) {
            const double middle = 0.5 * (low + high);
            const glm::dvec2 uv = at(middle);
            if ((torus.wSquaredRadialCurvature(eye, uv.x, uv.y) < 0.0) == lowNegative)
                low = middle;
            else
                high = middle;
        }
        return at(0.5 * (low + high));
    };
    // A zero of kappa_r kept as a suggestive contour: its image point, or nothing.
    auto keptPoint = [&](const glm::dvec2& uv) -> std::optional<TorusSample> {
        const double u = uv.x, v = uv.y;
        const glm::dvec3 p = torus.point(u, v);
        const glm::dvec3 n = torus.normal(u, v);
        const glm::dvec3 toEye = eye - p;
        const double normalDistance = glm::dot(toEye, n);
        if (!(normalDistance > 0.0)) return std::nullopt;
        const double wLength = glm::length(toEye - normalDistance * n);
        if (wLength < settings.minSinTheta * glm::length(toEye)) return std::nullopt;
        const double derivative = torus.radialCurvatureDerivative(eye, u, v);
        if (!(derivative > 0.0)) return std::nullopt;
        const double strength = settings.featureSize * settings.featureSize * (wLength / normalDistance) * derivative;
        if (!(strength > settings.threshold)) return std::nullopt;
        const glm::dvec3 world = center + p;
        if (!isVisibleOnTorus(camera.eye, world, center, ringRadius, tubeRadius)) return std::nullopt;
        const auto image = imagePointOf(camera, world);
        if (!image) return std::nullopt;
        return TorusSample{uv, *image};
    };

    std::vector<TorusCurve> curves;
    std::unordered_map<std::int64_t, bool> visited;
    visited.reserve(neighbours.size());
    // Cycles in the order of their smallest edge id, so the result does not depend on hashing.
    std::vector<std::int64_t> ids;
    ids.reserve(neighbours.size());
    for (const auto& entry : neighbours) ids.push_back(entry.first);
    std::sort(ids.begin(), ids.end());
    for (const std::int64_t start : ids) {
        if (visited[start]) continue;
        std::vector<std::optional<TorusSample>> cycle;
        std::int64_t previous = -1, current = start;
        while (current >= 0 && !visited[current]) {
            visited[current] = true;
            cycle.push_back(keptPoint(zeroOnEdge(current)));
            const auto& next = neighbours.at(current);
            const std::int64_t following = next[0] != previous ? next[0] : next[1];
            previous = current;
            current = following;
        }
        appendCurves(runsOfCycle(cycle, std::vector<bool>(cycle.size(), true)), curves);
    }
    return curves;
}

} // namespace inkgraph::test
