// Hidden lines of issue 36 (--hidden-lines, --hidden-dash; docs/lines.md "Hidden lines") from the real `inkgraph`
// executable: two interpenetrating spheres' mesh silhouettes against their exact perspective silhouette circles, each
// sample judged hidden or visible by analytic ray casting; a cube's hidden creases dashed in the picture and the SVG;
// the flags in a style file; bad values refused. Needs a GL context (llvmpipe in CI); each case renders at 256x256 or
// less.
#include "render/ImageFiles.h"
#include "tests/app/CliTestSupport.h"

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace inkgraph {
namespace {

using test::Cli;
using test::CliRun;
using test::readText;
namespace fs = std::filesystem;

constexpr double kPi = 3.14159265358979323846;

/** A UV sphere (latitude x longitude quads as two triangles) appended to OBJ `vertices` and `faces`. */
void appendSphere(std::ostringstream& vertices, std::ostringstream& faces, int& vertexCount, glm::dvec3 centre,
                  double radius) {
    constexpr int kRings = 48, kSegments = 96;
    const int first = vertexCount + 1; // OBJ indices start at 1
    for (int ring = 0; ring <= kRings; ++ring)
        for (int segment = 0; segment < kSegments; ++segment) {
            const double theta = kPi * ring / kRings, phi = 2.0 * kPi * segment / kSegments;
            const glm::dvec3 p = centre + radius * glm::dvec3(std::sin(theta) * std::cos(phi), std::cos(theta),
                                                              std::sin(theta) * std::sin(phi));
            vertices << "v " << p.x << ' ' << p.y << ' ' << p.z << '\n';
            ++vertexCount;
        }
    for (int ring = 0; ring < kRings; ++ring)
        for (int segment = 0; segment < kSegments; ++segment) {
            const int a = first + ring * kSegments + segment, b = first + ring * kSegments + (segment + 1) % kSegments;
            const int c = a + kSegments, d = b + kSegments;
            faces << "f " << a << ' ' << c << ' ' << b << "\nf " << b << ' ' << c << ' ' << d << '\n';
        }
}

/** The camera of a render: --eye, --target, --fov (up 0,1,0), a square picture of `size` pixels. */
struct View {
    glm::dvec3 eye;
    glm::dvec3 target;
    double fovYDegrees;
    int size;
    std::string flags() const {
        std::ostringstream text;
        text << "--eye " << eye.x << ',' << eye.y << ',' << eye.z << " --target " << target.x << ',' << target.y << ','
             << target.z << " --fov " << fovYDegrees << " --size " << size << 'x' << size;
        return text.str();
    }
    /** A world point in picture pixels: origin at the top-left corner, pixel centres at col + 0.5, row + 0.5. */
    glm::dvec2 project(glm::dvec3 point) const {
        const glm::dmat4 view = glm::lookAt(eye, target, glm::dvec3(0.0, 1.0, 0.0));
        const glm::dmat4 clip = glm::perspective(fovYDegrees * kPi / 180.0, 1.0, 0.1, 100.0);
        const glm::dvec4 p = clip * view * glm::dvec4(point, 1.0);
        return {(p.x / p.w + 1.0) * 0.5 * size, (1.0 - p.y / p.w) * 0.5 * size};
    }
};

/** Whether the sphere (centre, radius) hides `point` from `eye`: the point lies inside it, or the segment from the eye
 *  to the point enters it before the point. */
bool sphereHides(glm::dvec3 eye, glm::dvec3 point, glm::dvec3 centre, double radius) {
    if (glm::length(point - centre) < radius) return true;
    const glm::dvec3 ray = point - eye, toEye = eye - centre;
    const double a = glm::dot(ray, ray), b = 2.0 * glm::dot(ray, toEye), c = glm::dot(toEye, toEye) - radius * radius;
    const double discriminant = b * b - 4.0 * a * c;
    if (discriminant <= 0.0) return false;
    const double entry = (-b - std::sqrt(discriminant)) / (2.0 * a);
    return entry > 0.0 && entry < 1.0;
}

/** A sample of the exact silhouette curves, in picture pixels. */
struct TruthSample {
    glm::dvec2 pixel;
    bool hidden = false;
};

/** Whether `mask` (CV_8UC1) has a pixel >= `threshold` whose centre lies within `radius` of `point`. */
bool hasPixelNear(const cv::Mat& mask, glm::dvec2 point, double radius, int threshold = 1) {
    for (int row = std::max(0, int(point.y - radius - 1)); row <= std::min(mask.rows - 1, int(point.y + radius + 1));
         ++row)
        for (int col = std::max(0, int(point.x - radius - 1));
             col <= std::min(mask.cols - 1, int(point.x + radius + 1)); ++col)
            if (mask.at<uchar>(row, col) >= threshold &&
                glm::length(glm::dvec2(col + 0.5, row + 0.5) - point) <= radius)
                return true;
    return false;
}

/** Precision, recall and F1 of a one-pixel mask against truth samples (those with `hidden` == `which`) at `radius`. */
struct Score {
    double precision = 0.0, recall = 0.0;
    double f1() const { return precision + recall > 0.0 ? 2.0 * precision * recall / (precision + recall) : 0.0; }
};
Score scoreAgainst(const cv::Mat& mask, const std::vector<TruthSample>& truth, bool which, double radius) {
    std::vector<glm::dvec2> wanted;
    for (const TruthSample& sample : truth)
        if (sample.hidden == which) wanted.push_back(sample.pixel);
    int pixels = 0, near = 0;
    for (int row = 0; row < mask.rows; ++row)
        for (int col = 0; col < mask.cols; ++col) {
            if (mask.at<uchar>(row, col) == 0) continue;
            ++pixels;
            const glm::dvec2 centre(col + 0.5, row + 0.5);
            for (const glm::dvec2& point : wanted)
                if (glm::length(point - centre) <= radius) {
                    ++near;
                    break;
                }
        }
    int found = 0;
    for (const glm::dvec2& point : wanted) found += hasPixelNear(mask, point, radius);
    Score score;
    score.precision = pixels == 0 ? 0.0 : double(near) / pixels;
    score.recall = wanted.empty() ? 0.0 : double(found) / double(wanted.size());
    return score;
}

class HiddenLines : public Cli {};

TEST_F(HiddenLines, TwoSpheresHiddenSilhouettesAreInTheHiddenLayerAndNotInTheVisibleOne) {
    // Two spheres of radius 0.8 at x = -0.45 and x = +0.45 cross each other; seen obliquely from the right, above and
    // in front, the right sphere hides part of the left one's silhouette circle and the left one's inner part of the
    // right one's.
    const double radius = 0.8;
    const std::vector<glm::dvec3> centres = {{-0.45, 0.0, 0.0}, {0.45, 0.0, 0.0}};
    std::ostringstream vertices, faces;
    int vertexCount = 0;
    for (const glm::dvec3& centre : centres) appendSphere(vertices, faces, vertexCount, centre, radius);
    std::ofstream(directory / "spheres.obj") << vertices.str() << faces.str();
    const View view{{2.2, 1.1, 3.3}, {0.0, 0.0, 0.0}, 40.0, 256};
    const CliRun result = run("render spheres.obj " + view.flags() +
                              " --shading none --lines mesh-silhouette --hidden-lines mesh-silhouette --hidden-dash "
                              "none --dump dump --stats stats.json -o out.png -q");
    ASSERT_EQ(result.exitCode, 0) << result.err;

    // Each sphere's exact silhouette under perspective: for d = |E - C|, the circle of centre C + (R^2 / d^2)(E - C)
    // and radius R sqrt(d^2 - R^2) / d in the plane normal to E - C; a sample is hidden when the other sphere hides it.
    std::vector<TruthSample> truth;
    constexpr int kSamples = 3000;
    for (std::size_t index = 0; index < centres.size(); ++index) {
        const glm::dvec3 toEye = view.eye - centres[index];
        const double d = glm::length(toEye);
        const glm::dvec3 normal = toEye / d;
        const glm::dvec3 centre = centres[index] + (radius * radius / (d * d)) * toEye;
        const double circleRadius = radius * std::sqrt(d * d - radius * radius) / d;
        const glm::dvec3 u = glm::normalize(glm::cross(normal, glm::dvec3(0.0, 1.0, 0.0)));
        const glm::dvec3 v = glm::cross(normal, u);
        for (int sample = 0; sample < kSamples; ++sample) {
            const double angle = 2.0 * kPi * sample / kSamples;
            const glm::dvec3 point = centre + circleRadius * (std::cos(angle) * u + std::sin(angle) * v);
            TruthSample truthSample;
            truthSample.pixel = view.project(point);
            truthSample.hidden = sphereHides(view.eye, point, centres[1 - index], radius);
            truth.push_back(truthSample);
        }
    }
    int hiddenSamples = 0;
    for (const TruthSample& sample : truth) hiddenSamples += sample.hidden;
    ASSERT_GT(hiddenSamples, kSamples / 4) << "the view must hide a good part of the circles";
    ASSERT_LT(hiddenSamples, kSamples * 3 / 2);

    const cv::Mat hiddenSkeleton = readImage(directory / "dump" / "skeleton-hidden-mesh-silhouette.png");
    const cv::Mat visibleSkeleton = readImage(directory / "dump" / "skeleton-mesh-silhouette.png");
    const cv::Mat hiddenLayer = readImage(directory / "dump" / "lines-hidden-mesh-silhouette.png");
    const cv::Mat visibleLayer = readImage(directory / "dump" / "lines-mesh-silhouette.png");
    for (const cv::Mat* image : {&hiddenSkeleton, &visibleSkeleton, &hiddenLayer, &visibleLayer}) {
        ASSERT_EQ(image->type(), CV_8UC1);
        ASSERT_EQ(image->size(), cv::Size(view.size, view.size));
    }
    const Score hidden = scoreAgainst(hiddenSkeleton, truth, true, 1.5);
    const Score visible = scoreAgainst(visibleSkeleton, truth, false, 1.5);
    EXPECT_GE(hidden.f1(), 0.90) << "precision " << hidden.precision << ", recall " << hidden.recall;
    EXPECT_GE(visible.f1(), 0.90) << "precision " << visible.precision << ", recall " << visible.recall;

    // No hidden part in the visible layers: the share of hidden samples (more than 2 px from every visible one, where
    // the two meet at the occluder's outline) with a visible skeleton pixel within 1 px, or visible ink within 1 px.
    std::vector<glm::dvec2> visibleTruth;
    for (const TruthSample& sample : truth)
        if (!sample.hidden) visibleTruth.push_back(sample.pixel);
    int clearOfOutline = 0, inVisibleSkeleton = 0, inVisibleInk = 0, inHiddenInk = 0;
    for (const TruthSample& sample : truth) {
        if (!sample.hidden) continue;
        bool nearVisible = false;
        for (const glm::dvec2& point : visibleTruth)
            nearVisible = nearVisible || glm::length(point - sample.pixel) <= 2.0;
        if (nearVisible) continue;
        ++clearOfOutline;
        inVisibleSkeleton += hasPixelNear(visibleSkeleton, sample.pixel, 1.0);
        inVisibleInk += hasPixelNear(visibleLayer, sample.pixel, 1.0, 128);
        inHiddenInk += hasPixelNear(hiddenLayer, sample.pixel, 1.5, 128);
    }
    ASSERT_GT(clearOfOutline, kSamples / 4);
    EXPECT_LE(double(inVisibleSkeleton) / clearOfOutline, 0.02) << inVisibleSkeleton << " of " << clearOfOutline;
    EXPECT_LE(double(inVisibleInk) / clearOfOutline, 0.02) << inVisibleInk << " of " << clearOfOutline;
    // Solid (--hidden-dash none): the stroked hidden layer covers the hidden curves.
    EXPECT_GE(double(inHiddenInk) / clearOfOutline, 0.95) << inHiddenInk << " of " << clearOfOutline;

    // --stats: the hidden type's entry with its dash (off 0: solid) and its edges.
    const nlohmann::json stats = nlohmann::json::parse(readText(directory / "stats.json"));
    bool sawHidden = false;
    for (const nlohmann::json& entry : stats["look"]["lines"]) {
        if (entry["type"] != "hidden-mesh-silhouette") continue;
        sawHidden = true;
        EXPECT_EQ(entry["dash_pixels"]["off"], 0.0);
        EXPECT_GT(entry["edges_drawn"].get<int>(), 100);
    }
    EXPECT_TRUE(sawHidden) << stats["look"]["lines"].dump();
    std::cout << "[ hidden ] F1 " << hidden.f1() << " (precision " << hidden.precision << ", recall " << hidden.recall
              << "); visible F1 " << visible.f1() << "; hidden samples in the visible skeleton " << inVisibleSkeleton
              << " of " << clearOfOutline << ", in its ink " << inVisibleInk << "\n";
}

/** The <path elements of the SVG group "lines-<type>", each as its "d" attribute. */
std::vector<std::string> pathsOf(const std::string& svg, const std::string& type) {
    std::vector<std::string> paths;
    const std::size_t start = svg.find("<g id=\"lines-" + type + "\"");
    if (start == std::string::npos) return paths;
    const std::size_t end = svg.find("</g>", start);
    for (std::size_t at = svg.find(" d=\"", start); at < end; at = svg.find(" d=\"", at + 1))
        paths.push_back(svg.substr(at + 4, svg.find('"', at + 4) - at - 4));
    return paths;
}

/** The length of an SVG path "M x y L x y ...", in SVG units (output pixels). */
double pathLength(const std::string& d) {
    std::istringstream text(d);
    std::string command;
    double length = 0.0;
    glm::dvec2 previous(0.0);
    bool first = true;
    while (text >> command) {
        if (command == "Z") break;
        glm::dvec2 point;
        text >> point.x >> point.y;
        if (!first) length += glm::length(point - previous);
        previous = point;
        first = false;
    }
    return length;
}

TEST_F(HiddenLines, ACubesHiddenCreasesAreDashedInThePictureAndTheSvg) {
    // A unit cube seen from the (+, +, +) side: the corner (-0.5, -0.5, -0.5) and its three edges are hidden.
    std::ofstream(directory / "cube.obj") << "v -0.5 -0.5 -0.5\nv 0.5 -0.5 -0.5\nv 0.5 0.5 -0.5\nv -0.5 0.5 -0.5\n"
                                             "v -0.5 -0.5 0.5\nv 0.5 -0.5 0.5\nv 0.5 0.5 0.5\nv -0.5 0.5 0.5\n"
                                             "f 1 4 3\nf 1 3 2\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\n"
                                             "f 4 8 7\nf 4 7 3\nf 1 5 8\nf 1 8 4\nf 2 3 7\nf 2 7 6\n";
    const View view{{2.0, 1.6, 2.6}, {0.0, 0.0, 0.0}, 40.0, 192};
    for (const std::string dash : {"6,4", "none"}) {
        const CliRun result =
            run("render cube.obj " + view.flags() + " --lines crease --hidden-lines crease " + "--hidden-dash " + dash +
                " --hidden-crease-width 1.5 --dump " + dash.substr(0, 1) + " --svg " + dash.substr(0, 1) +
                ".svg --stats " + dash.substr(0, 1) + ".json -o " + dash.substr(0, 1) + ".png -q");
        ASSERT_EQ(result.exitCode, 0) << result.err;
    }
    const glm::dvec3 hiddenCorner(-0.5, -0.5, -0.5);
    const std::vector<glm::dvec3> ends = {{0.5, -0.5, -0.5}, {-0.5, 0.5, -0.5}, {-0.5, -0.5, 0.5}};
    // The 9 visible edges, projected: a hidden edge passes behind one (the front vertical edge), and there the visible
    // layer draws over it.
    std::vector<std::pair<glm::dvec2, glm::dvec2>> visibleEdges;
    for (int axis = 0; axis < 3; ++axis)
        for (const double u : {-0.5, 0.5})
            for (const double v : {-0.5, 0.5}) {
                glm::dvec3 a(0.0), b(0.0);
                a[axis] = -0.5, b[axis] = 0.5;
                a[(axis + 1) % 3] = b[(axis + 1) % 3] = u;
                a[(axis + 2) % 3] = b[(axis + 2) % 3] = v;
                if (a == hiddenCorner) continue;
                visibleEdges.emplace_back(view.project(a), view.project(b));
            }
    ASSERT_EQ(visibleEdges.size(), 9u);
    const auto nearVisibleEdge = [&](glm::dvec2 point) {
        for (const auto& [a, b] : visibleEdges) {
            const double t = std::clamp(glm::dot(point - a, b - a) / glm::dot(b - a, b - a), 0.0, 1.0);
            if (glm::length(point - (a + t * (b - a))) <= 2.5) return true;
        }
        return false;
    };
    // A layer's coverage at a point, interpolated between pixel centres.
    const auto coverageAt = [](const cv::Mat& layer, glm::dvec2 point) {
        cv::Mat patch;
        cv::getRectSubPix(layer, {1, 1}, cv::Point2f(float(point.x - 0.5), float(point.y - 0.5)), patch, CV_32F);
        return double(patch.at<float>(0, 0));
    };
    // Along the middle 80% of each hidden edge, every half pixel: dashed, runs of ink and of gaps; solid, ink only.
    for (const std::string name : {"6", "n"}) {
        SCOPED_TRACE(name);
        const cv::Mat layer = readImage(directory / name / "lines-hidden-crease.png");
        const cv::Mat visible = readImage(directory / name / "lines-crease.png");
        ASSERT_EQ(layer.type(), CV_8UC1);
        ASSERT_EQ(visible.type(), CV_8UC1);
        int samples = 0, inked = 0, runs = 0;
        double lengthPixels = 0.0;
        for (const glm::dvec3& end : ends) {
            const glm::dvec2 a = view.project(hiddenCorner), b = view.project(end);
            lengthPixels += 0.8 * glm::length(b - a);
            const int steps = int(glm::length(b - a) * 2.0);
            bool previous = false;
            for (int step = steps / 10; step <= steps - steps / 10; ++step) {
                const glm::dvec2 point = glm::mix(a, b, double(step) / steps);
                const bool ink = coverageAt(layer, point) >= 128.0;
                ++samples;
                inked += ink;
                runs += ink && !previous;
                previous = ink;
                if (!nearVisibleEdge(point)) {
                    EXPECT_LT(coverageAt(visible, point), 32.0) << "the hidden edge at " << point.x << ", " << point.y;
                }
            }
        }
        ASSERT_GT(samples, 200);
        std::cout << "[ cube " << name << " ] inked " << double(inked) / samples << " of " << samples
                  << " samples, runs " << runs << ", expected dashes " << lengthPixels / 10.0 << "\n";
        if (name == "n") {
            EXPECT_GE(double(inked) / samples, 0.97);
            EXPECT_EQ(runs, 3); // one unbroken run per edge
        } else {
            // 6 on, 4 off, and round caps of half the 1.5 px width at each dash's ends: about 7.5 of every 10 px.
            EXPECT_GT(double(inked) / samples, 0.6);
            EXPECT_LT(double(inked) / samples, 0.9);
            // One run per 10 px of the pattern: the staircase of pixel centres the pattern is measured along makes it
            // up to 8% shorter in the picture, and each of the 3 sampled stretches may cut a dash at both ends.
            EXPECT_GE(double(runs), lengthPixels / 10.0);
            EXPECT_LE(double(runs), 1.1 * lengthPixels / 10.0 + 4.0);
        }
    }

    // The SVG: the hidden layer's paths are its dashes, as many as --stats counts, each 6 px long along the stroke's
    // points (the last of a stroke may be shorter). Those are a one-pixel mask's pixel centres, a staircase on a
    // slanted edge up to 8% longer than the straight line the simplified path draws: so from 5 px (6 / 1.08 and the
    // 2-decimal rounding) to 6. Solid, one path per stroke.
    const nlohmann::json dashedStats = nlohmann::json::parse(readText(directory / "6.json"));
    const nlohmann::json& types = dashedStats["post_stage"]["strokes"]["types"];
    ASSERT_TRUE(types.contains("hidden-crease")) << types.dump();
    const int dashes = types["hidden-crease"]["dashes"].get<int>();
    const std::vector<std::string> paths = pathsOf(readText(directory / "6.svg"), "hidden-crease");
    EXPECT_EQ(int(paths.size()), dashes);
    EXPECT_GT(dashes, 3 * 4);
    int fullDashes = 0;
    for (const std::string& d : paths) {
        const double length = pathLength(d);
        EXPECT_LE(length, 6.0 + 0.05) << d;
        fullDashes += length >= 5.0;
    }
    EXPECT_GE(fullDashes, int(paths.size()) - 3) << "all but the last dash of each of the 3 strokes are whole";
    std::cout << "[ cube svg ] " << paths.size() << " dash paths, " << fullDashes << " of 5 to 6 px\n";
    const std::vector<std::string> solidPaths = pathsOf(readText(directory / "n.svg"), "hidden-crease");
    const nlohmann::json solidStats = nlohmann::json::parse(readText(directory / "n.json"));
    EXPECT_EQ(int(solidPaths.size()), solidStats["post_stage"]["strokes"]["types"]["hidden-crease"]["strokes_kept"]);
    EXPECT_EQ(solidStats["post_stage"]["strokes"]["types"]["hidden-crease"]["dashes"], 0);
}

TEST_F(HiddenLines, StyleFilesSetThemAndBadValuesAreRefused) {
    std::ofstream(directory / "cube.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
    std::ofstream(directory / "hidden.style") << "hidden-lines = crease, border\nhidden-dash = 3,2\nlines = crease\n";
    const CliRun styled = run("render cube.obj --size 64x64 --style hidden.style --stats s.json -o s.png -q");
    ASSERT_EQ(styled.exitCode, 0) << styled.err;
    const nlohmann::json stats = nlohmann::json::parse(readText(directory / "s.json"));
    std::vector<std::string> drawn;
    for (const nlohmann::json& entry : stats["look"]["lines"]) drawn.push_back(entry["type"]);
    // Composite order: the hidden types under the visible ones, and --lines after --hidden-lines keeps them.
    EXPECT_EQ(drawn, (std::vector<std::string>{"hidden-crease", "hidden-border", "crease"}));
    EXPECT_EQ(stats["look"]["lines"][0]["dash_pixels"]["on"], 3.0);
    EXPECT_EQ(stats["look"]["lines"][0]["dash_pixels"]["off"], 2.0);

    for (const auto& [flags, words] : std::vector<std::pair<std::string, std::vector<std::string>>>{
             {"--hidden-lines foo", {"--hidden-lines", "'foo'", "crease", "mesh-silhouette", "border"}},
             {"--hidden-lines contour", {"--hidden-lines", "'contour' has no hidden lines"}},
             {"--hidden-lines crease,crease", {"--hidden-lines", "listed twice"}},
             {"--hidden-lines crease --hidden-dash 0,4", {"--hidden-dash", "'0,4'"}},
             {"--hidden-lines crease --hidden-dash 6", {"--hidden-dash", "'6'"}},
             {"--hidden-lines crease --hidden-dash 6,-1", {"--hidden-dash", "'6,-1'"}},
             {"--hidden-lines crease --hidden-dash a,b", {"--hidden-dash", "'a'"}},
             {"--hidden-dash 6,4", {"--hidden-dash has no effect"}},
         }) {
        SCOPED_TRACE(flags);
        const CliRun bad = run("render cube.obj --size 64x64 --lines crease -o bad.png " + flags);
        EXPECT_EQ(bad.exitCode, 2) << bad.err;
        for (const std::string& word : words) EXPECT_NE(bad.err.find(word), std::string::npos) << bad.err;
        EXPECT_FALSE(fs::exists(directory / "bad.png"));
    }
}

} // namespace
} // namespace inkgraph
