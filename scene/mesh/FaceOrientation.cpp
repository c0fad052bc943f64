#include "scene/mesh/FaceOrientation.h"

#include "scene/MessageText.h"
#include "scene/mesh/MeshOps.h"

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

namespace inkgraph {

namespace {

/** chooseViewVector() falls back to exact vectors when the eye is within this fraction of the radius outside the
 *  bounding sphere (counted as inside), or when sin(alpha) exceeds kMaxSinAlpha: beyond that the constant vector is
 *  too rough for the specular term and the cut-off accepts nearly everything (docs/shading.md). */
constexpr double kInsideMargin = 1e-3;
constexpr double kMaxSinAlpha = 0.5;

/** Added to the front cut-off of the approximate tests. Stored unit normals are floats, off by ~1e-7 in length and
 *  direction, which could otherwise drop a face that is front by a hair. It can only add front triangles. */
constexpr double kCutoffSlack = 1e-6;

/** Per-vertex flags of the vertex methods. */
constexpr std::uint8_t kFrontVertex = 1;     // N.V < cut-off: lit, counts toward the front rule
constexpr std::uint8_t kDeepFrontVertex = 2; // N.V <= -cut-off: not intermediate

/** During-vertices adds kFrontStep to a triangle's counter per front vertex and kDeepStep more per deep-front vertex,
 *  so one byte holds both counts: front = counter & 3, deep = counter >> 2. */
constexpr std::uint8_t kFrontStep = 1;
constexpr std::uint8_t kDeepStep = 4;
constexpr std::uint8_t kFrontCountMask = 3;
constexpr std::uint8_t kAllThreeDeep = 3 * (kFrontStep + kDeepStep);

[[noreturn]] void invalid(const char* function, const std::string& problem) {
    throw std::invalid_argument(std::string(function) + ": " + problem);
}

bool isFinite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

/** n_f.(P - E) < 0 with the unnormalised face normal and P the first vertex, in double. Every exact classification
 *  goes through here so they agree bit for bit. */
inline bool isExactFront(const glm::vec3* positions, const glm::uvec3& triangle, const glm::dvec3& eye) {
    const glm::dvec3 a(positions[triangle.x]);
    const glm::dvec3 b(positions[triangle.y]);
    const glm::dvec3 c(positions[triangle.z]);
    return glm::dot(glm::cross(b - a, c - a), a - eye) < 0.0;
}

/** The largest angle between pairs of vectors, with one atan2 at the end instead of one per pair: with c = |a x b|
 *  and d = a.b, angle 1 exceeds angle 2 exactly when c1 d2 - d1 c2 > 0 (a positive multiple of the sine of their
 *  difference, which lies in (-pi, pi) unless the angles are 0 and pi; that pair is handled apart). */
class LargestAngle {
public:
    void add(const glm::dvec3& a, const glm::dvec3& b) {
        const double c = glm::length(glm::cross(a, b));
        const double d = glm::dot(a, b);
        if (c == 0.0) {
            if (d < 0.0) { // opposite: pi, which nothing exceeds
                mSin = 0.0;
                mCos = -1.0;
            }
            return;
        }
        if (c * mCos - d * mSin > 0.0) {
            mSin = c;
            mCos = d;
        }
    }
    double radians() const { return std::atan2(mSin, mCos); }

private:
    double mSin = 0.0;
    double mCos = 1.0;
};

/** What every vertex evaluation needs, fixed for one call. */
struct ViewTerms {
    bool constant = false;
    glm::dvec3 constantView{0.0}; ///< unit V_c when `constant`
    glm::dvec3 eye{0.0};
    glm::dvec3 towardLight{0.0}; ///< unit L
    double constantDotLV = 0.0;  ///< L.V_c, once per call (Winnemöller & Bangay 2002 §3.6)
    double shininess = 0.0;
    std::uint32_t wholeShininess = 0; ///< the shininess when it is a whole number in [1, 1024], else 0
};

/** The cut-off and the two thresholds derived from it. */
struct Cutoff {
    double reported = 0.0;   ///< the formula's value (with betaMax for the vertex tests: the largest cut-off)
    double frontBelow = 0.0; ///< front <=> N.V < frontBelow (cut-off + slack, or +inf when everything is front)
    double deepAtMost = 0.0; ///< not intermediate <=> N.V <= deepAtMost (= -cut-off)
    bool perVertex = false;  ///< vertex tests: each vertex's own cut-off from alpha and its beta (forVertex())
    double sinAlpha = 0.0;
    double cosAlpha = 1.0;

    /** The thresholds for a vertex of (sin beta, cos beta): sin(alpha + beta) by the angle sum, no trig per vertex. */
    Cutoff forVertex(const glm::vec2& beta) const {
        if (!perVertex) {
            return *this;
        }
        const double sinBeta = beta.x;
        const double cosBeta = beta.y;
        if (cosAlpha * cosBeta - sinAlpha * sinBeta <= 0.0) { // alpha + beta >= pi/2: see cutoffFor()
            return {reported, std::numeric_limits<double>::infinity(), -1.0};
        }
        const double cutoff = sinAlpha * cosBeta + cosAlpha * sinBeta;
        return {reported, cutoff + kCutoffSlack, -cutoff};
    }
};

Cutoff cutoffFor(const OrientationRequest& request, double betaMaxRadians, bool faceTest) {
    const double sinAlpha = request.view.constant ? std::clamp(request.view.sinAlpha, 0.0, 1.0) : 0.0;
    if (request.paperCutoff) {
        // The paper's reading: -sin(alpha) for faces and vertices alike, no betaMax, no slack.
        const double cutoff = -sinAlpha;
        return {cutoff, cutoff, -cutoff};
    }
    if (faceTest) {
        return {sinAlpha, sinAlpha + kCutoffSlack, -sinAlpha};
    }
    const double angle = std::asin(sinAlpha) + betaMaxRadians;
    Cutoff cutoff;
    cutoff.perVertex = true;
    cutoff.sinAlpha = sinAlpha;
    cutoff.cosAlpha = std::sqrt(std::max(0.0, 1.0 - sinAlpha * sinAlpha));
    if (angle >= glm::half_pi<double>()) {
        // The bound angle(N_v, V) > pi/2 - alpha - beta says nothing any more: N.V = 1 exactly may still belong
        // to a front face, so the strict test against sin(pi/2) = 1 would not do.
        cutoff.reported = 1.0;
        cutoff.frontBelow = std::numeric_limits<double>::infinity();
        cutoff.deepAtMost = -1.0;
        return cutoff;
    }
    cutoff.reported = std::sin(angle);
    cutoff.frontBelow = cutoff.reported + kCutoffSlack;
    cutoff.deepAtMost = -cutoff.reported;
    return cutoff;
}

/** Whole shininess values up to this are raised by repeated squaring (at most 10 squarings and 10 products, a few
 *  ulp from std::pow and several times cheaper); larger or fractional ones use std::pow. */
constexpr double kMaxSquaringShininess = 1024.0;

/** base^shininess for base in (0, 1]; `wholeShininess` > 0 selects repeated squaring. */
inline double specularPower(double base, double shininess, std::uint32_t wholeShininess) {
    if (wholeShininess == 0) {
        return std::pow(base, shininess);
    }
    double power = 1.0;
    for (std::uint32_t n = wholeShininess; n != 0; n >>= 1) {
        if (n & 1u) {
            power *= base;
        }
        base *= base;
    }
    return power;
}

/** (s, t) of Listing 1 for unit N, L and V (V eye -> point), with the paper's R.V = L.V - 2 (N.L)(N.V)
 *  (docs/shading.md; the same number as the textbook r.v with v = -V). */
inline glm::vec2 shadeCoord(double dotNL, double dotNV, double dotLV, double shininess, std::uint32_t wholeShininess) {
    if (!(dotNL > 0.0)) {
        return glm::vec2(0.0f); // no diffuse and, as in Phong's gate, no specular
    }
    // Clamped before the power: a negative base is undefined, and rounding above 1 would grow with the exponent.
    const double dotRV = std::clamp(dotLV - 2.0 * dotNL * dotNV, 0.0, 1.0);
    const double specular =
        shininess == 0.0 ? 1.0 : (dotRV > 0.0 ? specularPower(dotRV, shininess, wholeShininess) : 0.0);
    return {float(std::min(dotNL, 1.0)), float(specular)};
}

inline glm::dvec3 viewAt(const ViewTerms& terms, const glm::vec3& position) {
    return terms.constant ? terms.constantView : normalizedOrZero(glm::dvec3(position) - terms.eye);
}

inline glm::vec2 lightVertex(const ViewTerms& terms, const glm::dvec3& normal, const glm::dvec3& view, double dotNV) {
    const double dotLV = terms.constant ? terms.constantDotLV : glm::dot(terms.towardLight, view);
    return shadeCoord(glm::dot(normal, terms.towardLight), dotNV, dotLV, terms.shininess, terms.wholeShininess);
}

/** Listing 1's vertex loop body: orientation, and lighting only for front vertices. Returns the flags. */
inline std::uint8_t classifyVertex(const ViewTerms& terms, const Cutoff& cutoff, const glm::vec3& position,
                                   const glm::vec3& storedNormal, glm::vec2& shade) {
    const glm::dvec3 normal(storedNormal);
    const glm::dvec3 view = viewAt(terms, position);
    const double dotNV = glm::dot(normal, view);
    if (!(dotNV < cutoff.frontBelow)) {
        return 0;
    }
    shade = lightVertex(terms, normal, view, dotNV);
    return dotNV <= cutoff.deepAtMost ? std::uint8_t(kFrontVertex | kDeepFrontVertex) : kFrontVertex;
}

/** Adds one triangle to the lists: front ones to the fill, the rest and the intermediate front ones to the outline. */
inline void sortTriangle(MeshOrientation& result, const glm::uvec3& triangle, bool front, bool intermediate,
                         bool countMissed, const glm::vec3* positions, const glm::dvec3& eye) {
    if (front) {
        result.frontTriangles.push_back(triangle);
        if (intermediate) {
            result.backTriangles.push_back(triangle);
        }
        return;
    }
    result.backTriangles.push_back(triangle);
    if (countMissed && isExactFront(positions, triangle, eye)) {
        ++result.missedTriangles;
    }
}

/** How many front vertices each rule asks of a triangle. */
int frontVerticesNeeded(int frontRule) { return 4 - frontRule; }

void markDuringTriangles(const Mesh& mesh, const OrientationMeshData& data, const OrientationRequest& request,
                         const ViewTerms& terms, const Cutoff& cutoff, MeshOrientation& result) {
    const glm::vec3* positions = mesh.positions.data();
    std::vector<std::uint8_t> marked(mesh.positions.size(), 0);
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
        const glm::uvec3& triangle = mesh.triangles[i];
        bool front = false;
        bool intermediate = false;
        if (terms.constant) {
            const double dotNV = glm::dot(glm::dvec3(data.faceNormals[i]), terms.constantView);
            front = dotNV < cutoff.frontBelow;
            intermediate = dotNV > cutoff.deepAtMost;
        } else {
            // Exact vectors: n_f.(P - E) is the same at every point of the face's plane, so the face test is the
            // exact test; its cut-off is 0, and no front face has n_f.V > -0.
            front = isExactFront(positions, triangle, terms.eye);
        }
        if (front) {
            marked[triangle.x] = 1;
            marked[triangle.y] = 1;
            marked[triangle.z] = 1;
        }
        sortTriangle(result, triangle, front, intermediate, request.countMissed, positions, terms.eye);
    }
    for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
        if (!marked[v]) {
            continue;
        }
        ++result.frontVertexCount;
        const glm::dvec3 normal(mesh.normals[v]);
        const glm::dvec3 view = viewAt(terms, mesh.positions[v]);
        result.shadeCoords[v] = lightVertex(terms, normal, view, glm::dot(normal, view));
    }
}

void markDuringVertices(const Mesh& mesh, const OrientationMeshData& data, const OrientationRequest& request,
                        const ViewTerms& terms, const Cutoff& cutoff, MeshOrientation& result) {
    const glm::vec3* positions = mesh.positions.data();
    const std::uint32_t* start = data.vertexTriangleStart.data();
    const std::uint32_t* around = data.vertexTriangles.data();
    std::vector<std::uint8_t> counters(mesh.triangles.size(), 0);
    for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
        const std::uint8_t flags = classifyVertex(terms, cutoff.forVertex(data.vertexBeta[v]), mesh.positions[v],
                                                  mesh.normals[v], result.shadeCoords[v]);
        if (!flags) {
            continue;
        }
        ++result.frontVertexCount;
        const std::uint8_t step = (flags & kDeepFrontVertex) ? kFrontStep + kDeepStep : kFrontStep;
        for (std::uint32_t k = start[v]; k < start[v + 1]; ++k) {
            counters[around[k]] += step;
        }
    }
    const int needed = frontVerticesNeeded(request.frontRule);
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
        const std::uint8_t counter = counters[i];
        const bool front = (counter & kFrontCountMask) >= needed;
        sortTriangle(result, mesh.triangles[i], front, counter != kAllThreeDeep, request.countMissed, positions,
                     terms.eye);
    }
}

void markAfterVertices(const Mesh& mesh, const OrientationMeshData& data, const OrientationRequest& request,
                       const ViewTerms& terms, const Cutoff& cutoff, MeshOrientation& result) {
    const glm::vec3* positions = mesh.positions.data();
    std::vector<std::uint8_t> flags(mesh.positions.size());
    for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
        flags[v] = classifyVertex(terms, cutoff.forVertex(data.vertexBeta[v]), mesh.positions[v], mesh.normals[v],
                                  result.shadeCoords[v]);
        result.frontVertexCount += flags[v] & kFrontVertex;
    }
    const int needed = frontVerticesNeeded(request.frontRule);
    for (const glm::uvec3& triangle : mesh.triangles) {
        const std::uint8_t a = flags[triangle.x];
        const std::uint8_t b = flags[triangle.y];
        const std::uint8_t c = flags[triangle.z];
        const int frontCount = (a & kFrontVertex) + (b & kFrontVertex) + (c & kFrontVertex);
        const bool allDeep = (a & b & c & kDeepFrontVertex) != 0;
        sortTriangle(result, triangle, frontCount >= needed, !allDeep, request.countMissed, positions, terms.eye);
    }
}

ViewTerms viewTermsFor(const OrientationRequest& request) {
    constexpr const char* function = "orientMesh()";
    if (!isFinite(request.eye)) {
        invalid(function, "the eye must be finite");
    }
    ViewTerms terms;
    terms.eye = request.eye;
    terms.towardLight = normalizedOrZero(request.towardLight);
    if (terms.towardLight == glm::dvec3(0.0)) {
        invalid(function, "'towardLight' must be a finite, non-zero direction");
    }
    terms.shininess = request.shininess;
    if (request.shininess >= 1.0 && request.shininess <= kMaxSquaringShininess &&
        request.shininess == std::floor(request.shininess)) {
        terms.wholeShininess = std::uint32_t(request.shininess);
    }
    terms.constant = request.view.constant;
    if (terms.constant) {
        terms.constantView = normalizedOrZero(request.view.constantView);
        if (terms.constantView == glm::dvec3(0.0) || !std::isfinite(request.view.sinAlpha)) {
            invalid(function, "a constant view needs a finite, non-zero 'constantView' and a finite 'sinAlpha'");
        }
        terms.constantDotLV = glm::dot(terms.towardLight, terms.constantView);
    }
    return terms;
}

} // namespace

std::string viewVectorModeName(ViewVectorMode mode) {
    switch (mode) {
    case ViewVectorMode::Exact: return "exact";
    case ViewVectorMode::Constant: return "constant";
    }
    return "unknown";
}

std::string faceOrientationMethodName(FaceOrientationMethod mode) {
    switch (mode) {
    case FaceOrientationMethod::Standard: return "standard";
    case FaceOrientationMethod::DuringTriangles: return "during-triangles";
    case FaceOrientationMethod::DuringVertices: return "during-vertices";
    case FaceOrientationMethod::AfterVertices: return "after-vertices";
    }
    return "unknown";
}

OrientationMeshData deriveOrientationData(const Mesh& mesh, bool withVertexTriangles) {
    constexpr const char* function = "deriveOrientationData()";
    const std::size_t vertexCount = mesh.positions.size();
    if (mesh.normals.size() != vertexCount) {
        invalid(function, "mesh '" + detail::excerptForMessage(mesh.name) + "' has " +
                              std::to_string(mesh.normals.size()) + " normals for " + std::to_string(vertexCount) +
                              " positions");
    }
    if (withVertexTriangles && mesh.triangles.size() > std::numeric_limits<std::uint32_t>::max() / 3) {
        invalid(function, "mesh '" + detail::excerptForMessage(mesh.name) +
                              "' has too many triangles for 32-bit adjacency offsets");
    }

    OrientationMeshData data;
    data.faceNormals.resize(mesh.triangles.size());
    std::vector<LargestAngle> vertexBeta(vertexCount);
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
        const glm::uvec3& triangle = mesh.triangles[i];
        if (std::max(triangle.x, std::max(triangle.y, triangle.z)) >= vertexCount) {
            invalid(function, "mesh '" + detail::excerptForMessage(mesh.name) + "' triangle " + std::to_string(i) +
                                  " uses a vertex past its " + std::to_string(vertexCount) + " vertices");
        }
        const glm::dvec3 a(mesh.positions[triangle.x]);
        const glm::dvec3 b(mesh.positions[triangle.y]);
        const glm::dvec3 c(mesh.positions[triangle.z]);
        const glm::dvec3 faceNormal = normalizedOrZero(glm::cross(b - a, c - a));
        data.faceNormals[i] = glm::vec3(faceNormal);
        // Measured against the double normal, not its float copy; a zero (degenerate) face adds nothing.
        for (int corner = 0; corner < 3; ++corner) {
            vertexBeta[triangle[corner]].add(glm::dvec3(mesh.normals[triangle[corner]]), faceNormal);
        }
    }
    data.vertexBeta.resize(vertexCount);
    for (std::size_t v = 0; v < vertexCount; ++v) {
        const double beta = vertexBeta[v].radians();
        // Rounded up to float so the float copy never understates beta (which could drop a front vertex).
        data.vertexBeta[v] =
            glm::vec2(std::nextafter(float(std::sin(beta)), 2.0f), std::nextafter(float(std::cos(beta)), -2.0f));
        data.betaMaxRadians = std::max(data.betaMaxRadians, beta);
    }

    if (withVertexTriangles) {
        // Compressed rows: count the triangles of each vertex, prefix-sum into offsets, then fill.
        std::vector<std::uint32_t>& start = data.vertexTriangleStart;
        start.assign(vertexCount + 1, 0);
        for (const glm::uvec3& triangle : mesh.triangles) {
            ++start[triangle.x + 1];
            ++start[triangle.y + 1];
            ++start[triangle.z + 1];
        }
        for (std::size_t v = 0; v < vertexCount; ++v) {
            start[v + 1] += start[v];
        }
        data.vertexTriangles.resize(start[vertexCount]);
        std::vector<std::uint32_t> cursor(start.begin(), start.end() - 1);
        for (std::uint32_t i = 0; i < mesh.triangles.size(); ++i) {
            const glm::uvec3& triangle = mesh.triangles[i];
            data.vertexTriangles[cursor[triangle.x]++] = i;
            data.vertexTriangles[cursor[triangle.y]++] = i;
            data.vertexTriangles[cursor[triangle.z]++] = i;
        }
    }
    return data;
}

ViewVectorChoice chooseViewVector(ViewVectorMode requested, const glm::dvec3& eye, const glm::dvec3& center,
                                  double radius) {
    constexpr const char* function = "chooseViewVector()";
    if (!isFinite(eye) || !isFinite(center)) {
        invalid(function, "the eye and the centre must be finite");
    }
    if (!std::isfinite(radius) || radius < 0.0) {
        invalid(function, "the radius must be finite and >= 0, got " + std::to_string(radius));
    }
    ViewVectorChoice choice;
    if (requested == ViewVectorMode::Exact) {
        return choice;
    }
    const glm::dvec3 toCenter = center - eye;
    const double distance = glm::length(toCenter);
    if (!std::isfinite(distance)) {
        invalid(function, "the distance from the eye to the centre overflows a double");
    }
    // Compared before any division, so an eye at the centre (distance 0) never normalises a zero vector.
    if (distance <= radius * (1.0 + kInsideMargin)) {
        choice.fellBack = true;
        choice.reason = "eye inside the bounding sphere";
        return choice;
    }
    const double sinAlpha = radius / distance; // < 1 here, so asin(sinAlpha) is always defined
    if (sinAlpha > kMaxSinAlpha) {
        char reason[128];
        std::snprintf(reason, sizeof(reason),
                      "eye within %g radii of the bounding-sphere centre (sin alpha = %.2f > %g)", 1.0 / kMaxSinAlpha,
                      sinAlpha, kMaxSinAlpha);
        choice.fellBack = true;
        choice.reason = reason;
        return choice;
    }
    choice.constant = true;
    choice.constantView = toCenter / distance;
    choice.sinAlpha = sinAlpha;
    return choice;
}

void orientMesh(const Mesh& mesh, const OrientationMeshData& data, const OrientationRequest& request,
                MeshOrientation& result) {
    constexpr const char* function = "orientMesh()";
    if (request.method == FaceOrientationMethod::Standard) {
        invalid(function, "the 'standard' method runs on the GPU; pick a CPU method");
    }
    if (request.frontRule < 1 || request.frontRule > 3) {
        invalid(function, "the front rule must be 1, 2 or 3, got " + std::to_string(request.frontRule));
    }
    if (!(request.shininess >= 0.0)) {
        invalid(function, "the shininess must be >= 0, got " + std::to_string(request.shininess));
    }
    if (mesh.normals.size() != mesh.positions.size() || data.faceNormals.size() != mesh.triangles.size() ||
        data.vertexBeta.size() != mesh.positions.size()) {
        invalid(function, "mesh '" + detail::excerptForMessage(mesh.name) +
                              "' does not match its derived data (normals, face normals or vertex betas)");
    }
    if (request.method == FaceOrientationMethod::DuringVertices &&
        (data.vertexTriangleStart.size() != mesh.positions.size() + 1 ||
         data.vertexTriangles.size() != data.vertexTriangleStart.back())) {
        invalid(function, "'during-vertices' needs the vertex-triangle adjacency of mesh '" +
                              detail::excerptForMessage(mesh.name) + "' (deriveOrientationData(mesh, true))");
    }
    const ViewTerms terms = viewTermsFor(request);
    const bool faceTest = request.method == FaceOrientationMethod::DuringTriangles;
    const Cutoff cutoff = cutoffFor(request, data.betaMaxRadians, faceTest);

    result.cutoff = cutoff.reported;
    result.betaMaxRadians = data.betaMaxRadians;
    result.frontVertexCount = 0;
    result.missedTriangles = 0;
    result.shadeCoords.assign(mesh.positions.size(), glm::vec2(0.0f));
    // Worst case for each list; only the pages written are ever touched, so the unused capacity costs no time.
    result.frontTriangles.clear();
    result.backTriangles.clear();
    result.frontTriangles.reserve(mesh.triangles.size());
    result.backTriangles.reserve(mesh.triangles.size());

    switch (request.method) {
    case FaceOrientationMethod::DuringTriangles: markDuringTriangles(mesh, data, request, terms, cutoff, result); break;
    case FaceOrientationMethod::DuringVertices: markDuringVertices(mesh, data, request, terms, cutoff, result); break;
    case FaceOrientationMethod::AfterVertices: markAfterVertices(mesh, data, request, terms, cutoff, result); break;
    case FaceOrientationMethod::Standard: break;
    }
}

MeshOrientation orientMesh(const Mesh& mesh, const OrientationMeshData& data, const OrientationRequest& request) {
    MeshOrientation result;
    orientMesh(mesh, data, request, result);
    return result;
}

std::size_t countExactFrontTriangles(const Mesh& mesh, const glm::dvec3& eye) {
    const glm::vec3* positions = mesh.positions.data();
    std::size_t count = 0;
    for (const glm::uvec3& triangle : mesh.triangles) {
        count += isExactFront(positions, triangle, eye) ? 1 : 0;
    }
    return count;
}

std::size_t countExactFrontVertices(const Mesh& mesh, const glm::dvec3& eye) {
    const glm::vec3* positions = mesh.positions.data();
    std::vector<std::uint8_t> used(mesh.positions.size(), 0);
    for (const glm::uvec3& triangle : mesh.triangles) {
        if (isExactFront(positions, triangle, eye)) {
            used[triangle.x] = 1;
            used[triangle.y] = 1;
            used[triangle.z] = 1;
        }
    }
    return std::size_t(std::count(used.begin(), used.end(), std::uint8_t(1)));
}

std::size_t countMissedTriangles(const Mesh& mesh, const glm::dvec3& eye,
                                 const std::vector<glm::uvec3>& frontTriangles) {
    // Both lists are in mesh order, so one merge walk finds which triangles are front without a per-triangle flag.
    const glm::vec3* positions = mesh.positions.data();
    std::size_t next = 0;
    std::size_t missed = 0;
    for (const glm::uvec3& triangle : mesh.triangles) {
        if (next < frontTriangles.size() && frontTriangles[next] == triangle) {
            ++next;
            continue;
        }
        missed += isExactFront(positions, triangle, eye) ? 1 : 0;
    }
    if (next != frontTriangles.size()) {
        invalid("countMissedTriangles()", "'frontTriangles' is not a subsequence of mesh '" +
                                              detail::excerptForMessage(mesh.name) + "' triangles in their order");
    }
    return missed;
}

} // namespace inkgraph
