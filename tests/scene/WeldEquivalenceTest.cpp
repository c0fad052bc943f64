// weldVertices() (its lookups made ahead and prefetched since issue 20) against the weld as first written
// (WeldReference.h): the same kept vertices and the same map on random, jittered, clustered and tied point sets,
// with normals and attribute classes.
#include "WeldReference.h"

#include "scene/mesh/MeshOps.h"
#include "scene/Scene.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>
#include <vector>

namespace inkgraph {
namespace {

void expectSameWeld(std::span<const glm::vec3> positions, std::span<const glm::vec3> normals, double distance,
                    std::span<const std::uint32_t> classes, const std::string& what) {
    const WeldMap expected = test::referenceWeldVertices(positions, normals, distance, classes);
    const WeldMap actual = weldVertices(positions, normals, distance, classes);
    EXPECT_EQ(actual.kept, expected.kept) << what << ", distance " << distance;
    EXPECT_EQ(actual.outputOf, expected.outputOf) << what << ", distance " << distance;
}

std::vector<glm::vec3> uniformPoints(std::size_t count, glm::vec3 low, glm::vec3 high, unsigned seed) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<glm::vec3> points(count);
    for (glm::vec3& p : points) p = low + (high - low) * glm::vec3(unit(random), unit(random), unit(random));
    return points;
}

TEST(SceneWeldEquivalence, RandomPointsAtEveryDistance) {
    const std::vector<glm::vec3> points = uniformPoints(20000, glm::vec3(-1.0f), glm::vec3(1.0f), 1);
    for (double distance : {0.0, 1e-6, 1e-3, 0.01, 0.03, 0.08, 0.3})
        expectSameWeld(points, {}, distance, {}, "uniform points");
}

TEST(SceneWeldEquivalence, JitteredCopiesInShuffledOrder) {
    // Lattice points copied 1 to 6 times, each copy moved by up to 0.7 x the distance: some copies merge, some are
    // just out of reach, many straddle cell borders.
    for (double distance : {1e-4, 0.02, 0.2}) {
        std::mt19937 random(7);
        std::uniform_real_distribution<double> jitter(-0.7 * distance, 0.7 * distance);
        std::uniform_int_distribution<int> copies(1, 6);
        std::vector<glm::vec3> points;
        for (int x = 0; x < 18; ++x)
            for (int y = 0; y < 18; ++y)
                for (int z = 0; z < 6; ++z) {
                    const glm::dvec3 base = glm::dvec3(x, y, z) * (3.0 * distance);
                    for (int copy = copies(random); copy > 0; --copy)
                        points.emplace_back(base + glm::dvec3(jitter(random), jitter(random), jitter(random)));
                }
        std::shuffle(points.begin(), points.end(), random);
        expectSameWeld(points, {}, distance, {}, "jittered copies");
        // Far from the origin: cell coordinates stay small, but the positions round differently.
        for (glm::vec3& p : points) p += glm::vec3(1000.0f, -3000.0f, 512.0f);
        expectSameWeld(points, {}, distance, {}, "jittered copies, offset");
    }
}

TEST(SceneWeldEquivalence, ExactTiesGoToTheSameRepresentative) {
    // Lattice points 1 apart stay apart at distance 0.6; the midpoints between them are 0.5 from two (edge
    // midpoints), four (face centres) or eight (cube centres) representatives at once, in different cells.
    std::vector<glm::vec3> points;
    for (int x = 0; x <= 8; ++x)
        for (int y = 0; y <= 8; ++y)
            for (int z = 0; z <= 4; ++z) points.emplace_back(float(x), float(y), float(z));
    const std::size_t lattice = points.size();
    for (int x = 0; x < 16; ++x)
        for (int y = 0; y < 16; ++y)
            for (int z = 0; z < 8; ++z)
                if ((x | y | z) & 1) points.emplace_back(0.5f * float(x), 0.5f * float(y), 0.5f * float(z));
    expectSameWeld(points, {}, 0.6, {}, "lattice then midpoints");
    expectSameWeld(points, {}, 0.87, {}, "lattice then midpoints");
    std::mt19937 random(11);
    std::shuffle(points.begin(), points.end(), random);
    expectSameWeld(points, {}, 0.6, {}, "shuffled lattice and midpoints");
    std::rotate(points.begin(), points.begin() + std::ptrdiff_t(lattice / 2), points.end());
    expectSameWeld(points, {}, 0.87, {}, "rotated lattice and midpoints");
}

TEST(SceneWeldEquivalence, NormalsAndClassesDecideWhoMerges) {
    std::mt19937 random(3);
    std::vector<glm::vec3> points;
    std::vector<glm::vec3> normals;
    std::vector<std::uint32_t> classes;
    const glm::vec3 directions[3] = {{0, 0, 1}, {1, 0, 0}, glm::normalize(glm::vec3(1, 1, 0))};
    std::uniform_int_distribution<int> pick(0, 2);
    // Normal noise around the 1e-3 chord that decides a match, so some copies match and some do not.
    std::uniform_real_distribution<float> noise(-8e-4f, 8e-4f);
    std::uniform_real_distribution<float> jitter(-4e-3f, 4e-3f);
    for (int x = 0; x < 30; ++x)
        for (int y = 0; y < 30; ++y)
            for (int copy = 0; copy < 4; ++copy) {
                points.emplace_back(0.01f * float(x) + jitter(random), 0.01f * float(y) + jitter(random), 0.0f);
                normals.push_back(
                    glm::normalize(directions[pick(random)] + glm::vec3(noise(random), noise(random), noise(random))));
                classes.push_back(std::uint32_t(pick(random)));
            }
    for (double distance : {0.0, 2e-3, 6e-3}) {
        expectSameWeld(points, normals, distance, {}, "with normals");
        expectSameWeld(points, {}, distance, classes, "with classes");
        expectSameWeld(points, normals, distance, classes, "with normals and classes");
    }
}

TEST(SceneWeldEquivalence, CoincidentClustersAndDegenerateBoxes) {
    // 3000 copies of one point (one cell holds them all), a line of points (a box flat in two axes), one point.
    std::vector<glm::vec3> cluster(3000, glm::vec3(0.25f, -4.0f, 9.0f));
    cluster.emplace_back(0.25f, -4.0f, 9.001f);
    for (double distance : {0.0, 1e-6, 0.01}) expectSameWeld(cluster, {}, distance, {}, "coincident cluster");
    std::vector<glm::vec3> line;
    for (int i = 0; i < 5000; ++i) line.emplace_back(float(i % 1000) * 1e-3f, 2.0f, 2.0f);
    for (double distance : {0.0, 4e-4, 1e-3}) expectSameWeld(line, {}, distance, {}, "points on a line");
    const std::vector<glm::vec3> one = {glm::vec3(1.0f, 2.0f, 3.0f)};
    expectSameWeld(one, {}, 0.0, {}, "one point");
    expectSameWeld({}, {}, 1.0, {}, "no points");
}

TEST(SceneWeldEquivalence, LargeSoup) {
    // A bumpy sheet as a triangle soup, 6 copies of each inner point, welded at a loader's tolerance and at a loose
    // one, and points enough that the lookups made ahead wrap around many times.
    std::vector<glm::vec3> soup;
    const auto height = [](int x, int y) { return 0.01f * float((x * 7 + y * 13) % 11); };
    for (int y = 0; y < 130; ++y)
        for (int x = 0; x < 130; ++x) {
            const glm::vec3 a(x, y, height(x, y)), b(x + 1, y, height(x + 1, y));
            const glm::vec3 c(x + 1, y + 1, height(x + 1, y + 1)), d(x, y + 1, height(x, y + 1));
            soup.insert(soup.end(), {a, b, c, a, c, d});
        }
    const double diagonal = computeBoundingBox(soup).diagonal();
    expectSameWeld(soup, {}, LoadOptions{}.weldTolerance * diagonal, {}, "sheet soup");
    expectSameWeld(soup, {}, 0.45, {}, "sheet soup, loose");
    const std::vector<glm::vec3> scattered = uniformPoints(150000, glm::vec3(0.0f), glm::vec3(1.0f, 2.0f, 0.5f), 5);
    expectSameWeld(scattered, {}, 2e-3, {}, "150k uniform points");
}

} // namespace
} // namespace inkgraph
