#include "scene/mesh/PolygonTriangulation.h"

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>

namespace inkgraph {

namespace {

/** A corner turns (left or right) when the sine of its turn exceeds this: the cross product of its two edges measured
 *  against their own lengths, so a dense curve's corners and a hair-thin notch in a large polygon count as turns.
 *  Below it (exact reversals and corners on their neighbours' line) a corner is straight: neither convex nor reflex. */
constexpr double kStraightSine = 1e-12;

/** A polygon whose area is below this fraction of its squared extent has none: every triangulation is as good. */
constexpr double kFlatArea = 1e-12;

double cross2(const glm::dvec2& a, const glm::dvec2& b) { return a.x * b.y - a.y * b.x; }

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
    if (!(areaLength > kFlatArea * extentSquared)) {
        fanFromFirst(); // no area, or not finite: no shape to get wrong
        return PolygonShape::Convex;
    }
    const glm::dvec3 normal = areaNormal / areaLength;

    // Convex: every corner turns left about the normal (or goes straight on; turning back is no convex corner) and
    // the turns add up to one full turn; all left turns adding up to two or more is a star that crosses itself.
    bool convex = true;
    double turning = 0.0;
    for (std::size_t i = 0; i < count && convex; ++i) {
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
        const double straight = kStraightSine * glm::length(in) * glm::length(out);
        const double along = glm::dot(in, out);
        convex = turn > straight || (turn >= -straight && along > 0.0);
        if (count > 4) {
            turning += std::atan2(turn, along);
        }
    }
    if (convex) {
        fanFromFirst();
        if (turning > 3.0 * glm::pi<double>()) {
            ++mUnresolved;
            return PolygonShape::Unresolved;
        }
        return PolygonShape::Convex;
    }
    const std::size_t beyondWorkBefore = mBeyondWork;
    const PolygonShape shape = clipEars(corners, normal, kFlatArea * extentSquared, triangles);
    if (mBeyondWork == beyondWorkBefore) {
        ++(shape == PolygonShape::Concave ? mConcave : mUnresolved);
    }
    return shape;
}

PolygonShape PolygonTriangulator::clipEars(std::span<const glm::dvec3> corners, const glm::dvec3& normal, double noArea,
                                           std::vector<glm::uvec3>& triangles) {
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
    /** How far b turns left between a and c, and the size below which that is going straight on. */
    const auto turnsLeft = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
        const glm::dvec2 in = mPlane[b] - mPlane[a];
        const glm::dvec2 out = mPlane[c] - mPlane[b];
        return cross2(in, out) > kStraightSine * glm::length(in) * glm::length(out);
    };
    // Only a corner that is not strictly convex can lie inside an ear of a simple polygon.
    for (std::uint32_t i = 0; i < count; ++i) {
        mMayBlock[i] = !turnsLeft(mPrevious[i], i, mNext[i]);
    }
    std::size_t remaining = count;
    const auto cut = [&](std::uint32_t corner) {
        const std::uint32_t before = mPrevious[corner];
        const std::uint32_t after = mNext[corner];
        triangles.emplace_back(before, corner, after);
        mNext[before] = after;
        mPrevious[after] = before;
        --remaining;
        // Cutting an ear only ever makes its neighbours' corners more convex.
        mMayBlock[before] = mMayBlock[before] && !turnsLeft(mPrevious[before], before, after);
        mMayBlock[after] = mMayBlock[after] && !turnsLeft(before, after, mNext[after]);
    };
    /** A corner written twice in a row, or the tip of a spike that goes out and comes back along itself: a triangle
     *  of no area, which leaves the outline as it was. */
    const auto enclosesNothing = [&](std::uint32_t corner) {
        const glm::dvec2 a = mPlane[mPrevious[corner]], b = mPlane[corner], c = mPlane[mNext[corner]];
        return b == a || b == c || a == c;
    };
    // Those first, everywhere: an ear taken across a spike would reach outside the polygon.
    for (std::uint32_t start = 0; start < count && remaining > 3; ++start) {
        std::uint32_t corner = start;
        while (remaining > 3 && mNext[mPrevious[corner]] == corner && enclosesNothing(corner)) {
            const std::uint32_t before = mPrevious[corner];
            cut(corner);
            corner = enclosesNothing(before) ? before : mNext[before];
        }
    }

    bool outOfWork = false;
    const auto isEar = [&](std::uint32_t corner) {
        if (enclosesNothing(corner)) {
            return true;
        }
        const std::uint32_t before = mPrevious[corner];
        const std::uint32_t after = mNext[corner];
        if (!turnsLeft(before, corner, after)) {
            return false;
        }
        const glm::dvec2 a = mPlane[before], b = mPlane[corner], c = mPlane[after];
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

    std::uint32_t corner = 0;
    while (mNext[mPrevious[corner]] != corner) {
        ++corner; // cut above
    }
    std::size_t sinceLastEar = 0;
    while (remaining > 3 && sinceLastEar < remaining && !outOfWork) {
        if (isEar(corner)) {
            const std::uint32_t after = mNext[corner];
            cut(corner);
            corner = after;
            sinceLastEar = 0;
        } else {
            corner = mNext[corner];
            ++sinceLastEar;
        }
    }
    if (outOfWork) {
        triangles.clear();
        for (std::uint32_t i = 1; i + 1 < count; ++i) {
            triangles.emplace_back(0u, i, i + 1);
        }
        ++mBeyondWork;
        return PolygonShape::Unresolved;
    }
    if (remaining == 3) {
        // The last triangle turned the wrong way round is what is left of a polygon that crosses itself.
        const std::uint32_t before = mPrevious[corner], after = mNext[corner];
        triangles.emplace_back(before, corner, after);
        return cross2(mPlane[corner] - mPlane[before], mPlane[after] - mPlane[corner]) >= -noArea
                   ? PolygonShape::Concave
                   : PolygonShape::Unresolved;
    }
    // No ear among the corners left: the polygon crosses itself (or they lie on one line, which is no shape).
    double area = 0.0;
    std::uint32_t other = corner;
    for (std::size_t i = 0; i < remaining; ++i, other = mNext[other]) {
        area += cross2(mPlane[other], mPlane[mNext[other]]);
    }
    for (std::uint32_t fanned = mNext[corner]; mNext[fanned] != corner; fanned = mNext[fanned]) {
        triangles.emplace_back(corner, fanned, mNext[fanned]);
    }
    return std::abs(area) <= noArea ? PolygonShape::Concave : PolygonShape::Unresolved;
}

void rotateTriangles(std::vector<glm::uvec3>& triangles, std::size_t first, std::size_t cornerCount) {
    const auto rotated = [&](std::uint32_t i) { return std::uint32_t((first + i) % cornerCount); };
    for (glm::uvec3& triangle : triangles)
        triangle = glm::uvec3(rotated(triangle.x), rotated(triangle.y), rotated(triangle.z));
}

} // namespace inkgraph
