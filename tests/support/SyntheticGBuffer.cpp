#include "tests/support/SyntheticGBuffer.h"

#include <glm/gtc/matrix_transform.hpp>
#include <opencv2/core/utility.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace inkgraph::test {
namespace {

/** The surface under one pixel, in world space; the normal is unit but may face either way. */
struct SurfaceHit {
    glm::dvec3 point;
    glm::dvec3 normal;
};

/** c[0] + c[1] x + ... + c[degree] x^degree. */
double evaluatePolynomial(const double* coefficients, int degree, double x) {
    double value = coefficients[degree];
    for (int power = degree - 1; power >= 0; --power) value = value * x + coefficients[power];
    return value;
}

/** The one root of a polynomial that is monotone on [low, high] and changes sign there: Newton steps, with
 *  bisection whenever a step leaves the bracket, so it converges like Newton and never escapes. */
double refineBracketedRoot(const double* coefficients, int degree, double low, double high) {
    double derivative[4];
    for (int power = 1; power <= degree; ++power) derivative[power - 1] = power * coefficients[power];
    const bool lowIsNegative = evaluatePolynomial(coefficients, degree, low) < 0.0;
    double x = 0.5 * (low + high);
    for (int iteration = 0; iteration < 200; ++iteration) {
        const double value = evaluatePolynomial(coefficients, degree, x);
        if (value == 0.0) return x;
        if ((value < 0.0) == lowIsNegative)
            low = x;
        else
            high = x;
        const double slope = evaluatePolynomial(derivative, degree - 1, x);
        double next = slope != 0.0 ? x - value / slope : 0.5 * (low + high);
        if (!(next > low && next < high)) next = 0.5 * (low + high);
        if (std::abs(next - x) <= 1e-15 * std::max(1.0, std::abs(x)) ||
            high - low <= 1e-15 * std::max(1.0, std::abs(x)))
            return next;
        x = next;
    }
    return x;
}

/** Every real root in [low, high], ascending; returns their count (at most `degree`). Between consecutive roots of
 *  the derivative the polynomial is monotone, so a sign change there brackets exactly one root: nothing is missed
 *  however close two roots lie, which is what a grazing ray produces. */
int polynomialRootsIn(const double* coefficients, int degree, double low, double high, double* roots) {
    if (degree <= 0) return 0;
    if (degree == 1) {
        if (coefficients[1] == 0.0) return 0;
        const double root = -coefficients[0] / coefficients[1];
        if (!(root >= low && root <= high)) return 0;
        roots[0] = root;
        return 1;
    }
    double derivative[4];
    for (int power = 1; power <= degree; ++power) derivative[power - 1] = power * coefficients[power];
    double knots[6];
    knots[0] = low;
    const int criticalCount = polynomialRootsIn(derivative, degree - 1, low, high, knots + 1);
    knots[criticalCount + 1] = high;

    int rootCount = 0;
    auto addRoot = [&](double root) {
        if (rootCount == 0 || root > roots[rootCount - 1]) roots[rootCount++] = root;
    };
    for (int interval = 0; interval <= criticalCount; ++interval) {
        const double a = knots[interval];
        const double b = knots[interval + 1];
        const double valueA = evaluatePolynomial(coefficients, degree, a);
        const double valueB = evaluatePolynomial(coefficients, degree, b);
        if (valueA == 0.0) addRoot(a);
        if (valueA != 0.0 && valueB != 0.0 && (valueA < 0.0) != (valueB < 0.0))
            addRoot(refineBracketedRoot(coefficients, degree, a, b));
        if (valueB == 0.0 && interval == criticalCount) addRoot(b);
    }
    return rootCount;
}

/** The two distances where the ray meets a sphere, if it does; the nearer is computed without cancellation. */
std::optional<std::pair<double, double>> sphereInterval(const SyntheticRay& ray, const glm::dvec3& center,
                                                        double radius) {
    const glm::dvec3 offset = ray.origin - center;
    const double halfB = glm::dot(offset, ray.direction);
    const double c = glm::dot(offset, offset) - radius * radius;
    const double discriminant = halfB * halfB - c;
    if (discriminant < 0.0) return std::nullopt;
    const double root = std::sqrt(discriminant);
    // q = -(halfB + sign(halfB) root) has no cancellation; the two distances are q and c / q.
    const double q = halfB > 0.0 ? -(halfB + root) : -(halfB - root);
    if (q == 0.0) return std::pair{0.0, 0.0};
    const double first = q;
    const double second = c / q;
    return std::pair{std::min(first, second), std::max(first, second)};
}

std::optional<SurfaceHit> hitSphere(const SyntheticRay& ray, const glm::dvec3& center, double radius) {
    const auto interval = sphereInterval(ray, center, radius);
    if (!interval) return std::nullopt;
    // From outside the nearer distance; from inside (eye in the sphere) the far one.
    const double distance = interval->first > 0.0 ? interval->first : interval->second;
    if (!(distance > 0.0)) return std::nullopt;
    const glm::dvec3 point = ray.origin + distance * ray.direction;
    return SurfaceHit{point, (point - center) / radius};
}

std::optional<SurfaceHit> hitTorus(const SyntheticRay& ray, const glm::dvec3& center, double ringRadius,
                                   double tubeRadius) {
    const auto distance = intersectTorus(ray, center, ringRadius, tubeRadius);
    if (!distance) return std::nullopt;
    const glm::dvec3 point = ray.origin + *distance * ray.direction;
    const glm::dvec3 local = point - center;
    const double axial = std::hypot(local.x, local.y);
    const glm::dvec3 ringPoint(ringRadius * local.x / axial, ringRadius * local.y / axial, 0.0);
    return SurfaceHit{point, glm::normalize(local - ringPoint)};
}

std::optional<SurfaceHit> hitPlane(const SyntheticRay& ray, const glm::dvec3& planePoint, const glm::dvec3& normal) {
    const double approach = glm::dot(normal, ray.direction);
    if (approach == 0.0) return std::nullopt;
    const double distance = glm::dot(normal, planePoint - ray.origin) / approach;
    if (!(distance > 0.0) || !std::isfinite(distance)) return std::nullopt;
    return SurfaceHit{ray.origin + distance * ray.direction, normal};
}

/** One ray per pixel centre; the view-space fields from each hit, in double until the final float. */
template <typename Intersect>
SyntheticGBuffer renderSurface(const SyntheticCamera& camera, Intersect intersect) {
    SyntheticGBuffer buffer;
    const cv::Size size(camera.width, camera.height);
    buffer.normal = cv::Mat::zeros(size, CV_32FC4);
    buffer.nDotV = cv::Mat::zeros(size, CV_32FC1);
    buffer.depth = cv::Mat::zeros(size, CV_32FC1);
    buffer.radial = cv::Mat::zeros(size, CV_32FC4);
    const glm::dmat4 view = camera.view();
    const glm::dmat3 rotation(view);
    const double focal = camera.focalPixels();

    cv::parallel_for_(cv::Range(0, camera.height), [&](const cv::Range& rows) {
        for (int row = rows.start; row < rows.end; ++row) {
            auto* normalRow = buffer.normal.ptr<cv::Vec4f>(row);
            auto* nDotVRow = buffer.nDotV.ptr<float>(row);
            auto* depthRow = buffer.depth.ptr<float>(row);
            auto* radialRow = buffer.radial.ptr<cv::Vec4f>(row);
            for (int col = 0; col < camera.width; ++col) {
                const auto hit = intersect(camera.rayThrough({col + 0.5, row + 0.5}));
                if (!hit) continue;
                const glm::dvec3 point = glm::dvec3(view * glm::dvec4(hit->point, 1.0));
                glm::dvec3 normal = glm::normalize(rotation * hit->normal);
                const glm::dvec3 toEye = -point; // v = c - p, the eye being the view-space origin
                if (glm::dot(normal, toEye) < 0.0) normal = -normal;
                const double normalDotView = glm::dot(normal, toEye);
                const glm::dvec3 tangential = toEye - normalDotView * normal;
                // J v = 0 (moving along the eye ray does not move the pixel), so J w = -(n.v) J n exactly, and
                // J n has no cancellation where J applied to w itself would.
                const double z = point.z;
                const glm::dvec2 jacobianNormal(focal * (-normal.x / z + point.x * normal.z / (z * z)),
                                                focal * (normal.y / z - point.y * normal.z / (z * z)));
                const glm::dvec2 jacobianW = -normalDotView * jacobianNormal;

                normalRow[col] = {float(normal.x), float(normal.y), float(normal.z), 1.0f};
                nDotVRow[col] = float(normalDotView / glm::length(toEye));
                depthRow[col] = float(-z);
                radialRow[col] = {float(normalDotView), float(jacobianW.x), float(jacobianW.y),
                                  float(glm::dot(tangential, tangential))};
            }
        }
    });
    return buffer;
}

} // namespace

double SyntheticCamera::focalPixels() const { return (height / 2.0) / std::tan(glm::radians(fovYDegrees) / 2.0); }

glm::dmat4 SyntheticCamera::view() const { return glm::lookAt(eye, target, up); }

SyntheticRay SyntheticCamera::rayThrough(const glm::dvec2& imagePoint) const {
    const double focal = focalPixels();
    const glm::dvec3 viewDirection((imagePoint.x - width / 2.0) / focal, -(imagePoint.y - height / 2.0) / focal, -1.0);
    const glm::dmat3 viewToWorld = glm::transpose(glm::dmat3(view()));
    return {eye, glm::normalize(viewToWorld * viewDirection)};
}

glm::dvec2 SyntheticCamera::project(const glm::dvec3& worldPoint) const {
    const glm::dvec3 point = glm::dvec3(view() * glm::dvec4(worldPoint, 1.0));
    const double focal = focalPixels();
    return {width / 2.0 + focal * point.x / -point.z, height / 2.0 - focal * point.y / -point.z};
}

void SyntheticCamera::check(const char* function) const {
    if (width <= 0 || height <= 0)
        throw std::invalid_argument(std::string(function) + ": 'camera' size must be positive");
    if (!(fovYDegrees > 0.0 && fovYDegrees < 180.0))
        throw std::invalid_argument(std::string(function) + ": 'camera' fovYDegrees must lie in (0, 180)");
    const glm::dvec3 forward = target - eye;
    if (!(glm::length(forward) > 0.0) || !(glm::length(glm::cross(forward, up)) > 0.0))
        throw std::invalid_argument(std::string(function) +
                                    ": 'camera' needs eye != target and 'up' not along the view direction");
}

std::optional<double> intersectTorus(const SyntheticRay& ray, const glm::dvec3& center, double ringRadius,
                                     double tubeRadius) {
    // Only the part of the ray inside the bounding sphere can hit; starting the polynomial there keeps its
    // coefficients of order (R + r)^4, so it is evaluated to ~1e-15 relative near its roots.
    const auto bounds = sphereInterval(ray, center, (ringRadius + tubeRadius) * (1.0 + 1e-9));
    if (!bounds || bounds->second <= 0.0) return std::nullopt;
    const double start = std::max(bounds->first, 0.0);
    const glm::dvec3 origin = ray.origin + start * ray.direction - center;
    const glm::dvec3& direction = ray.direction;

    // (|p|^2 + R^2 - r^2)^2 = 4 R^2 (x^2 + y^2) with p = origin + s direction and |direction| = 1.
    const double ring2 = ringRadius * ringRadius;
    const double sumLinear = 2.0 * glm::dot(origin, direction);
    const double sumConstant = glm::dot(origin, origin) + ring2 - tubeRadius * tubeRadius;
    const double planarQuadratic = direction.x * direction.x + direction.y * direction.y;
    const double planarLinear = 2.0 * (origin.x * direction.x + origin.y * direction.y);
    const double planarConstant = origin.x * origin.x + origin.y * origin.y;
    const double coefficients[5] = {
        sumConstant * sumConstant - 4.0 * ring2 * planarConstant,
        2.0 * sumLinear * sumConstant - 4.0 * ring2 * planarLinear,
        sumLinear * sumLinear + 2.0 * sumConstant - 4.0 * ring2 * planarQuadratic,
        2.0 * sumLinear,
        1.0,
    };
    double roots[4];
    const int rootCount = polynomialRootsIn(coefficients, 4, 0.0, bounds->second - start, roots);
    if (rootCount == 0) return std::nullopt;
    return start + roots[0];
}

SyntheticGBuffer renderSphere(const SyntheticCamera& camera, const glm::dvec3& center, double radius) {
    camera.check("renderSphere()");
    if (!(radius > 0.0) || !std::isfinite(radius))
        throw std::invalid_argument("renderSphere(): 'radius' must be positive and finite");
    return renderSurface(camera, [&](const SyntheticRay& ray) { return hitSphere(ray, center, radius); });
}

SyntheticGBuffer renderTorus(const SyntheticCamera& camera, const glm::dvec3& center, double ringRadius,
                             double tubeRadius) {
    camera.check("renderTorus()");
    if (!(tubeRadius > 0.0 && tubeRadius < ringRadius) || !std::isfinite(ringRadius))
        throw std::invalid_argument("renderTorus(): need 0 < 'tubeRadius' < 'ringRadius' (a ring torus)");
    return renderSurface(camera,
                         [&](const SyntheticRay& ray) { return hitTorus(ray, center, ringRadius, tubeRadius); });
}

SyntheticGBuffer renderPlane(const SyntheticCamera& camera, const glm::dvec3& point, const glm::dvec3& normal) {
    camera.check("renderPlane()");
    if (!(glm::length(normal) > 0.0)) throw std::invalid_argument("renderPlane(): 'normal' must be non-zero");
    const glm::dvec3 unitNormal = glm::normalize(normal);
    return renderSurface(camera, [&](const SyntheticRay& ray) { return hitPlane(ray, point, unitNormal); });
}

} // namespace inkgraph::test
