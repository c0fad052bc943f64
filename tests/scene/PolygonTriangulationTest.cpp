// The triangles of a file's polygons (scene/mesh/PolygonTriangulation.h): a convex polygon keeps the fan from its
// first corner; a concave one is cut into triangles that all turn the polygon's way and cover exactly its area,
// in any plane and either winding; one that crosses itself is fanned and counted.
#include "scene/mesh/PolygonTriangulation.h"

#include <gtest/gtest.h>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <random>
#include <vector>

namespace inkgraph {
namespace {

std::vector<glm::dvec3> inPlane(const std::vector<glm::dvec2>& points, const glm::dmat4& placement = glm::dmat4(1.0)) {
    std::vector<glm::dvec3> corners;
    for (const glm::dvec2& point : points) {
        corners.emplace_back(placement * glm::dvec4(point, 0.0, 1.0));
    }
    return corners;
}

double shoelaceArea(const std::vector<glm::dvec2>& points) {
    double twice = 0.0;
    for (std::size_t i = 0; i < points.size(); ++i) {
        const glm::dvec2& a = points[i];
        const glm::dvec2& b = points[(i + 1) % points.size()];
        twice += a.x * b.y - a.y * b.x;
    }
    return 0.5 * twice;
}

/** Every triangle turns the polygon's way (its normal along the polygon's, within rounding) and their areas add up
 *  to the polygon's: a triangle outside the polygon or overlapping another breaks one of the two. */
void expectTiling(const std::vector<glm::dvec3>& corners, const std::vector<glm::uvec3>& triangles, double area) {
    ASSERT_EQ(triangles.size(), corners.size() - 2);
    glm::dvec3 polygonNormal(0.0);
    for (std::size_t i = 1; i + 1 < corners.size(); ++i) {
        polygonNormal += glm::cross(corners[i] - corners[0], corners[i + 1] - corners[0]);
    }
    polygonNormal = glm::normalize(polygonNormal);
    double sum = 0.0;
    for (const glm::uvec3& triangle : triangles) {
        for (int k = 0; k < 3; ++k) {
            ASSERT_LT(triangle[k], corners.size());
        }
        const double signedArea = 0.5 * glm::dot(glm::cross(corners[triangle.y] - corners[triangle.x],
                                                            corners[triangle.z] - corners[triangle.x]),
                                                 polygonNormal);
        EXPECT_GE(signedArea, -1e-9 * std::abs(area)) << triangle.x << " " << triangle.y << " " << triangle.z;
        sum += std::abs(signedArea);
    }
    EXPECT_NEAR(sum, std::abs(area), 1e-9 * std::abs(area));
}

/** Cut as a concave polygon, tiling it, in `placement`. */
void expectCutInside(const std::vector<glm::dvec2>& polygon, const glm::dmat4& placement) {
    PolygonTriangulator triangulator;
    std::vector<glm::uvec3> triangles;
    const auto corners = inPlane(polygon, placement);
    EXPECT_EQ(triangulator.triangulate(corners, triangles), PolygonShape::Concave) << polygon.size() << " corners";
    expectTiling(corners, triangles, shoelaceArea(polygon));
}

const glm::dmat4 kTilted = glm::rotate(glm::translate(glm::dmat4(1.0), glm::dvec3(1e3, -2e3, 5.0)), 1.1,
                                       glm::normalize(glm::dvec3(0.3, -0.8, 0.5)));

TEST(PolygonTriangulation, ATriangleAndAConvexPolygonKeepTheFanFromTheFirstCorner) {
    PolygonTriangulator triangulator;
    std::vector<glm::uvec3> triangles;
    EXPECT_EQ(triangulator.triangulate(inPlane({{0, 0}, {1, 0}, {0, 1}}), triangles), PolygonShape::Convex);
    EXPECT_EQ(triangles, (std::vector<glm::uvec3>{{0, 1, 2}}));
    std::vector<glm::dvec2> hexagon;
    for (int i = 0; i < 6; ++i) {
        hexagon.emplace_back(std::cos(i * glm::pi<double>() / 3), std::sin(i * glm::pi<double>() / 3));
    }
    EXPECT_EQ(triangulator.triangulate(inPlane(hexagon, kTilted), triangles), PolygonShape::Convex);
    EXPECT_EQ(triangles, (std::vector<glm::uvec3>{{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}}));
    // A corner on the straight line between its neighbours leaves the polygon convex.
    EXPECT_EQ(triangulator.triangulate(inPlane({{0, 0}, {1, 0}, {2, 0}, {2, 2}, {0, 2}}), triangles),
              PolygonShape::Convex);
    EXPECT_EQ(triangulator.concavePolygons(), 0u);
    EXPECT_EQ(triangulator.unresolvedPolygons(), 0u);
}

TEST(PolygonTriangulation, AConcaveQuadIsCutAlongItsInsideDiagonal) {
    // A dart whose corner 2 is reflex: the fan's diagonal 0-2 runs outside it.
    const std::vector<glm::dvec2> dart{{0, 0}, {2, 1}, {0.5, 0}, {2, -1}};
    // Clockwise as written; either winding is cut the same way.
    PolygonTriangulator triangulator;
    std::vector<glm::uvec3> triangles;
    const auto corners = inPlane(dart);
    EXPECT_EQ(triangulator.triangulate(corners, triangles), PolygonShape::Concave);
    expectTiling(corners, triangles, shoelaceArea(dart));
    for (const glm::uvec3& triangle : triangles) {
        EXPECT_TRUE(triangle.x == 2 || triangle.y == 2 || triangle.z == 2) << "each triangle holds the reflex corner";
    }
    EXPECT_EQ(triangulator.concavePolygons(), 1u);
}

TEST(PolygonTriangulation, AnLShapeAStarAndAComb) {
    const std::vector<glm::dvec2> lShape{{0, 0}, {3, 0}, {3, 1}, {1, 1}, {1, 3}, {0, 3}};
    std::vector<glm::dvec2> star;
    for (int i = 0; i < 10; ++i) {
        const double radius = i % 2 == 0 ? 1.0 : 0.38;
        star.emplace_back(radius * std::cos(i * glm::pi<double>() / 5), radius * std::sin(i * glm::pi<double>() / 5));
    }
    std::vector<glm::dvec2> comb{{0, 0}};
    for (int tooth = 0; tooth < 200; ++tooth) {
        comb.insert(comb.end(), {{tooth + 0.0, 1.0}, {tooth + 0.5, 3.0}, {tooth + 1.0, 1.0}});
    }
    comb.emplace_back(200.0, 0.0);
    std::reverse(comb.begin(), comb.end()); // clockwise
    // With corners on the L's straight edges, as CAD exports write them.
    const std::vector<glm::dvec2> lWithMidpoints{{0, 0}, {1.5, 0}, {3, 0}, {3, 1}, {2, 1},
                                                 {1, 1}, {1, 2},   {1, 3}, {0, 3}, {0, 1.5}};
    for (const std::vector<glm::dvec2>* polygon :
         std::initializer_list<const std::vector<glm::dvec2>*>{&lShape, &star, &comb, &lWithMidpoints}) {
        for (const glm::dmat4& placement : {glm::dmat4(1.0), kTilted}) {
            expectCutInside(*polygon, placement);
        }
    }
}

TEST(PolygonTriangulation, AHoleJoinedByABridgeIsLeftOpen) {
    // A square with a square hole, joined by a cut from (0,0) to (1,1) and back: how hole-less formats write one.
    const std::vector<glm::dvec2> keyhole{{0, 0}, {4, 0}, {4, 4}, {0, 4}, {0, 0},
                                          {1, 1}, {1, 3}, {3, 3}, {3, 1}, {1, 1}};
    EXPECT_DOUBLE_EQ(shoelaceArea(keyhole), 16.0 - 4.0);
    expectCutInside(keyhole, kTilted);
}

TEST(PolygonTriangulation, RandomSimplePolygonsInAnyPlane) {
    std::mt19937 random(38);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int trial = 0; trial < 300; ++trial) {
        // Star-shaped about the origin, hence simple: increasing angles, random radii.
        const int count = 4 + int(unit(random) * 60);
        std::vector<glm::dvec2> polygon;
        for (int i = 0; i < count; ++i) {
            const double angle = (i + 0.8 * unit(random)) * 2.0 * glm::pi<double>() / count;
            const double radius = 0.2 + unit(random);
            polygon.emplace_back(radius * std::cos(angle), radius * std::sin(angle));
        }
        if (trial % 2 == 1) {
            std::reverse(polygon.begin(), polygon.end());
        }
        const glm::dmat4 placement = glm::rotate(glm::dmat4(1.0), 6.0 * unit(random),
                                                 glm::normalize(glm::dvec3(unit(random) - 0.5, unit(random), 0.1)));
        PolygonTriangulator triangulator;
        std::vector<glm::uvec3> triangles;
        const auto corners = inPlane(polygon, placement);
        EXPECT_NE(triangulator.triangulate(corners, triangles), PolygonShape::Unresolved) << trial;
        expectTiling(corners, triangles, shoelaceArea(polygon));
    }
}

TEST(PolygonTriangulation, DenseCurvesAndThinFeaturesOfALargePolygonTurn) {
    // A corner is straight by the sine of its own turn, not by the polygon's size: a crescent of 3,000 corners per
    // arc, and a ring of 3,000 corners per circle whose hole is joined by a bridge, were fanned whole as convex.
    constexpr int kArc = 3000;
    std::vector<glm::dvec2> crescent;
    for (int i = 0; i < kArc; ++i) {
        const double angle = glm::radians(-150.0 + 300.0 * i / (kArc - 1));
        crescent.emplace_back(std::cos(angle), std::sin(angle));
    }
    const glm::dvec2 top = crescent.front(), bottom = crescent.back();
    for (int i = 1; i < kArc - 1; ++i) {
        crescent.emplace_back(bottom.x + 0.6 * std::sin(glm::pi<double>() * i / (kArc - 1)),
                              bottom.y + (top.y - bottom.y) * i / (kArc - 1));
    }
    std::vector<glm::dvec2> ring;
    for (int i = 0; i <= kArc; ++i) {
        const double angle = 2.0 * glm::pi<double>() * i / kArc;
        ring.emplace_back(std::cos(angle), std::sin(angle));
    }
    for (int i = 0; i <= kArc; ++i) { // across the bridge, round the hole clockwise, and back over the bridge
        const double angle = -2.0 * glm::pi<double>() * i / kArc;
        ring.emplace_back(0.5 * std::cos(angle), 0.5 * std::sin(angle));
    }
    // A notch a millionth wide in a rectangle a thousand long.
    const std::vector<glm::dvec2> notched{{0, 0},     {1000, 0},       {1000, 1}, {500.000001, 1},
                                          {500, 0.5}, {499.999999, 1}, {0, 1}};
    for (const std::vector<glm::dvec2>* polygon :
         std::initializer_list<const std::vector<glm::dvec2>*>{&crescent, &ring, &notched}) {
        expectCutInside(*polygon, kTilted);
    }
}

TEST(PolygonTriangulation, SpikesAndSlitsOfNoWidthEncloseNothing) {
    // A spike out to x = 3 and back along itself: an ear taken across it drew a wedge outside the square. A slit
    // cut in and back out is the same thing turned inward, taken for a polygon that crosses itself.
    const std::vector<glm::dvec2> spike{{0, 0}, {1, 0}, {1, 0.5}, {3, 0.5}, {1, 0.5}, {1, 1}, {0, 1}};
    const std::vector<glm::dvec2> spikeFirst{{3, 0.5}, {1, 0.5}, {1, 1}, {0, 1}, {0, 0}, {1, 0}, {1, 0.5}};
    const std::vector<glm::dvec2> slit{{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 0.3}, {1, 1}, {0, 1}};
    for (const std::vector<glm::dvec2>* polygon :
         std::initializer_list<const std::vector<glm::dvec2>*>{&spike, &spikeFirst, &slit}) {
        expectCutInside(*polygon, kTilted);
    }
}

TEST(PolygonTriangulation, AWarpedConcavePolygonIsCutInItsAveragePlane) {
    std::vector<glm::dvec3> corners = inPlane({{0, 0}, {3, 0}, {3, 1}, {1, 1}, {1, 3}, {0, 3}});
    for (std::size_t i = 0; i < corners.size(); ++i) {
        corners[i].z = i % 2 == 0 ? 0.05 : -0.05;
    }
    PolygonTriangulator triangulator;
    std::vector<glm::uvec3> triangles;
    EXPECT_EQ(triangulator.triangulate(corners, triangles), PolygonShape::Concave);
    ASSERT_EQ(triangles.size(), 4u);
    for (const glm::uvec3& triangle : triangles) {
        const glm::dvec3 normal =
            glm::cross(corners[triangle.y] - corners[triangle.x], corners[triangle.z] - corners[triangle.x]);
        EXPECT_GT(normal.z, 0.0);
    }
}

TEST(PolygonTriangulation, APolygonThatCrossesItselfIsFannedAndCounted) {
    std::vector<glm::dvec2> pentagram;
    for (int i = 0; i < 5; ++i) {
        pentagram.emplace_back(std::cos(i * 4 * glm::pi<double>() / 5), std::sin(i * 4 * glm::pi<double>() / 5));
    }
    PolygonTriangulator triangulator;
    std::vector<glm::uvec3> triangles;
    EXPECT_EQ(triangulator.triangulate(inPlane(pentagram), triangles), PolygonShape::Unresolved);
    EXPECT_EQ(triangles, (std::vector<glm::uvec3>{{0, 1, 2}, {0, 2, 3}, {0, 3, 4}}));
    // A figure eight whose lobes differ: ear clipping runs to its end, and the last triangle turns the wrong way.
    const std::vector<glm::dvec2> figureEight{{0, 0}, {1, 0}, {1, 1}, {2, 1}, {2, 2}, {1.5, 2}, {1.5, 0.5}, {0, 0.5}};
    EXPECT_EQ(triangulator.triangulate(inPlane(figureEight), triangles), PolygonShape::Unresolved);
    EXPECT_EQ(triangles.size(), figureEight.size() - 2);
    // A bow tie's lobes cancel: no area, nothing to get wrong.
    EXPECT_EQ(triangulator.triangulate(inPlane({{0, 0}, {1, 1}, {1, 0}, {0, 1}}), triangles), PolygonShape::Convex);
    EXPECT_EQ(triangulator.unresolvedPolygons(), 2u);
    EXPECT_EQ(triangulator.polygonsBeyondWork(), 0u);
    EXPECT_EQ(triangulator.concavePolygons(), 0u);
}

TEST(PolygonTriangulation, TheWorkOfAFileIsBoundedThenPolygonsAreFanned) {
    std::vector<glm::dvec2> comb{{0, 0}};
    for (int tooth = 0; tooth < 100; ++tooth) {
        comb.insert(comb.end(), {{tooth + 0.0, 1.0}, {tooth + 0.5, 3.0}, {tooth + 1.0, 1.0}});
    }
    comb.emplace_back(100.0, 0.0);
    PolygonTriangulator triangulator(1000);
    std::vector<glm::uvec3> triangles;
    EXPECT_EQ(triangulator.triangulate(inPlane(comb), triangles), PolygonShape::Unresolved);
    ASSERT_EQ(triangles.size(), comb.size() - 2);
    EXPECT_EQ(triangles.front(), glm::uvec3(0, 1, 2));
    EXPECT_EQ(triangles.back(), glm::uvec3(0, comb.size() - 2, comb.size() - 1));
    // The budget is spent: the next concave polygon is fanned at once.
    EXPECT_EQ(triangulator.triangulate(inPlane({{0, 0}, {2, 1}, {0.5, 0}, {2, -1}}), triangles),
              PolygonShape::Unresolved);
    EXPECT_EQ(triangulator.unresolvedPolygons(), 2u);
    EXPECT_EQ(triangulator.polygonsBeyondWork(), 2u);
}

} // namespace
} // namespace inkgraph
