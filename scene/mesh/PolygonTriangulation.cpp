#include "scene/mesh/PolygonTriangulation.h"

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>

namespace inkgraph {

namespace {

/** A turn (the cross product of two edges, area units) below this fraction of the polygon's squared extent is
 *  straight: a corner that rounding put a hair off its neighbours' line is neither convex nor reflex. */
constexpr double kStraightTurn = 1e-9;

double cross2(const glm::dvec2& a, const glm::dvec2& b) { return a.x * b.y - a.y * b.x; }

void fan(std::size_t first, std::span<const std::uint32_t> next, std::size_t count,
         std::vector<glm::uvec3>& triangles) {
    std::uint32_t corner = next[first];
    for (std::size_t t = 0; t + 2 < count; ++t) {
        triangles.emplace_back(std::uint32_t(first), corner, next[corner]);
        corner = next[corner];
    }
}

} // namespace

PolygonShape PolygonTriangulator::triangulate(std::span<const glm::dvec3> corners, std::vector<glm::uvec3>& triangles) {
    triangles.clear();
    const std::size_t count = corners.size();
    const auto fanFromFirst = [&] {
        for (std::size_t i = 1; i + 1 < count; ++i) {
            triangles.emplace_back(0u, std::uint32_t(i), std::uint32_t(i + 1));
        }
    };
    if (count <= 3) {
        fanFromFirst();
        return PolygonShape::Convex;
    }
    // Newell's normal, about the first corner: twice the polygon's vector area.
    const glm::dvec3 origin = corners[0];
    glm::dvec3 areaNormal(0.0);
    double extentSquared = 0.0;
    for (std::size_t i = 1; i + 1 < count; ++i) {
        areaNormal += glm::cross(corners[i] - origin, corners[i + 1] - origin);
    }
    for (const glm::dvec3& corner : corners) {
        extentSquared = std::max(extentSquared, glm::dot(corner - origin, corner - origin));
    }
    const double areaLength = glm::length(areaNormal);
    const double tolerance = kStraightTurn * extentSquared;
    if (!(areaLength > tolerance)) {
        fanFromFirst(); // no area, or not finite: no shape to get wrong
        return PolygonShape::Convex;
    }
    const glm::dvec3 normal = areaNormal / areaLength;

    // Convex: every corner turns left about the normal (or goes straight) and the turns add up to one full turn; all
    // left turns adding up to two or more is a star that crosses itself.
    bool allLeft = true;
    double turning = 0.0;
    for (std::size_t i = 0; i < count && allLeft; ++i) {
        // A corner written twice in a row turns once, at its last copy, between the corners either side of it.
        std::size_t after = (i + 1) % count;
        if (corners[after] == corners[i]) {
            continue;
        }
        std::size_t before = (i + count - 1) % count;
        while (before != i && corners[before] == corners[i]) {
            before = (before + count - 1) % count;
        }
        const glm::dvec3 in = corners[i] - corners[before];
        const glm::dvec3 out = corners[after] - corners[i];
        const double turn = glm::dot(glm::cross(in, out), normal);
        allLeft = turn >= -tolerance;
        if (count > 4) {
            turning += std::atan2(turn, glm::dot(in, out));
        }
    }
    if (allLeft) {
        fanFromFirst();
        if (turning > 3.0 * glm::pi<double>()) {
            ++mUnresolved;
            return PolygonShape::Unresolved;
        }
        return PolygonShape::Convex;
    }
    const PolygonShape shape = clipEars(corners, normal, tolerance, triangles);
    ++(shape == PolygonShape::Concave ? mConcave : mUnresolved);
    return shape;
}

PolygonShape PolygonTriangulator::clipEars(std::span<const glm::dvec3> corners, const glm::dvec3& normal,
                                           double tolerance, std::vector<glm::uvec3>& triangles) {
    const std::size_t count = corners.size();
    // The plane's axes (u, v) with u x v = normal, so the polygon turns counter-clockwise in them.
    const glm::dvec3 leastAligned = std::abs(normal.x) <= std::abs(normal.y) && std::abs(normal.x) <= std::abs(normal.z)
                                        ? glm::dvec3(1, 0, 0)
                                    : std::abs(normal.y) <= std::abs(normal.z) ? glm::dvec3(0, 1, 0)
                                                                               : glm::dvec3(0, 0, 1);
    const glm::dvec3 u = glm::normalize(glm::cross(normal, leastAligned));
    const glm::dvec3 v = glm::cross(normal, u);
    mPlane.resize(count);
    mNext.resize(count);
    mPrevious.resize(count);
    mMayBlock.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
        const glm::dvec3 offset = corners[i] - corners[0];
        mPlane[i] = glm::dvec2(glm::dot(offset, u), glm::dot(offset, v));
        mNext[i] = std::uint32_t((i + 1) % count);
        mPrevious[i] = std::uint32_t((i + count - 1) % count);
    }
    const auto turn = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
        return cross2(mPlane[b] - mPlane[a], mPlane[c] - mPlane[b]);
    };
    // Only a corner that is not strictly convex can lie inside an ear of a simple polygon.
    for (std::uint32_t i = 0; i < count; ++i) {
        mMayBlock[i] = turn(mPrevious[i], i, mNext[i]) <= tolerance;
    }
    bool outOfWork = false;
    const auto isEar = [&](std::uint32_t corner) {
        const std::uint32_t before = mPrevious[corner];
        const std::uint32_t after = mNext[corner];
        const glm::dvec2 a = mPlane[before], b = mPlane[corner], c = mPlane[after];
        if (b == a || b == c) {
            return true; // a corner written twice in a row: cut as a triangle of no area, the shape unchanged
        }
        if (turn(before, corner, after) <= tolerance) {
            return false;
        }
        for (std::uint32_t other = mNext[after]; other != before; other = mNext[other]) {
            if (mWorkLeft == 0) {
                outOfWork = true;
                return false;
            }
            --mWorkLeft;
            const glm::dvec2 q = mPlane[other];
            // A copy of a triangle's corner (where a bridge to a hole doubles back) touches the ear, not inside it.
            if (!mMayBlock[other] || q == a || q == b || q == c) {
                continue;
            }
            if (cross2(b - a, q - a) >= 0.0 && cross2(c - b, q - b) >= 0.0 && cross2(a - c, q - c) >= 0.0) {
                return false;
            }
        }
        return true;
    };

    std::size_t remaining = count;
    std::uint32_t corner = 0;
    std::size_t sinceLastEar = 0;
    while (remaining > 3 && sinceLastEar < remaining && !outOfWork) {
        if (isEar(corner)) {
            const std::uint32_t before = mPrevious[corner];
            const std::uint32_t after = mNext[corner];
            triangles.emplace_back(before, corner, after);
            mNext[before] = after;
            mPrevious[after] = before;
            --remaining;
            // Cutting an ear only ever makes its neighbours' corners more convex.
            mMayBlock[before] = mMayBlock[before] && turn(mPrevious[before], before, after) <= tolerance;
            mMayBlock[after] = mMayBlock[after] && turn(before, after, mNext[after]) <= tolerance;
            corner = after;
            sinceLastEar = 0;
        } else {
            corner = mNext[corner];
            ++sinceLastEar;
        }
    }
    if (outOfWork) {
        triangles.clear();
        for (std::uint32_t i = 0; i < count; ++i) {
            mNext[i] = std::uint32_t((i + 1) % count);
        }
        fan(0, mNext, count, triangles);
        return PolygonShape::Unresolved;
    }
    if (remaining == 3) {
        triangles.emplace_back(mPrevious[corner], corner, mNext[corner]);
        return PolygonShape::Concave;
    }
    // No ear among the corners left: the polygon crosses itself (or they lie on one line, which is no shape).
    double area = 0.0;
    std::uint32_t other = corner;
    for (std::size_t i = 0; i < remaining; ++i, other = mNext[other]) {
        area += cross2(mPlane[other], mPlane[mNext[other]]);
    }
    fan(corner, mNext, remaining, triangles);
    return std::abs(area) <= tolerance ? PolygonShape::Concave : PolygonShape::Unresolved;
}

} // namespace inkgraph
