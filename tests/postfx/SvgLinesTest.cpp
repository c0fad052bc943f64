// postfx/SvgLines, read back with tests/support/SvgPaths.h (whose strictness is tested here too); no GL.
#include "postfx/SvgLines.h"

#include "tests/support/SvgPaths.h"

#include "tests/support/ThrowMessage.h"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <limits>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace inkgraph {
namespace {

using test::parseSvgPathDocument;
using test::parseSvgPathGroups;
using test::SvgPathDocument;
using test::SvgPathGroup;

using test::invalidArgumentMessage;

bool startsWith(const std::string& text, const std::string& prefix) { return text.rfind(prefix, 0) == 0; }

Polyline openPolyline(std::vector<cv::Point2f> points) { return {std::move(points), false}; }
Polyline closedPolyline(std::vector<cv::Point2f> points) { return {std::move(points), true}; }

/** The <path .../> elements of `svg`, whole, in order. */
std::vector<std::string> pathElements(const std::string& svg) {
    std::vector<std::string> elements;
    for (std::size_t at = svg.find("<path "); at != std::string::npos; at = svg.find("<path ", at + 1))
        elements.push_back(svg.substr(at, svg.find("/>", at) + 2 - at));
    return elements;
}

/** The value of `name`="..." in `element`, or "(absent)". */
std::string attributeOf(const std::string& element, const std::string& name) {
    const std::size_t at = element.find(" " + name + "=\"");
    if (at == std::string::npos) return "(absent)";
    const std::size_t from = at + name.size() + 3;
    return element.substr(from, element.find('"', from) - from);
}

/** One command of a weighted path's d (absolute M, L, A, Z) and its numbers. */
struct PathCommand {
    char command = 0;
    std::vector<double> numbers;
    /** Where the command ends: (x, y) for M and L, the last two numbers for A. */
    cv::Point2d end() const { return {numbers[numbers.size() - 2], numbers[numbers.size() - 1]}; }
};

std::vector<PathCommand> parseD(const std::string& d) {
    std::vector<PathCommand> commands;
    std::istringstream tokens(d);
    std::string token;
    while (tokens >> token) {
        if (token.size() == 1 && std::isalpha(static_cast<unsigned char>(token[0])))
            commands.push_back({token[0], {}});
        else if (!commands.empty())
            commands.back().numbers.push_back(std::stod(token));
        else
            ADD_FAILURE() << "a number before any command in '" << d << "'";
    }
    return commands;
}

std::size_t countOf(const std::vector<PathCommand>& commands, char command) {
    return std::size_t(std::count_if(commands.begin(), commands.end(),
                                     [&](const PathCommand& each) { return each.command == command; }));
}

TEST(SvgLinesTest, DocumentHeaderIsStandaloneSvgWithInkscapeLayers) {
    SvgLineLayer layer;
    layer.type = "contour";
    layer.polylines = {openPolyline({{0, 0}, {9, 0}})};
    const std::string svg = svgDocument(640, 480, {layer}, {"bunny"});
    EXPECT_TRUE(startsWith(svg, "<?xml version=\"1.0\" encoding=\"UTF-8\" standalone=\"no\"?>\n<svg "));
    EXPECT_NE(svg.find("xmlns=\"http://www.w3.org/2000/svg\""), std::string::npos);
    EXPECT_NE(svg.find("xmlns:inkscape=\"http://www.inkscape.org/namespaces/inkscape\""), std::string::npos);
    EXPECT_NE(svg.find("width=\"640\" height=\"480\" viewBox=\"0 0 640 480\""), std::string::npos);
    EXPECT_NE(svg.find("<title>bunny</title>"), std::string::npos);
    EXPECT_NE(svg.find("<g id=\"lines-contour\" inkscape:groupmode=\"layer\" inkscape:label=\"contour\" opacity=\"1\" "
                       "fill=\"none\" stroke=\"#000000\" stroke-width=\"2\" stroke-linecap=\"round\" "
                       "stroke-linejoin=\"round\">"),
              std::string::npos);
    // S = 1: data pixel centres land on output pixel centres, (col + 0.5, row + 0.5).
    EXPECT_NE(svg.find("<path d=\"M 0.5 0.5 L 9.5 0.5\"/>"), std::string::npos);
    EXPECT_EQ(svg.find("<rect"), std::string::npos); // no background unless asked
    EXPECT_EQ(svg.substr(svg.size() - 7), "</svg>\n");
}

TEST(SvgLinesTest, RoundTripThroughTheParser) {
    SvgLineLayer contour;
    contour.type = "contour";
    contour.color = {1.0, 0.0, 0.0, 1.0};
    contour.widthPixels = 2.0;
    contour.polylines = {openPolyline({{10.123f, 20.0f}, {30.0f, 40.56f}, {-0.5f, 3.25f}}),
                         closedPolyline({{1, 1}, {5, 1}, {5, 5}}), openPolyline({{7, 8}})}; // a dot
    SvgLineLayer silhouette;
    silhouette.type = "silhouette";
    silhouette.supersample = 2;
    silhouette.widthPixels = 3.5;
    silhouette.color = {0.0, 0.2, 1.0, 0.5};
    silhouette.polylines = {openPolyline({{1, 3}, {11, 3}})};
    SvgLineLayer empty;
    empty.type = "suggestive-object";

    const SvgPathDocument document =
        parseSvgPathDocument(svgDocument(100, 50, {contour, silhouette, empty}, {"t", std::nullopt}));
    EXPECT_EQ(document.width, 100);
    EXPECT_EQ(document.height, 50);
    EXPECT_EQ(document.title, "t");
    EXPECT_FALSE(document.background);
    ASSERT_EQ(document.groups.size(), 3u);

    const SvgPathGroup& first = document.groups[0];
    EXPECT_EQ(first.id, "lines-contour");
    EXPECT_EQ(first.label, "contour");
    EXPECT_EQ(first.stroke, "#ff0000");
    EXPECT_DOUBLE_EQ(first.opacity, 1.0);
    EXPECT_DOUBLE_EQ(first.strokeWidth, 2.0);
    ASSERT_EQ(first.paths.size(), 3u);
    // x + 0.5, y + 0.5, rounded to 2 decimals.
    const std::vector<cv::Point2d> path0 = {{10.62, 20.5}, {30.5, 41.06}, {0.0, 3.75}};
    ASSERT_EQ(first.paths[0].size(), path0.size());
    for (std::size_t index = 0; index < path0.size(); ++index) {
        EXPECT_DOUBLE_EQ(first.paths[0][index].x, path0[index].x);
        EXPECT_DOUBLE_EQ(first.paths[0][index].y, path0[index].y);
    }
    EXPECT_FALSE(first.closed[0]);
    EXPECT_EQ(first.paths[1], (std::vector<cv::Point2d>{{1.5, 1.5}, {5.5, 1.5}, {5.5, 5.5}}));
    EXPECT_TRUE(first.closed[1]);
    // A dot is a zero-length segment, so round caps draw it.
    EXPECT_EQ(first.paths[2], (std::vector<cv::Point2d>{{7.5, 8.5}, {7.5, 8.5}}));
    EXPECT_FALSE(first.closed[2]);

    const SvgPathGroup& second = document.groups[1];
    EXPECT_EQ(second.id, "lines-silhouette");
    EXPECT_EQ(second.stroke, "#0033ff"); // 0.2 x 255 = 51
    EXPECT_DOUBLE_EQ(second.opacity, 0.5);
    EXPECT_DOUBLE_EQ(second.strokeWidth, 3.5);
    // S = 2: (x + 0.5) / 2, so data pixels 0 and 1 (output pixel 0) straddle the output centre 0.5.
    ASSERT_EQ(second.paths.size(), 1u);
    EXPECT_EQ(second.paths[0], (std::vector<cv::Point2d>{{0.75, 1.75}, {5.75, 1.75}}));

    EXPECT_EQ(document.groups[2].id, "lines-suggestive-object"); // an empty layer is still a layer
    EXPECT_TRUE(document.groups[2].paths.empty());
}

/** The colour's alpha is the layer's group opacity, so paths that overlap do not darken each other (the picture lays
 *  each layer on once); a faded path's own opacity is its stroke-opacity (a weighted path's fill-opacity). */
TEST(SvgLinesTest, AFadedLineCarriesItsOwnOpacityUnderTheGroupsOpacity) {
    SvgLineLayer layer;
    layer.type = "suggestive";
    layer.color = {0.0, 0.0, 0.0, 0.4};
    layer.polylines = {openPolyline({{0, 0}, {9, 0}}), openPolyline({{0, 4}, {9, 4}}), openPolyline({{0, 8}, {9, 8}})};
    layer.opacities = {1.0, 0.25, 0.9996};
    const std::string svg = svgDocument(20, 20, {layer});
    const SvgPathDocument document = parseSvgPathDocument(svg);
    ASSERT_EQ(document.groups.size(), 1u);
    EXPECT_DOUBLE_EQ(document.groups[0].opacity, 0.4);
    EXPECT_EQ(document.groups[0].pathOpacities, (std::vector<double>{1.0, 0.25, 1.0}))
        << "an opacity that rounds to 1 is left out";
    layer.widths = {{2.0, 2.0}, {2.0, 3.0}, {1.0, 1.0}};
    const std::vector<std::string> paths = pathElements(svgDocument(20, 20, {layer}));
    ASSERT_EQ(paths.size(), 3u);
    EXPECT_EQ(attributeOf(paths[0], "fill-opacity"), "(absent)");
    EXPECT_EQ(attributeOf(paths[1], "fill-opacity"), "0.25");
    layer.opacities = {1.0, 0.0, 1.0};
    EXPECT_NE(invalidArgumentMessage([&] { svgDocument(20, 20, {layer}); }).find("'opacities' must lie in (0, 1]"),
              std::string::npos);
    layer.opacities = {1.0};
    EXPECT_NE(invalidArgumentMessage([&] { svgDocument(20, 20, {layer}); }).find("'opacities' must be empty or one"),
              std::string::npos);
}

TEST(SvgLinesTest, SupersampledTraceMapsToOutputPixels) {
    // A horizontal band at data rows 8..10 (S = 2, output 20 x 10): its centre line at data row 9 lies at
    // output y = (9 + 0.5) / 2 = 4.75, the centre of the output area rows 8..10 cover.
    cv::Mat mask = cv::Mat::zeros(20, 40, CV_8UC1);
    mask(cv::Rect(4, 8, 32, 3)).setTo(255);
    SvgLineLayer layer;
    layer.type = "outline";
    layer.supersample = 2;
    layer.polylines = traceMask(mask);
    const std::vector<SvgPathGroup> groups = parseSvgPathGroups(svgDocument(20, 10, {layer}));
    ASSERT_EQ(groups.size(), 1u);
    ASSERT_EQ(groups[0].paths.size(), 1u);
    const std::vector<cv::Point2d>& path = groups[0].paths[0];
    ASSERT_EQ(path.size(), 2u);
    for (const cv::Point2d& point : path) {
        EXPECT_DOUBLE_EQ(point.y, 4.75);
        EXPECT_GE(point.x, (4 + 0.5) / 2.0);
        EXPECT_LE(point.x, (35 + 0.5) / 2.0);
    }
    EXPECT_GT(std::abs(path[1].x - path[0].x), 12.0);
}

TEST(SvgLinesTest, BackgroundIsAFullSizeRectBelowTheLines) {
    SvgLineLayer layer;
    layer.type = "crease";
    SvgDocumentOptions options;
    options.background = std::array<double, 4>{1.0, 1.0, 0.5, 0.25};
    const std::string svg = svgDocument(32, 16, {layer}, options);
    EXPECT_NE(svg.find("<rect id=\"background\" x=\"0\" y=\"0\" width=\"32\" height=\"16\" fill=\"#ffff80\" "
                       "fill-opacity=\"0.25\"/>"),
              std::string::npos);
    EXPECT_LT(svg.find("<rect"), svg.find("<g "));
    const SvgPathDocument document = parseSvgPathDocument(svg);
    EXPECT_EQ(document.background, "#ffff80");
}

TEST(SvgLinesTest, TitleIsXmlEscaped) {
    const std::string title = "a<b & \"c\" 'd'> \xc3\xa9t\xc3\xa9"; // UTF-8 kept as it is
    const std::string svg = svgDocument(4, 4, {}, {title});
    EXPECT_NE(svg.find("<title>a&lt;b &amp; &quot;c&quot; &apos;d&apos;&gt; \xc3\xa9t\xc3\xa9</title>"),
              std::string::npos);
    EXPECT_EQ(parseSvgPathDocument(svg).title, title);
    // What XML 1.0 cannot hold: control characters and invalid UTF-8 become '?'.
    const std::string bad = std::string("x\x01y") + "\xff" + "z\xc3" + "\tw";
    EXPECT_EQ(parseSvgPathDocument(svgDocument(4, 4, {}, {bad})).title, "x?y?z?\tw");
}

TEST(SvgLinesTest, CoordinatesAreLocaleFreeWithTwoDecimals) {
    SvgLineLayer layer;
    layer.type = "a_b.c-1";
    layer.widthPixels = 0.75;
    layer.polylines = {openPolyline({{-0.504f, 0.0f}, {1234.5678f, 0.004f}})};
    const std::string svg = svgDocument(2000, 10, {layer});
    // -0.004 rounds to 0 (never "-0"); 1235.0678 to 1235.07; trailing zeros go.
    EXPECT_NE(svg.find("<path d=\"M 0 0.5 L 1235.07 0.5\"/>"), std::string::npos) << svg;
    EXPECT_NE(svg.find("stroke-width=\"0.75\""), std::string::npos);
}

TEST(SvgLinesTest, BadArgumentsThrowNamingThem) {
    SvgLineLayer good;
    good.type = "contour";
    good.polylines = {openPolyline({{1, 1}, {2, 2}})};
    auto withLayer = [&](auto change) {
        SvgLineLayer layer = good;
        change(layer);
        return invalidArgumentMessage([&] { svgDocument(10, 10, {layer}); });
    };
    EXPECT_TRUE(startsWith(invalidArgumentMessage([&] { svgDocument(0, 10, {good}); }), "svgDocument(): 'width'"));
    EXPECT_TRUE(startsWith(invalidArgumentMessage([&] { svgDocument(10, -1, {good}); }),
                           "svgDocument(): 'width' and 'height'"));
    EXPECT_TRUE(
        startsWith(withLayer([](SvgLineLayer& l) { l.supersample = 0; }), "svgDocument(): 'layers' [0] 'supersample'"));
    EXPECT_TRUE(startsWith(withLayer([](SvgLineLayer& l) { l.type = "a b"; }), "svgDocument(): 'layers' [0] 'type'"));
    EXPECT_TRUE(startsWith(withLayer([](SvgLineLayer& l) { l.type = "<x>"; }), "svgDocument(): 'layers' [0] 'type'"));
    EXPECT_TRUE(startsWith(withLayer([](SvgLineLayer& l) { l.type = ""; }), "svgDocument(): 'layers' [0] 'type'"));
    EXPECT_TRUE(startsWith(withLayer([](SvgLineLayer& l) { l.widthPixels = 0.0; }),
                           "svgDocument(): 'layers' [0] 'widthPixels'"));
    EXPECT_TRUE(startsWith(withLayer([](SvgLineLayer& l) { l.widthPixels = std::nan(""); }),
                           "svgDocument(): 'layers' [0] 'widthPixels'"));
    EXPECT_TRUE(
        startsWith(withLayer([](SvgLineLayer& l) { l.color[1] = 1.5; }), "svgDocument(): 'layers' [0] 'color'"));
    EXPECT_TRUE(startsWith(withLayer([](SvgLineLayer& l) { l.color[3] = std::nan(""); }),
                           "svgDocument(): 'layers' [0] 'color'"));
    EXPECT_TRUE(startsWith(
        withLayer([](SvgLineLayer& l) { l.polylines[0].points[1].y = std::numeric_limits<float>::infinity(); }),
        "svgDocument(): 'layers' [0] 'polylines' [0]"));
    EXPECT_TRUE(startsWith(invalidArgumentMessage([&] {
                               svgDocument(10, 10, {good, good});
                           }),
                           "svgDocument(): 'layers' [1] 'type' 'contour' repeats"));
    SvgDocumentOptions options;
    options.background = std::array<double, 4>{0.0, -0.1, 0.0, 1.0};
    EXPECT_TRUE(startsWith(invalidArgumentMessage([&] { svgDocument(10, 10, {good}, options); }),
                           "svgDocument(): 'options.background'"));
}

TEST(SvgPathsTest, ParserRejectsMalformedDocuments) {
    SvgLineLayer layer;
    layer.type = "contour";
    layer.polylines = {openPolyline({{1, 1}, {2, 2}})};
    const std::string good = svgDocument(10, 10, {layer}, {"t"});
    ASSERT_NO_THROW(parseSvgPathDocument(good));
    auto replaced = [&](const std::string& from, const std::string& to) {
        std::string text = good;
        const std::size_t at = text.find(from);
        EXPECT_NE(at, std::string::npos) << from;
        return text.replace(at, from.size(), to);
    };
    const std::vector<std::string> broken = {
        replaced("  </g>\n", ""),                                                             // unbalanced
        replaced("</g>", "</svg>"),                                                           // mismatched
        replaced("</svg>\n", ""),                                                             // never closed
        replaced("</svg>\n", "</svg>\n</svg>\n"),                                             // closes nothing
        replaced("<path d=\"M 1.5 1.5 L 2.5 2.5\"/>", "<path d=\"M 1.5 1.5 C 2.5 2.5\"/>"),   // unknown command
        replaced("<path d=\"M 1.5 1.5 L 2.5 2.5\"/>", "<path d=\"M 1.5 1.5 L 2.5\"/>"),       // missing y
        replaced("<path d=\"M 1.5 1.5 L 2.5 2.5\"/>", "<path d=\"M 1.5 1.5 Z L 2.5 2.5\"/>"), // Z not at the end
        replaced("<path d=\"M 1.5 1.5 L 2.5 2.5\"/>", "<path d=\"M 1.5 nan L 2.5 2.5\"/>"),   // not a number
        replaced("  <g ", "  <path d=\"M 1 1 L 2 2\"/>\n  <g "),                              // path outside a group
        replaced("<title>t</title>", "<title>a & b</title>"),                                 // bare '&'
        replaced("<title>t</title>", "<title>t</title>\n  stray text"),
        replaced("viewBox=\"0 0 10 10\"", "viewBox=\"0 0 10 11\""),
        replaced("<title>t</title>", "<circle r=\"1\"/>"),                       // unknown element (and no title)
        replaced("stroke=\"#000000\"", "stroke=\"#000000\" stroke=\"#000000\""), // repeated attribute
        replaced("<?xml", "<?xmm"),
    };
    for (std::size_t index = 0; index < broken.size(); ++index)
        EXPECT_THROW(parseSvgPathDocument(broken[index]), std::runtime_error) << index << ":\n" << broken[index];
}

TEST(SvgLinesTest, AWeightedLineIsAFilledOutlineAtHalfItsWidthFromTheCentreLine) {
    // Data pixel centres (0.5, 0.5) to (10.5, 0.5), 2 px wide at the start and 4 px at the end: the left side runs
    // 1 then 2 px to one side, a round cap of radius 2 turns to the other side, which runs back, and a cap of radius
    // 1 closes it.
    SvgLineLayer layer;
    layer.type = "contour";
    layer.color = {1.0, 0.0, 0.0, 0.5};
    layer.polylines = {openPolyline({{0, 0}, {10, 0}})};
    layer.widths = {{2.0, 4.0}};
    const std::vector<std::string> paths = pathElements(svgDocument(20, 10, {layer}));
    ASSERT_EQ(paths.size(), 1u);
    EXPECT_EQ(attributeOf(paths[0], "fill"), "#ff0000");
    EXPECT_EQ(attributeOf(paths[0], "fill-opacity"), "(absent)") << "the colour's alpha is the group's opacity";
    EXPECT_EQ(attributeOf(paths[0], "stroke"), "none");
    const std::string d = attributeOf(paths[0], "d");
    EXPECT_TRUE(startsWith(d, "M 0.5 1.5 ") || startsWith(d, "M 0.5 -0.5 ")) << d;
    const std::vector<PathCommand> commands = parseD(d);
    ASSERT_GE(commands.size(), 6u) << d;
    EXPECT_EQ(commands.front().command, 'M');
    EXPECT_EQ(commands.back().command, 'Z');
    EXPECT_EQ(countOf(commands, 'M'), 1u);
    EXPECT_EQ(countOf(commands, 'A'), 2u) << d;
    EXPECT_EQ(countOf(commands, 'Z'), 1u);
    // Every vertex lies at half the width at its x (1 px at x = 0.5, 2 px at x = 10.5) from the centre line y = 0.5,
    // and each cap's radius is half the width where it turns.
    std::size_t vertices = 0;
    for (const PathCommand& command : commands) {
        if (command.command == 'Z') continue;
        ASSERT_EQ(command.numbers.size(), command.command == 'A' ? 7u : 2u) << d;
        const cv::Point2d vertex = command.end();
        ASSERT_TRUE(vertex.x == 0.5 || vertex.x == 10.5) << d;
        const double halfWidth = vertex.x == 0.5 ? 1.0 : 2.0;
        EXPECT_NEAR(std::abs(vertex.y - 0.5), halfWidth, 1e-9) << d;
        if (command.command == 'A') {
            // The cap that ends here started on the other side at the same x: radius is half that width.
            EXPECT_NEAR(command.numbers[0], halfWidth, 1e-9) << d;
            EXPECT_NEAR(command.numbers[1], halfWidth, 1e-9) << d;
        }
        ++vertices;
    }
    EXPECT_EQ(vertices, 5u) << "two sides of two vertices and the start again: " << d;
    // Both sides are there: one vertex above and one below the centre line at each end.
    std::set<std::pair<double, double>> corners;
    for (const PathCommand& command : commands)
        if (command.command != 'Z') corners.insert({command.end().x, command.end().y});
    EXPECT_EQ(corners, (std::set<std::pair<double, double>>{{0.5, -0.5}, {0.5, 1.5}, {10.5, -1.5}, {10.5, 2.5}}));
    // Each cap bulges out of the line's end, not into the line: a half circle from one side to the other, whose
    // middle (the start turned a quarter about the centre, the way its sweep flag turns; y points down) lies a
    // radius beyond the end. Half of the caps bit into the strokes before.
    for (std::size_t index = 1; index < commands.size(); ++index) {
        if (commands[index].command != 'A') continue;
        const cv::Point2d from = commands[index - 1].end(), to = commands[index].end();
        const cv::Point2d centre = 0.5 * (from + to), start = from - centre;
        const bool sweep = commands[index].numbers[4] != 0.0;
        const cv::Point2d middle = centre + (sweep ? cv::Point2d(-start.y, start.x) : cv::Point2d(start.y, -start.x));
        if (centre.x < 5.0)
            EXPECT_NEAR(middle.x, 0.5 - 1.0, 1e-9) << "the start's cap: " << d;
        else
            EXPECT_NEAR(middle.x, 10.5 + 2.0, 1e-9) << "the end's cap: " << d;
        EXPECT_NEAR(middle.y, 0.5, 1e-9) << d;
    }
}

TEST(SvgLinesTest, AWeightedClosedLineIsARingOfTwoSubpaths) {
    SvgLineLayer layer;
    layer.type = "contour";
    layer.polylines = {closedPolyline({{0, 0}, {20, 0}, {10, 15}})};
    layer.widths = {{2.0, 2.0, 2.0}};
    const std::vector<std::string> paths = pathElements(svgDocument(30, 20, {layer}));
    ASSERT_EQ(paths.size(), 1u);
    EXPECT_EQ(attributeOf(paths[0], "stroke"), "none");
    const std::string d = attributeOf(paths[0], "d");
    const std::vector<PathCommand> commands = parseD(d);
    EXPECT_EQ(countOf(commands, 'M'), 2u) << "outer and inner sides: " << d;
    EXPECT_EQ(countOf(commands, 'Z'), 2u) << d;
    EXPECT_EQ(countOf(commands, 'A'), 0u) << "a ring has no ends to cap: " << d;
    EXPECT_EQ(countOf(commands, 'L'), 4u) << d;
    ASSERT_FALSE(commands.empty());
    EXPECT_EQ(commands.back().command, 'Z');
    // The inner side lies inside the triangle of the centre line, the outer one outside it.
    const std::vector<cv::Point2f> centre = {{0.5f, 0.5f}, {20.5f, 0.5f}, {10.5f, 15.5f}};
    std::size_t subpath = 0;
    std::array<int, 2> inside{0, 0}, outside{0, 0};
    for (const PathCommand& command : commands) {
        if (command.command == 'Z') {
            ++subpath;
            continue;
        }
        const cv::Point2d vertex = command.end();
        const double side = cv::pointPolygonTest(centre, cv::Point2f(float(vertex.x), float(vertex.y)), false);
        ASSERT_LT(subpath, 2u);
        (side > 0 ? inside : outside)[subpath] += 1;
    }
    EXPECT_TRUE((inside[0] == 3 && outside[1] == 3) || (outside[0] == 3 && inside[1] == 3))
        << "one subpath wholly inside, the other wholly outside: " << d;
}

TEST(SvgLinesTest, AWeightedDotIsACircleOfItsWidth) {
    SvgLineLayer layer;
    layer.type = "contour";
    layer.polylines = {openPolyline({{7, 8}})};
    layer.widths = {{3.0}};
    const std::vector<std::string> paths = pathElements(svgDocument(20, 20, {layer}));
    ASSERT_EQ(paths.size(), 1u);
    EXPECT_EQ(attributeOf(paths[0], "stroke"), "none");
    // Centre (7.5, 8.5), radius 1.5: from the left end a half circle to the right end and back.
    EXPECT_EQ(attributeOf(paths[0], "d"), "M 6 8.5 A 1.5 1.5 0 0 0 9 8.5 A 1.5 1.5 0 0 0 6 8.5 Z");
}

TEST(SvgLinesTest, WidthsMustMatchThePolylines) {
    SvgLineLayer layer;
    layer.type = "contour";
    layer.polylines = {openPolyline({{0, 0}, {5, 0}}), openPolyline({{1, 1}, {1, 5}})};
    layer.widths = {{2.0, 2.0}}; // one list for two polylines
    std::string message = invalidArgumentMessage([&] { svgDocument(10, 10, {layer}); });
    EXPECT_NE(message.find("'widths'"), std::string::npos) << message;
    layer.widths = {{2.0, 2.0}, {2.0}}; // one width for two vertices
    message = invalidArgumentMessage([&] { svgDocument(10, 10, {layer}); });
    EXPECT_NE(message.find("'widths' [1]"), std::string::npos) << message;
    layer.widths = {{2.0, 2.0}, {2.0, 0.0}};
    message = invalidArgumentMessage([&] { svgDocument(10, 10, {layer}); });
    EXPECT_NE(message.find("'widths' [1]"), std::string::npos) << message;
    layer.widths = {{2.0, 2.0}, {2.0, 3.0}};
    EXPECT_NO_THROW(svgDocument(10, 10, {layer}));
}

} // namespace
} // namespace inkgraph
