#pragma once
/** @file Ground truth for GL tests of a sphere on the view axis: exact ray casting in double, projection and the
 *  silhouette circle, for a square image and a pinhole camera at the view-space origin looking down -z. */

#include <glm/glm.hpp>

#include <cmath>
#include <optional>

namespace inkgraph::test {

/** The exact surface under an image point. */
struct SphereHit {
    glm::dvec3 point;     ///< view space
    glm::dvec3 normal;    ///< unit, outward
    glm::dvec3 towardEye; ///< unit, surface -> eye
    double depth;         ///< linear view depth, -point.z
};

/** A sphere of `radius` centred at (0, 0, -distance) in view space, seen in a `size` x `size` image. */
struct AnalyticSphereView {
    int size;
    double radius;
    double distance;
    double fovYDegrees;

    glm::dvec3 center() const { return {0.0, 0.0, -distance}; }
    double focalPixels() const { return (size / 2.0) / std::tan(glm::radians(fovYDegrees) / 2.0); }

    /** Image point in pixel units, origin top-left (pixel centres at col + 0.5, row + 0.5). */
    std::optional<SphereHit> castPoint(double x, double y) const {
        const double tanHalf = std::tan(glm::radians(fovYDegrees) / 2.0);
        const double ndcX = 2.0 * x / size - 1.0;
        const double ndcY = 1.0 - 2.0 * y / size;
        const glm::dvec3 direction = glm::normalize(glm::dvec3(ndcX * tanHalf, ndcY * tanHalf, -1.0));
        const double b = glm::dot(direction, center());
        const double discriminant = b * b - (glm::dot(center(), center()) - radius * radius);
        if (discriminant < 0.0) return std::nullopt;
        const glm::dvec3 hit = direction * (b - std::sqrt(discriminant));
        return SphereHit{hit, (hit - center()) / radius, -direction, -hit.z};
    }
    std::optional<SphereHit> castPixel(int col, int row) const { return castPoint(col + 0.5, row + 0.5); }

    /** View-space point -> image point (pixel units, origin top-left). */
    glm::dvec2 project(const glm::dvec3& point) const {
        return {size / 2.0 + focalPixels() * point.x / -point.z, size / 2.0 - focalPixels() * point.y / -point.z};
    }

    /** Distance in pixels from a pixel centre to the silhouette circle (radius f R / sqrt(d^2 - R^2)). */
    double pixelsFromSilhouette(int col, int row) const {
        const double circle = focalPixels() * radius / std::sqrt(distance * distance - radius * radius);
        const double dx = col + 0.5 - size / 2.0;
        const double dy = row + 0.5 - size / 2.0;
        return std::abs(std::sqrt(dx * dx + dy * dy) - circle);
    }
};

} // namespace inkgraph::test
