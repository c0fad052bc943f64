// tests/support/SyntheticGBuffer against closed forms: the buffers the no-GL line kernels are tested on.
#include "tests/support/SyntheticGBuffer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>

namespace inkgraph::test {
namespace {

/** The first hit of a ray with a sphere, in double, written independently of the renderer. */
std::optional<glm::dvec3> firstSphereHit(const SyntheticRay& ray, const glm::dvec3& center, double radius) {
    const glm::dvec3 offset = ray.origin - center;
    const double halfB = glm::dot(offset, ray.direction);
    const double discriminant = halfB * halfB - (glm::dot(offset, offset) - radius * radius);
    if (discriminant < 0.0) return std::nullopt;
    return ray.origin + (-halfB - std::sqrt(discriminant)) * ray.direction;
}

/** The first hit of a 2-D ray (origin, unit direction) with a circle, or nothing. */
std::optional<glm::dvec2> firstCircleHit(glm::dvec2 origin, glm::dvec2 direction, glm::dvec2 center, double radius) {
    const glm::dvec2 offset = origin - center;
    const double halfB = glm::dot(offset, direction);
    const double discriminant = halfB * halfB - (glm::dot(offset, offset) - radius * radius);
    if (discriminant < 0.0) return std::nullopt;
    return origin + (-halfB - std::sqrt(discriminant)) * direction;
}

TEST(SyntheticGBuffer, SphereSilhouetteIsTheExactCircle) {
    SyntheticCamera camera;
    camera.width = camera.height = 256;
    camera.eye = {0.0, 0.0, 5.0};
    const double radius = 1.0;
    const SyntheticGBuffer buffer = renderSphere(camera, glm::dvec3(0.0), radius);
    const double circle = camera.focalPixels() * radius / std::sqrt(5.0 * 5.0 - radius * radius);
    int covered = 0;
    for (int row = 0; row < camera.height; ++row)
        for (int col = 0; col < camera.width; ++col) {
            const double fromCentre = std::hypot(col + 0.5 - 128.0, row + 0.5 - 128.0);
            const bool isCovered = buffer.depth.at<float>(row, col) > 0.0f;
            covered += isCovered;
            // The exact circle, not merely within a pixel: a one-pixel error would shift every test built on it.
            if (std::abs(fromCentre - circle) > 1e-6) {
                EXPECT_EQ(isCovered, fromCentre < circle) << col << "," << row;
            }
            if (!isCovered) {
                EXPECT_EQ(buffer.normal.at<cv::Vec4f>(row, col), cv::Vec4f(0, 0, 0, 0));
                EXPECT_EQ(buffer.radial.at<cv::Vec4f>(row, col), cv::Vec4f(0, 0, 0, 0));
                EXPECT_EQ(buffer.nDotV.at<float>(row, col), 0.0f);
            }
        }
    EXPECT_NEAR(covered, M_PI * circle * circle, 2.0 * M_PI * circle); // and the circle is where it should be
}

TEST(SyntheticGBuffer, RadialFieldsAgreeWithGeometry) {
    // Off-axis and tilted so no component is special: the sphere sits left and above, the camera is rolled.
    SyntheticCamera camera;
    camera.width = 320;
    camera.height = 240;
    camera.eye = {1.0, -2.0, 5.0};
    camera.target = {0.3, 0.2, 0.0};
    camera.up = {0.3, 1.0, 0.1};
    const glm::dvec3 center(-0.4, 0.5, 0.2);
    const double radius = 0.9;
    const SyntheticGBuffer buffer = renderSphere(camera, center, radius);
    const glm::dmat4 view = camera.view();

    int checked = 0;
    for (int row = 3; row < camera.height; row += 7) {
        for (int col = 5; col < camera.width; col += 11) {
            const float depth = buffer.depth.at<float>(row, col);
            if (depth == 0.0f) continue;
            const SyntheticRay ray = camera.rayThrough({col + 0.5, row + 0.5});
            const auto hit = firstSphereHit(ray, center, radius);
            ASSERT_TRUE(hit.has_value()) << col << "," << row;
            const glm::dvec3 normal = (*hit - center) / radius;
            const glm::dvec3 toEye = camera.eye - *hit;
            const double normalDotView = glm::dot(normal, toEye);
            const glm::dvec3 w = toEye - normalDotView * normal;

            const cv::Vec4f radial = buffer.radial.at<cv::Vec4f>(row, col);
            const double distance = glm::length(toEye);
            EXPECT_NEAR(depth, -(view * glm::dvec4(*hit, 1.0)).z, 1e-6 * distance);
            EXPECT_NEAR(radial[0], distance * buffer.nDotV.at<float>(row, col), 1e-6 * distance);
            EXPECT_NEAR(radial[0], normalDotView, 1e-6 * distance);
            EXPECT_NEAR(radial[3] + double(radial[0]) * radial[0], distance * distance, 1e-6 * distance * distance);
            const glm::dvec3 viewNormal = glm::dmat3(view) * normal;
            const cv::Vec4f stored = buffer.normal.at<cv::Vec4f>(row, col);
            EXPECT_NEAR(stored[0], viewNormal.x, 1e-6);
            EXPECT_NEAR(stored[1], viewNormal.y, 1e-6);
            EXPECT_NEAR(stored[2], viewNormal.z, 1e-6);
            EXPECT_EQ(stored[3], 1.0f);

            // J w: how fast the image point moves along w, by a central difference of the projection.
            const double step = 1e-5;
            const glm::dvec2 moved = (camera.project(*hit + step * w) - camera.project(*hit - step * w)) / (2.0 * step);
            const double scale = glm::length(moved) + 1.0;
            EXPECT_NEAR(radial[1], moved.x, 1e-5 * scale) << col << "," << row;
            EXPECT_NEAR(radial[2], moved.y, 1e-5 * scale) << col << "," << row;
            ++checked;
        }
    }
    EXPECT_GT(checked, 100);
}

TEST(SyntheticGBuffer, ProjectInvertsRayThrough) {
    SyntheticCamera camera;
    camera.width = 300;
    camera.height = 200;
    camera.eye = {2.0, 3.0, 1.0};
    camera.up = {0.0, 0.0, 1.0};
    for (const glm::dvec2 point : {glm::dvec2(0.0, 0.0), glm::dvec2(150.0, 100.0), glm::dvec2(299.5, 17.25)}) {
        const SyntheticRay ray = camera.rayThrough(point);
        EXPECT_NEAR(glm::length(ray.direction), 1.0, 1e-12);
        const glm::dvec2 back = camera.project(ray.origin + 2.5 * ray.direction);
        EXPECT_NEAR(back.x, point.x, 1e-9);
        EXPECT_NEAR(back.y, point.y, 1e-9);
    }
}

TEST(SyntheticGBuffer, TorusFromAboveMatchesTubeCircles) {
    // Looking down the axis, the middle column's rays lie in the plane x = 0, which cuts the torus in two circles of
    // radius r about (0, +-R, 0): depth and normal in closed form, including the grazing rays at each circle's edge.
    SyntheticCamera camera;
    camera.width = camera.height = 401; // odd: the middle column's centre is on the axis
    camera.eye = {0.0, 0.0, 3.0};
    camera.up = {0.0, 1.0, 0.0};
    const double ring = 1.0;
    const double tube = 0.3;
    const SyntheticGBuffer buffer = renderTorus(camera, glm::dvec3(0.0), ring, tube);
    const glm::dmat4 view = camera.view();
    const int col = camera.width / 2;
    int hits = 0;
    for (int row = 0; row < camera.height; ++row) {
        const SyntheticRay ray = camera.rayThrough({col + 0.5, row + 0.5});
        ASSERT_NEAR(ray.direction.x, 0.0, 1e-15);
        const glm::dvec2 origin(ray.origin.y, ray.origin.z);
        const glm::dvec2 direction = glm::normalize(glm::dvec2(ray.direction.y, ray.direction.z));
        std::optional<glm::dvec2> nearest;
        glm::dvec2 nearestCenter(0.0);
        for (const double side : {-1.0, 1.0}) {
            const glm::dvec2 center(side * ring, 0.0);
            const auto hit = firstCircleHit(origin, direction, center, tube);
            if (hit && (!nearest || glm::length(*hit - origin) < glm::length(*nearest - origin))) {
                nearest = hit;
                nearestCenter = center;
            }
        }
        const float depth = buffer.depth.at<float>(row, col);
        // Rays passing the circle within 1e-9 could go either way; none of these does.
        ASSERT_EQ(depth > 0.0f, nearest.has_value()) << "row " << row;
        if (!nearest) continue;
        ++hits;
        const glm::dvec3 point(0.0, nearest->x, nearest->y);
        const glm::dvec2 normal2 = (*nearest - nearestCenter) / tube;
        const glm::dvec3 viewNormal = glm::dmat3(view) * glm::dvec3(0.0, normal2.x, normal2.y);
        EXPECT_NEAR(depth, -(view * glm::dvec4(point, 1.0)).z, 1e-6);
        const cv::Vec4f stored = buffer.normal.at<cv::Vec4f>(row, col);
        EXPECT_NEAR(stored[0], viewNormal.x, 1e-6);
        EXPECT_NEAR(stored[1], viewNormal.y, 1e-6);
        EXPECT_NEAR(stored[2], viewNormal.z, 1e-6);
    }
    EXPECT_GT(hits, 40);
}

TEST(SyntheticGBuffer, TorusFromTheSideMatchesOuterCircle) {
    // From the equator plane the middle row's rays lie in z = 0, where the torus is the annulus R - r <= rho <= R + r:
    // the first hit is on the outer circle, grazing at its ends.
    SyntheticCamera camera;
    camera.width = camera.height = 301;
    camera.eye = {0.0, -4.0, 0.0};
    camera.up = {0.0, 0.0, 1.0};
    const double ring = 1.0;
    const double tube = 0.25;
    const SyntheticGBuffer buffer = renderTorus(camera, glm::dvec3(0.0), ring, tube);
    const glm::dmat4 view = camera.view();
    const int row = camera.height / 2;
    int hits = 0;
    for (int col = 0; col < camera.width; ++col) {
        const SyntheticRay ray = camera.rayThrough({col + 0.5, row + 0.5});
        ASSERT_NEAR(ray.direction.z, 0.0, 1e-15);
        const auto hit = firstCircleHit({ray.origin.x, ray.origin.y}, glm::normalize(glm::dvec2(ray.direction)),
                                        glm::dvec2(0.0), ring + tube);
        const float depth = buffer.depth.at<float>(row, col);
        ASSERT_EQ(depth > 0.0f, hit.has_value()) << "col " << col;
        if (!hit) continue;
        ++hits;
        const glm::dvec3 point(hit->x, hit->y, 0.0);
        const glm::dvec3 viewNormal = glm::dmat3(view) * glm::dvec3(*hit / (ring + tube), 0.0);
        EXPECT_NEAR(depth, -(view * glm::dvec4(point, 1.0)).z, 1e-6);
        const cv::Vec4f stored = buffer.normal.at<cv::Vec4f>(row, col);
        EXPECT_NEAR(stored[0], viewNormal.x, 1e-6);
        EXPECT_NEAR(stored[1], viewNormal.y, 1e-6);
        EXPECT_NEAR(stored[2], viewNormal.z, 1e-6);
    }
    EXPECT_GT(hits, 50);
}

TEST(SyntheticGBuffer, TorusHitsLieOnTheSurfaceToDoublePrecision) {
    SyntheticCamera camera;
    camera.eye = {0.5, -3.0, 2.0};
    camera.up = {0.0, 0.0, 1.0};
    const glm::dvec3 center(0.1, -0.2, 0.05);
    const double ring = 1.0;
    const double tube = 0.4;
    int hits = 0;
    double worst = 0.0;
    for (double y = 0.5; y < camera.height; y += 3.7) {
        for (double x = 0.5; x < camera.width; x += 2.9) {
            const SyntheticRay ray = camera.rayThrough({x, y});
            const auto distance = intersectTorus(ray, center, ring, tube);
            if (!distance) continue;
            ++hits;
            const glm::dvec3 local = ray.origin + *distance * ray.direction - center;
            worst = std::max(worst, std::abs(std::hypot(std::hypot(local.x, local.y) - ring, local.z) - tube));
        }
    }
    EXPECT_GT(hits, 1000);
    EXPECT_LT(worst, 1e-9);
}

TEST(SyntheticGBuffer, PlaneHasConstantNormalDistance) {
    // n.(c - p) is the eye's distance to the plane wherever the plane is seen; the horizon crosses the image.
    SyntheticCamera camera;
    camera.width = camera.height = 64;
    camera.eye = {0.0, -3.0, 0.5};
    camera.up = {0.0, 0.0, 1.0};
    const SyntheticGBuffer buffer = renderPlane(camera, glm::dvec3(0.0, 0.0, -0.5), glm::dvec3(0.0, 0.0, 1.0));
    int covered = 0;
    for (int row = 0; row < camera.height; ++row)
        for (int col = 0; col < camera.width; ++col) {
            if (buffer.depth.at<float>(row, col) == 0.0f) continue;
            ++covered;
            EXPECT_NEAR(buffer.radial.at<cv::Vec4f>(row, col)[0], 1.0, 1e-6);
        }
    EXPECT_GT(covered, 64 * 20);
    EXPECT_LT(covered, 64 * 64);
}

TEST(SyntheticGBuffer, RejectsBadArguments) {
    SyntheticCamera camera;
    camera.width = 0;
    EXPECT_THROW(renderSphere(camera, glm::dvec3(0.0), 1.0), std::invalid_argument);
    camera.width = 16;
    EXPECT_THROW(renderSphere(camera, glm::dvec3(0.0), -1.0), std::invalid_argument);
    EXPECT_THROW(renderTorus(camera, glm::dvec3(0.0), 1.0, 1.5), std::invalid_argument);
    EXPECT_THROW(renderPlane(camera, glm::dvec3(0.0), glm::dvec3(0.0)), std::invalid_argument);
    camera.up = glm::normalize(camera.target - camera.eye);
    EXPECT_THROW(renderSphere(camera, glm::dvec3(0.0), 1.0), std::invalid_argument);
}

} // namespace
} // namespace inkgraph::test
