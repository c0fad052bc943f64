#include "graph/Plan.h"

#include "FakePass.h"

#include <gtest/gtest.h>

#include <string>

namespace inkgraph::test {
namespace {

/** G-buffer -> lambert -> export (side effect), with a culled hull and a dead optional G-buffer output. */
void addSmallGraph(FakeGraph& graph) {
    graph.addPass("gbuffer", {},
                  {{"normal", Need::Required, {Format::RGBA32F, 1}},
                   {"depth", Need::Required, {Format::R32F, 2}},
                   optionalWrite("wVec")});
    graph.addPass("lambert", {"gbuffer.normal"}, {{"color", Need::Required, {Format::RGBA8, 1}}});
    graph.addPass("hull", {"lambert.color"}, {{"color", Need::Required, {Format::RGBA8, 1}}});
    graph.addPass("export", {"lambert.color"}, {}, true);
}

std::size_t countOf(const std::string& text, const std::string& needle) {
    std::size_t count = 0;
    for (std::size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1)) ++count;
    return count;
}

TEST(GraphPlanTest, FindPassAndResource) {
    FakeGraph graph;
    addSmallGraph(graph);
    const Plan plan = graph.compile({"lambert.color"});

    ASSERT_NE(plan.findPass("lambert"), nullptr);
    EXPECT_EQ(plan.findPass("lambert")->registrationIndex, 1u);
    EXPECT_EQ(plan.findPass("hull"), nullptr); // culled
    EXPECT_EQ(plan.findPass("nothing"), nullptr);

    ASSERT_NE(plan.findResource("gbuffer.depth"), nullptr);
    EXPECT_EQ(plan.findResource("gbuffer.depth")->desc, (TextureDesc{Format::R32F, 2}));
    EXPECT_EQ(plan.findResource("gbuffer.wVec"), nullptr); // dead optional output
    EXPECT_EQ(plan.findResource("hull.color"), nullptr);   // written by a culled pass
    EXPECT_EQ(plan.findResource("gbuffer"), nullptr);
}

TEST(GraphPlanTest, DescribeShowsPassesCulledReasonsAndLifetimes) {
    FakeGraph graph;
    addSmallGraph(graph);
    const Plan plan = graph.compile({"lambert.color"});

    const std::string expected =
        "plan: 3 passes run, 1 culled; requested: 'lambert.color'\n"
        "  1. gbuffer  reads: -               writes: gbuffer.normal(rgba32f) gbuffer.depth(r32f x2)  "
        "not computed: gbuffer.wVec\n"
        "  2. lambert  reads: gbuffer.normal  writes: lambert.color(rgba8)\n"
        "  3. export   reads: lambert.color   writes: -                                               side effect\n"
        "culled:\n"
        "  - hull: no requested output depends on 'hull.color' (nothing reads it)\n"
        "lifetimes:\n"
        "  gbuffer.depth   r32f x2  passes 1..1  gbuffer -> -\n"
        "  gbuffer.normal  rgba32f  passes 1..2  gbuffer -> lambert\n"
        "  lambert.color   rgba8    passes 2..3  lambert -> export   (requested)\n";
    EXPECT_EQ(plan.describe(), expected);
}

TEST(GraphPlanTest, DescribeNamesEveryPassAndIsStableAcrossCompiles) {
    FakeGraph graph;
    addSmallGraph(graph);
    graph.addPass("contours", {"gbuffer.depth"}, {{"lines", Need::Required, {Format::R8, 1}}});

    const std::string first = graph.compile({"lambert.color"}).describe();
    const std::string second = graph.compile({"lambert.color"}).describe();
    EXPECT_EQ(first, second);
    for (const char* name : {"gbuffer", "lambert", "hull", "export", "contours"})
        EXPECT_NE(first.find(name), std::string::npos) << name;
    EXPECT_NE(first.find("  - contours: no requested output depends on 'contours.lines' (nothing reads it)\n"),
              std::string::npos)
        << first;
    EXPECT_NE(first.find("2 culled"), std::string::npos) << first;
    // No line ends in padding.
    EXPECT_EQ(countOf(first, " \n"), 0u) << first;
}

TEST(GraphPlanTest, DescribeWithNothingCulledOrRequested) {
    FakeGraph graph;
    graph.addPass("src", {}, {{"out", Need::Required, {Format::R8, 1}}});
    graph.addPass("log", {"src.out"}, {}, true);

    EXPECT_EQ(graph.compile({}).describe(), "plan: 2 passes run, 0 culled; requested: none\n"
                                            "  1. src  reads: -        writes: src.out(r8)\n"
                                            "  2. log  reads: src.out  writes: -            side effect\n"
                                            "culled: none\n"
                                            "lifetimes:\n"
                                            "  src.out  r8  passes 1..2  src -> log\n");
}

TEST(GraphPlanTest, DescribeAlignsTwoDigitPassNumbers) {
    FakeGraph graph;
    std::string previous;
    for (int i = 0; i < 10; ++i) {
        // Built with append: GCC 12 warns falsely (-Wrestrict, bug 105651) on "literal" + std::string here.
        std::string name = "p";
        name += std::to_string(i);
        graph.addPass(name, previous.empty() ? std::vector<std::string>{} : std::vector<std::string>{previous},
                      {{"out"}});
        previous = name + ".out";
    }
    const std::string text = graph.compile({previous}).describe();
    EXPECT_NE(text.find("\n   1. p0  "), std::string::npos) << text;
    EXPECT_NE(text.find("\n  10. p9  "), std::string::npos) << text;
    EXPECT_NE(text.find("  p9.out  rgba32f  passes 10..10  p9 -> -   (requested)\n"), std::string::npos) << text;
}

TEST(GraphPlanTest, GraphvizDrawsLiveAndCulledPasses) {
    FakeGraph graph;
    addSmallGraph(graph);
    const Plan plan = graph.compile({"lambert.color"});
    const std::string dot = plan.graphviz();

    EXPECT_EQ(dot.rfind("digraph plan {\n", 0), 0u);
    EXPECT_EQ(dot.substr(dot.size() - 2), "}\n");
    EXPECT_NE(dot.find("\"pass:gbuffer\" [shape=box, style=solid, label=\"1. gbuffer\"];"), std::string::npos) << dot;
    EXPECT_NE(dot.find("\"pass:export\" [shape=box, style=bold, label=\"3. export\"];"), std::string::npos) << dot;
    EXPECT_NE(dot.find("\"res:lambert.color\" [shape=ellipse, label=\"lambert.color\\nrgba8, passes 2..3\", "
                       "peripheries=2];"),
              std::string::npos)
        << dot;
    // Culled pass greyed, its reason as a tooltip, its edges and outputs dashed.
    EXPECT_NE(dot.find("\"pass:hull\" [shape=box, style=dashed, color=grey60, fontcolor=grey50, label=\"hull\", "
                       "tooltip=\"culled: no requested output depends on 'hull.color' (nothing reads it)\"];"),
              std::string::npos)
        << dot;
    EXPECT_NE(dot.find("\"res:lambert.color\" -> \"pass:hull\" [style=dashed"), std::string::npos) << dot;
    EXPECT_NE(dot.find("\"res:hull.color\" [shape=ellipse, style=dashed"), std::string::npos) << dot;
    EXPECT_NE(dot.find("\"res:gbuffer.wVec\" [shape=ellipse, style=dashed"), std::string::npos) << dot;
    // Live edges: write then read.
    EXPECT_NE(dot.find("\"pass:gbuffer\" -> \"res:gbuffer.normal\";"), std::string::npos) << dot;
    EXPECT_NE(dot.find("\"res:gbuffer.normal\" -> \"pass:lambert\";"), std::string::npos) << dot;
    // Every node is declared once.
    EXPECT_EQ(countOf(dot, "    \"res:hull.color\" [shape"), 1u);
    EXPECT_EQ(countOf(dot, "    \"res:lambert.color\" [shape"), 1u);
    EXPECT_EQ(dot, graph.compile({"lambert.color"}).graphviz());
}

TEST(GraphPlanTest, GraphvizEscapesQuotes) {
    Plan plan;
    plan.passes.push_back({"say\"hi\\", 0, {}, {}, {}, false});
    const std::string dot = plan.graphviz();
    EXPECT_NE(dot.find("\"pass:say\\\"hi\\\\\""), std::string::npos) << dot;
}

} // namespace
} // namespace inkgraph::test
