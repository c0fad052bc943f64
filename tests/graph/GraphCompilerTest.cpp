#include "graph/GraphCompiler.h"

#include "FakePass.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace inkgraph::test {
namespace {

using Names = std::vector<std::string>;

const TextureDesc kNormalDesc{Format::RGBA32F, 1};
const TextureDesc kDepthDesc{Format::R32F, 1};
const TextureDesc kColorDesc{Format::RGBA8, 1};
const TextureDesc kLinesDesc{Format::R8, 1};

/** The shape of the real pipeline: a G-buffer with optional outputs, shading, a hull, contours and a composite.
 *  Registered in the order a user would write it. */
void addPipeline(FakeGraph& graph) {
    graph.addPass("gbuffer", {},
                  {{"normal", Need::Required, kNormalDesc},
                   {"depth", Need::Required, kDepthDesc},
                   optionalWrite("viewVec"),
                   optionalWrite("wVec")});
    graph.addPass("lambert", {"gbuffer.normal"}, {{"color", Need::Required, kColorDesc}});
    graph.addPass("hull", {"lambert.color"}, {{"color", Need::Required, kColorDesc}});
    graph.addPass("contours", {"gbuffer.normal", "gbuffer.depth"}, {{"lines", Need::Required, kLinesDesc}});
    graph.addPass("composite", {"hull.color", "contours.lines"}, {{"final", Need::Required, kColorDesc}});
}

const CulledPass* findCulled(const Plan& plan, const std::string& name) {
    for (const CulledPass& pass : plan.culled)
        if (pass.name == name) return &pass;
    return nullptr;
}

// --- background reads ---------------------------------------------------------------------------------------------

TEST(GraphCompilerTest, AFieldReadOnlyWhereCoveredLeavesItsBackgroundUnread) {
    const auto build = [](FakeGraph& graph) {
        graph.addPass("gbuffer", {}, {{"normal", Need::Required, kNormalDesc}, {"depth", Need::Required, kDepthDesc}});
        graph.addPass("shade", {}, {{"color", Need::Required, kColorDesc}}).readWhereCovered("gbuffer.normal");
        graph.addPass("contours", {"gbuffer.depth"}, {{"lines", Need::Required, kLinesDesc}})
            .readWhereCovered("gbuffer.normal");
    };
    const auto backgroundRead = [](const Plan& plan, const std::string& name) {
        const PlannedResource* resource = plan.findResource(name);
        EXPECT_NE(resource, nullptr) << name;
        return resource == nullptr || resource->backgroundRead;
    };
    {
        FakeGraph graph;
        build(graph);
        graph.addPass("composite", {"shade.color", "contours.lines"}, {{"final", Need::Required, kColorDesc}});
        const Plan plan = graph.compile({"composite.final"});
        EXPECT_FALSE(backgroundRead(plan, "gbuffer.normal")) << "both readers read where covered";
        EXPECT_TRUE(backgroundRead(plan, "gbuffer.depth")) << "the contours read the depth whole";
        EXPECT_TRUE(backgroundRead(plan, "shade.color"));
        EXPECT_TRUE(backgroundRead(plan, "composite.final")) << "requested";
        EXPECT_NE(plan.describe().find("gbuffer -> shade, contours  (read where covered: not cleared)"),
                  std::string::npos)
            << plan.describe();
        // Asked for, every pixel of it is handed out.
        EXPECT_TRUE(backgroundRead(graph.compile({"composite.final", "gbuffer.normal"}), "gbuffer.normal"));
    }
    {
        // One reader of the whole image is enough; a culled one does not count.
        FakeGraph graph;
        build(graph);
        graph.addPass("edges", {"gbuffer.normal"}, {{"lines", Need::Required, kLinesDesc}});
        graph.addPass("composite", {"shade.color", "contours.lines"}, {{"final", Need::Required, kColorDesc}});
        EXPECT_FALSE(backgroundRead(graph.compile({"composite.final"}), "gbuffer.normal")) << "edges is culled";
        EXPECT_TRUE(backgroundRead(graph.compile({"composite.final", "edges.lines"}), "gbuffer.normal"));
    }
    {
        // A pass that reads a field both ways reads it whole.
        FakeGraph graph;
        build(graph);
        graph.addPass("both", {"gbuffer.normal"}, {{"lines", Need::Required, kLinesDesc}})
            .readWhereCovered("gbuffer.normal");
        EXPECT_TRUE(backgroundRead(graph.compile({"both.lines", "shade.color"}), "gbuffer.normal"));
    }
}

// --- order -----------------------------------------------------------------------------------------------------------

TEST(GraphCompilerTest, LinearChainCompilesInOrder) {
    FakeGraph graph;
    graph.addPass("a", {}, {{"out"}});
    graph.addPass("b", {"a.out"}, {{"out"}});
    graph.addPass("c", {"b.out"}, {{"out"}});

    const Plan plan = graph.compile({"c.out"});
    EXPECT_EQ(passNames(plan), (Names{"a", "b", "c"}));
    EXPECT_TRUE(plan.culled.empty());
    ASSERT_EQ(plan.passes.size(), 3u);
    EXPECT_EQ(plan.passes[0].registrationIndex, 0u);
    EXPECT_EQ(plan.passes[2].registrationIndex, 2u);
    EXPECT_EQ(plan.passes[1].reads, (Names{"a.out"}));
    EXPECT_EQ(plan.passes[1].liveWrites, (Names{"b.out"}));
    EXPECT_EQ(plan.requested, (Names{"c.out"}));
}

TEST(GraphCompilerTest, LinearChainRegisteredBackwardsStillRunsWritersFirst) {
    FakeGraph graph;
    graph.addPass("c", {"b.out"}, {{"out"}});
    graph.addPass("b", {"a.out"}, {{"out"}});
    graph.addPass("a", {}, {{"out"}});

    const Plan plan = graph.compile({"c.out"});
    EXPECT_EQ(passNames(plan), (Names{"a", "b", "c"}));
    EXPECT_EQ(plan.passes[0].registrationIndex, 2u);
    EXPECT_EQ(plan.passes[2].registrationIndex, 0u);
}

TEST(GraphCompilerTest, DiamondBreaksTiesByRegistrationOrder) {
    FakeGraph graph;
    graph.addPass("top", {}, {{"out"}});
    graph.addPass("left", {"top.out"}, {{"out"}});
    graph.addPass("right", {"top.out"}, {{"out"}});
    graph.addPass("bottom", {"left.out", "right.out"}, {{"out"}});

    EXPECT_EQ(passNames(graph.compile({"bottom.out"})), (Names{"top", "left", "right", "bottom"}));
}

TEST(GraphCompilerTest, DiamondRegisteredInReverseBreaksTiesByRegistrationOrder) {
    FakeGraph graph;
    graph.addPass("bottom", {"left.out", "right.out"}, {{"out"}});
    graph.addPass("right", {"top.out"}, {{"out"}});
    graph.addPass("left", {"top.out"}, {{"out"}});
    graph.addPass("top", {}, {{"out"}});

    // 'right' and 'left' are both ready after 'top'; 'right' was registered first.
    EXPECT_EQ(passNames(graph.compile({"bottom.out"})), (Names{"top", "right", "left", "bottom"}));
}

TEST(GraphCompilerTest, HostPassesRunAfterTheGpuPassesTheirReadsAllow) {
    // Registered as the still graph registers them: a line layer on the host between two GPU passes.
    FakeGraph graph;
    graph.addPass("gbuffer", {}, {{"normal"}, {"depth"}});
    graph.addPass("contour", {"gbuffer.depth"}, {{"skeleton"}}).runOnHost();
    graph.addPass("shade", {"gbuffer.normal"}, {{"color"}});
    graph.addPass("silhouette", {"gbuffer.depth"}, {{"lines"}});
    graph.addPass("composite", {"shade.color", "contour.skeleton", "silhouette.lines"}, {{"final"}}).runOnHost();

    const Plan plan = graph.compile({"composite.final"});
    EXPECT_EQ(passNames(plan), (Names{"gbuffer", "shade", "silhouette", "contour", "composite"}));
    EXPECT_EQ(plan.hostTailStart(), 3u);
    EXPECT_TRUE(plan.passes[3].runsOnHost);
    EXPECT_FALSE(plan.passes[2].runsOnHost);
}

TEST(GraphCompilerTest, AHostPassAGpuPassReadsStaysBeforeItAndOutsideTheTail) {
    FakeGraph graph;
    graph.addPass("gbuffer", {}, {{"depth"}});
    graph.addPass("lines", {"gbuffer.depth"}, {{"mask"}}).runOnHost();
    graph.addPass("outline", {"lines.mask"}, {{"color"}});
    graph.addPass("composite", {"outline.color"}, {{"final"}}).runOnHost();

    const Plan plan = graph.compile({"composite.final"});
    EXPECT_EQ(passNames(plan), (Names{"gbuffer", "lines", "outline", "composite"}));
    EXPECT_EQ(plan.hostTailStart(), 3u) << "only the host passes after the last GPU pass are the tail";
}

TEST(GraphCompilerTest, APlanEndingOnTheGpuHasNoHostTail) {
    FakeGraph graph;
    graph.addPass("gbuffer", {}, {{"depth"}});
    graph.addPass("shade", {"gbuffer.depth"}, {{"color"}});
    const Plan plan = graph.compile({"shade.color"});
    EXPECT_EQ(plan.hostTailStart(), plan.passes.size());
}

TEST(GraphCompilerTest, IndependentPassesKeepRegistrationOrder) {
    FakeGraph graph;
    graph.addPass("z", {}, {{"out"}});
    graph.addPass("y", {}, {{"out"}});
    graph.addPass("x", {}, {{"out"}});

    // The request order does not matter, only registration.
    EXPECT_EQ(passNames(graph.compile({"x.out", "y.out", "z.out"})), (Names{"z", "y", "x"}));
}

TEST(GraphCompilerTest, SmallestReadyIndexWinsOverDepthFirst) {
    FakeGraph graph;
    graph.addPass("a", {}, {{"out"}});
    graph.addPass("b", {"a.out"}, {{"out"}});
    graph.addPass("c", {}, {{"out"}});
    graph.addPass("d", {"b.out", "c.out"}, {{"out"}});
    graph.addPass("e", {"a.out"}, {{"out"}});

    // After 'a': 'b' (1), 'c' (2), 'e' (4) are ready; 'd' (3) becomes ready after 'b' and 'c' and beats 'e'.
    EXPECT_EQ(passNames(graph.compile({"d.out", "e.out"})), (Names{"a", "b", "c", "d", "e"}));
}

TEST(GraphCompilerTest, RepeatedCompilesGiveTheSamePlan) {
    FakeGraph graph;
    addPipeline(graph);
    graph.addPass("debug", {"gbuffer.wVec"}, {{"heat"}});

    const Plan first = graph.compile({"composite.final", "gbuffer.viewVec"});
    for (int i = 0; i < 5; ++i) {
        const Plan again = graph.compile({"composite.final", "gbuffer.viewVec"});
        EXPECT_EQ(passNames(again), passNames(first));
        EXPECT_EQ(culledNames(again), culledNames(first));
        ASSERT_EQ(again.resources.size(), first.resources.size());
        for (std::size_t r = 0; r < first.resources.size(); ++r) {
            EXPECT_EQ(again.resources[r].name, first.resources[r].name);
            EXPECT_EQ(again.resources[r].firstUse, first.resources[r].firstUse);
            EXPECT_EQ(again.resources[r].lastUse, first.resources[r].lastUse);
            EXPECT_EQ(again.resources[r].readers, first.resources[r].readers);
        }
        EXPECT_EQ(again.describe(), first.describe());
    }
}

// --- culling ---------------------------------------------------------------------------------------------------------

TEST(GraphCompilerTest, RequestingAnUpstreamOutputCullsEverythingDownstream) {
    FakeGraph graph;
    addPipeline(graph);

    const Plan plan = graph.compile({"gbuffer.normal"});
    EXPECT_EQ(passNames(plan), (Names{"gbuffer"}));
    EXPECT_EQ(culledNames(plan), (Names{"lambert", "hull", "contours", "composite"}));

    EXPECT_EQ(findCulled(plan, "lambert")->reason,
              "no requested output depends on 'lambert.color' (read only by culled 'hull')");
    EXPECT_EQ(findCulled(plan, "contours")->reason,
              "no requested output depends on 'contours.lines' (read only by culled 'composite')");
    EXPECT_EQ(findCulled(plan, "composite")->reason,
              "no requested output depends on 'composite.final' (nothing reads it)");
    EXPECT_EQ(findCulled(plan, "hull")->reads, (Names{"lambert.color"}));
    EXPECT_EQ(findCulled(plan, "hull")->writes, (Names{"hull.color"}));
}

TEST(GraphCompilerTest, PassWritingNothingRequestedIsCulled) {
    FakeGraph graph;
    addPipeline(graph);

    const Plan plan = graph.compile({"hull.color"});
    EXPECT_EQ(passNames(plan), (Names{"gbuffer", "lambert", "hull"}));
    EXPECT_EQ(culledNames(plan), (Names{"contours", "composite"}));
    EXPECT_NE(findCulled(plan, "contours")->reason.find("'contours.lines'"), std::string::npos);
    EXPECT_EQ(plan.findResource("contours.lines"), nullptr);
}

TEST(GraphCompilerTest, PassWithOnlyAnUnreadOptionalOutputIsCulled) {
    FakeGraph graph;
    graph.addPass("gbuffer", {}, {{"normal"}});
    graph.addPass("debug", {"gbuffer.normal"}, {optionalWrite("heat")});

    const Plan plan = graph.compile({"gbuffer.normal"});
    EXPECT_EQ(passNames(plan), (Names{"gbuffer"}));
    ASSERT_EQ(plan.culled.size(), 1u);
    EXPECT_EQ(plan.culled[0].name, "debug");
    EXPECT_EQ(plan.culled[0].reason, "no requested output depends on 'debug.heat' (nothing reads it)");
}

TEST(GraphCompilerTest, CulledReasonListsEveryOutput) {
    FakeGraph graph;
    graph.addPass("source", {}, {{"out"}});
    graph.addPass("split", {"source.out"}, {{"low"}, {"mid"}, optionalWrite("high")});

    const Plan plan = graph.compile({"source.out"});
    ASSERT_EQ(plan.culled.size(), 1u);
    EXPECT_EQ(plan.culled[0].reason,
              "no requested output depends on 'split.low', 'split.mid' or 'split.high' (nothing reads them)");
}

TEST(GraphCompilerTest, PassWithNoWritesAndNoSideEffectIsCulled) {
    FakeGraph graph;
    graph.addPass("source", {}, {{"out"}});
    graph.addPass("sink", {"source.out"}, {});

    const Plan plan = graph.compile({"source.out"});
    EXPECT_EQ(passNames(plan), (Names{"source"}));
    ASSERT_EQ(plan.culled.size(), 1u);
    EXPECT_EQ(plan.culled[0].reason, "writes nothing and has no side effect");
}

TEST(GraphCompilerTest, CulledPassesAreListedInRegistrationOrder) {
    FakeGraph graph;
    graph.addPass("c", {"b.out"}, {{"out"}});
    graph.addPass("a", {}, {{"out"}});
    graph.addPass("b", {"a.out"}, {{"out"}});
    graph.addPass("keep", {}, {{"out"}});

    const Plan plan = graph.compile({"keep.out"});
    EXPECT_EQ(culledNames(plan), (Names{"c", "a", "b"}));
}

// --- optional outputs ------------------------------------------------------------------------------------------------

TEST(GraphCompilerTest, OptionalOutputIsLiveOnlyWhenRead) {
    FakeGraph graph;
    addPipeline(graph);
    graph.addPass("specular", {"gbuffer.normal", "gbuffer.viewVec"}, {{"color", Need::Required, kColorDesc}});

    const Plan plan = graph.compile({"specular.color"});
    const PlannedPass* gbuffer = plan.findPass("gbuffer");
    ASSERT_NE(gbuffer, nullptr);
    EXPECT_EQ(gbuffer->liveWrites, (Names{"gbuffer.normal", "gbuffer.depth", "gbuffer.viewVec"}));
    EXPECT_EQ(gbuffer->deadOptionalWrites, (Names{"gbuffer.wVec"}));
    ASSERT_NE(plan.findResource("gbuffer.viewVec"), nullptr);
    EXPECT_EQ(plan.findResource("gbuffer.viewVec")->readers, (Names{"specular"}));
    EXPECT_EQ(plan.findResource("gbuffer.wVec"), nullptr);
}

TEST(GraphCompilerTest, OptionalOutputIsLiveWhenRequested) {
    FakeGraph graph;
    addPipeline(graph);

    const Plan plan = graph.compile({"lambert.color", "gbuffer.wVec"});
    const PlannedPass* gbuffer = plan.findPass("gbuffer");
    ASSERT_NE(gbuffer, nullptr);
    EXPECT_EQ(gbuffer->liveWrites, (Names{"gbuffer.normal", "gbuffer.depth", "gbuffer.wVec"}));
    EXPECT_EQ(gbuffer->deadOptionalWrites, (Names{"gbuffer.viewVec"}));
    ASSERT_NE(plan.findResource("gbuffer.wVec"), nullptr);
    EXPECT_TRUE(plan.findResource("gbuffer.wVec")->requested);
    EXPECT_TRUE(plan.findResource("gbuffer.wVec")->readers.empty());
}

TEST(GraphCompilerTest, OptionalOutputReadOnlyByACulledPassIsDead) {
    FakeGraph graph;
    addPipeline(graph);
    graph.addPass("specular", {"gbuffer.viewVec"}, {{"color"}});

    const Plan plan = graph.compile({"lambert.color"});
    EXPECT_EQ(plan.findPass("gbuffer")->deadOptionalWrites, (Names{"gbuffer.viewVec", "gbuffer.wVec"}));
    EXPECT_EQ(plan.findResource("gbuffer.viewVec"), nullptr);
    EXPECT_NE(findCulled(plan, "specular"), nullptr);
}

TEST(GraphCompilerTest, RequiredWritesOfALivePassAreAlwaysLive) {
    FakeGraph graph;
    addPipeline(graph);

    // Nothing live reads 'gbuffer.depth' (contours is culled), but the G-buffer computes it anyway.
    const Plan plan = graph.compile({"lambert.color"});
    const PlannedResource* depth = plan.findResource("gbuffer.depth");
    ASSERT_NE(depth, nullptr);
    EXPECT_EQ(depth->writer, "gbuffer");
    EXPECT_TRUE(depth->readers.empty());
    EXPECT_FALSE(depth->requested);
    EXPECT_EQ(depth->firstUse, 0u);
    EXPECT_EQ(depth->lastUse, 0u);
    EXPECT_EQ(plan.findPass("gbuffer")->liveWrites, (Names{"gbuffer.normal", "gbuffer.depth"}));
}

TEST(GraphCompilerTest, PassLiveOnlyForAnOptionalOutputStillComputesItsRequiredOnes) {
    FakeGraph graph;
    graph.addPass("gbuffer", {}, {{"normal"}, optionalWrite("wVec")});
    graph.addPass("hull", {"gbuffer.wVec"}, {{"color"}});

    const Plan plan = graph.compile({"hull.color"});
    EXPECT_EQ(plan.findPass("gbuffer")->liveWrites, (Names{"gbuffer.normal", "gbuffer.wVec"}));
    EXPECT_TRUE(plan.findPass("gbuffer")->deadOptionalWrites.empty());
}

// --- lifetimes -------------------------------------------------------------------------------------------------------

TEST(GraphCompilerTest, LifetimesRunFromWriterToLastReader) {
    FakeGraph graph;
    addPipeline(graph);

    const Plan plan = graph.compile({"composite.final"});
    ASSERT_EQ(passNames(plan), (Names{"gbuffer", "lambert", "hull", "contours", "composite"}));

    struct Expected {
        const char* name;
        std::size_t firstUse, lastUse;
        Names readers;
    };
    const Expected expected[] = {
        {"gbuffer.depth", 0, 3, {"contours"}},   {"gbuffer.normal", 0, 3, {"lambert", "contours"}},
        {"lambert.color", 1, 2, {"hull"}},       {"hull.color", 2, 4, {"composite"}},
        {"contours.lines", 3, 4, {"composite"}}, {"composite.final", 4, 4, {}},
    };
    ASSERT_EQ(plan.resources.size(), std::size(expected));
    for (std::size_t i = 0; i < plan.resources.size(); ++i) {
        SCOPED_TRACE(expected[i].name);
        const PlannedResource& resource = plan.resources[i];
        EXPECT_EQ(resource.name, expected[i].name);
        EXPECT_EQ(resource.firstUse, expected[i].firstUse);
        EXPECT_EQ(resource.lastUse, expected[i].lastUse);
        EXPECT_EQ(resource.readers, expected[i].readers);
        EXPECT_EQ(resource.requested, resource.name == "composite.final");
    }
    EXPECT_EQ(plan.findResource("gbuffer.normal")->desc, kNormalDesc);
    EXPECT_EQ(plan.findResource("contours.lines")->desc, kLinesDesc);
    EXPECT_EQ(plan.findResource("hull.color")->writer, "hull");
}

TEST(GraphCompilerTest, RequestedResourceLivesToTheEnd) {
    FakeGraph graph;
    addPipeline(graph);

    const Plan plan = graph.compile({"composite.final", "gbuffer.normal", "lambert.color"});
    const PlannedResource* normal = plan.findResource("gbuffer.normal");
    ASSERT_NE(normal, nullptr);
    EXPECT_TRUE(normal->requested);
    EXPECT_EQ(normal->firstUse, 0u);
    EXPECT_EQ(normal->lastUse, 4u);
    EXPECT_EQ(plan.findResource("lambert.color")->lastUse, 4u);
    // Not requested: still ends at its last reader.
    EXPECT_EQ(plan.findResource("gbuffer.depth")->lastUse, 3u);
}

TEST(GraphCompilerTest, ReadersAreListedInPlanOrder) {
    FakeGraph graph;
    graph.addPass("late", {"src.out", "early.out"}, {{"out"}});
    graph.addPass("early", {"src.out"}, {{"out"}});
    graph.addPass("src", {}, {{"out"}});

    const Plan plan = graph.compile({"late.out"});
    EXPECT_EQ(passNames(plan), (Names{"src", "early", "late"}));
    EXPECT_EQ(plan.findResource("src.out")->readers, (Names{"early", "late"}));
    EXPECT_EQ(plan.findResource("src.out")->lastUse, 2u);
}

TEST(GraphCompilerTest, RepeatedReadsAreRecordedOnce) {
    FakeGraph graph;
    graph.addPass("src", {}, {{"out"}});
    graph.addPass("dst", {"src.out", "src.out"}, {{"out"}});

    const Plan plan = graph.compile({"dst.out"});
    EXPECT_EQ(plan.findPass("dst")->reads, (Names{"src.out"}));
    EXPECT_EQ(plan.findResource("src.out")->readers, (Names{"dst"}));
}

// --- side effects ----------------------------------------------------------------------------------------------------

TEST(GraphCompilerTest, SideEffectPassIsNeverCulledAndItsInputsAreLive) {
    FakeGraph graph;
    addPipeline(graph);
    graph.addPass("export", {"lambert.color", "gbuffer.viewVec"}, {}, true);

    const Plan plan = graph.compile({"gbuffer.normal"});
    EXPECT_EQ(passNames(plan), (Names{"gbuffer", "lambert", "export"}));
    EXPECT_TRUE(plan.findPass("export")->hasSideEffect);
    EXPECT_FALSE(plan.findPass("lambert")->hasSideEffect);
    EXPECT_EQ(plan.findResource("lambert.color")->readers, (Names{"export"}));
    EXPECT_EQ(plan.findResource("lambert.color")->lastUse, 2u);
    ASSERT_NE(plan.findResource("gbuffer.viewVec"), nullptr);
    EXPECT_EQ(culledNames(plan), (Names{"hull", "contours", "composite"}));
}

TEST(GraphCompilerTest, SideEffectAloneNeedsNoRequest) {
    FakeGraph graph;
    graph.addPass("src", {}, {{"out"}, optionalWrite("extra")});
    graph.addPass("log", {"src.out"}, {optionalWrite("stats")}, true);
    graph.addPass("unused", {}, {{"out"}});

    const Plan plan = graph.compile({});
    EXPECT_EQ(passNames(plan), (Names{"src", "log"}));
    EXPECT_EQ(culledNames(plan), (Names{"unused"}));
    EXPECT_TRUE(plan.requested.empty());
    // A side effect keeps the pass, not its optional outputs.
    EXPECT_TRUE(plan.findPass("log")->liveWrites.empty());
    EXPECT_EQ(plan.findPass("log")->deadOptionalWrites, (Names{"log.stats"}));
    EXPECT_EQ(plan.findPass("src")->deadOptionalWrites, (Names{"src.extra"}));
}

// --- errors ----------------------------------------------------------------------------------------------------------

TEST(GraphCompilerTest, TwoWritersOfOneResourceNameBothPasses) {
    FakeGraph graph;
    graph.addPass("gbuffer", {}, {{"normal"}});
    graph.addPass("cel", {"gbuffer.normal"}, {{"color"}});
    graph.addPass("gbuffer", {}, {{"normal"}, {"depth"}});

    EXPECT_EQ(compileProblems(graph, {"cel.color"}),
              (Names{"pass name 'gbuffer' is used by 2 passes (#0 and #2); pass names must be unique",
                     "resource 'gbuffer.normal' has two writers: 'gbuffer' and 'gbuffer' (passes #0, #2)"}));
}

TEST(GraphCompilerTest, DuplicatePassNamesAreAnError) {
    FakeGraph graph;
    graph.addPass("src", {}, {{"out"}});
    graph.addPass("cel", {"src.out"}, {{"color"}});
    graph.addPass("cel", {"src.out"}, {{"shade"}});
    graph.addPass("cel", {"src.out"}, {{"mask"}});

    EXPECT_EQ(compileProblems(graph, {"cel.color"}),
              (Names{"pass name 'cel' is used by 3 passes (#1, #2 and #3); pass names must be unique"}));
}

TEST(GraphCompilerTest, ReadOfAnUnwrittenResourceSuggestsACloseName) {
    FakeGraph graph;
    addPipeline(graph);
    graph.addPass("cel", {"gbuffer.normals"}, {{"color"}});

    EXPECT_EQ(compileProblems(graph, {"cel.color"}),
              (Names{"pass 'cel' reads 'gbuffer.normals' but no pass writes it (did you mean 'gbuffer.normal'?)"}));
}

TEST(GraphCompilerTest, ReadOfAnUnwrittenResourceSuggestsTheSameFieldElsewhere) {
    FakeGraph graph;
    addPipeline(graph);
    graph.addPass("cel", {"geometry.depth"}, {{"color"}});

    EXPECT_EQ(compileProblems(graph, {"cel.color"}),
              (Names{"pass 'cel' reads 'geometry.depth' but no pass writes it (did you mean 'gbuffer.depth'?)"}));
}

TEST(GraphCompilerTest, ReadOfAnUnwrittenResourceWithNothingSimilarHasNoSuggestion) {
    FakeGraph graph;
    addPipeline(graph);
    graph.addPass("cel", {"shademap.ramp"}, {{"color"}});

    EXPECT_EQ(compileProblems(graph, {"cel.color"}), (Names{"pass 'cel' reads 'shademap.ramp' but no pass writes it"}));
}

TEST(GraphCompilerTest, BrokenReadFailsEvenWhenItsPassWouldBeCulled) {
    FakeGraph graph;
    addPipeline(graph);
    graph.addPass("unused", {"missing.thing"}, {{"out"}});

    const Names problems = compileProblems(graph, {"lambert.color"});
    ASSERT_EQ(problems.size(), 1u);
    EXPECT_EQ(problems[0], "pass 'unused' reads 'missing.thing' but no pass writes it");
}

TEST(GraphCompilerTest, RequestedResourceNobodyWritesIsAnError) {
    FakeGraph graph;
    addPipeline(graph);

    EXPECT_EQ(compileProblems(graph, {"lambert.colour", "nowhere.at.all"}),
              (Names{"requested resource 'lambert.colour' is not written by any pass (did you mean 'lambert.color'?)",
                     "requested resource 'nowhere.at.all' is not written by any pass"}));
}

TEST(GraphCompilerTest, ThreePassCycleIsNamedInOrder) {
    FakeGraph graph;
    graph.addPass("src", {}, {{"out"}});
    graph.addPass("a", {"src.out", "c.out"}, {{"out"}});
    graph.addPass("b", {"a.out"}, {{"out"}});
    graph.addPass("c", {"b.out"}, {{"out"}});
    graph.addPass("sink", {"c.out"}, {{"out"}});

    std::string message;
    EXPECT_EQ(compileProblems(graph, {"sink.out"}, &message), (Names{"cycle: 'a' -> 'b' -> 'c' -> 'a'"}));
    EXPECT_NE(message.find("cycle: 'a' -> 'b' -> 'c' -> 'a'"), std::string::npos);
}

TEST(GraphCompilerTest, CycleStartsAtItsFirstRegisteredPass) {
    FakeGraph graph;
    graph.addPass("c", {"b.out"}, {{"out"}});
    graph.addPass("a", {"c.out"}, {{"out"}});
    graph.addPass("b", {"a.out"}, {{"out"}});

    EXPECT_EQ(compileProblems(graph, {"c.out"}), (Names{"cycle: 'c' -> 'a' -> 'b' -> 'c'"}));
}

TEST(GraphCompilerTest, SelfCycleAndTwoSeparateCyclesAreEachReported) {
    FakeGraph graph;
    graph.addPass("self", {"self.out"}, {{"out"}});
    graph.addPass("x", {"y.out"}, {{"out"}});
    graph.addPass("y", {"x.out"}, {{"out"}});

    EXPECT_EQ(compileProblems(graph, {"self.out", "y.out"}),
              (Names{"cycle: 'self' -> 'self'", "cycle: 'x' -> 'y' -> 'x'"}));
}

TEST(GraphCompilerTest, CycleReportsTheShortestLoop) {
    FakeGraph graph;
    // a -> b -> c -> d -> a, with the shortcut b -> a.
    graph.addPass("a", {"d.out", "b.out"}, {{"out"}});
    graph.addPass("b", {"a.out"}, {{"out"}});
    graph.addPass("c", {"b.out"}, {{"out"}});
    graph.addPass("d", {"c.out"}, {{"out"}});

    EXPECT_EQ(compileProblems(graph, {"d.out"}), (Names{"cycle: 'a' -> 'b' -> 'a'"}));
}

TEST(GraphCompilerTest, WritingAFieldWithADotIsAnError) {
    FakeGraph graph;
    graph.addPass("cel", {}, {{"color"}, {"hull.color"}});

    EXPECT_EQ(compileProblems(graph, {"cel.color"}),
              (Names{"pass 'cel' writes field 'hull.color', which has a '.': a pass writes only its own fields "
                     "('cel.<field>')"}));
}

TEST(GraphCompilerTest, WritingAnEmptyFieldIsAnError) {
    FakeGraph graph;
    graph.addPass("cel", {}, {{"color"}, {""}});

    EXPECT_EQ(compileProblems(graph, {"cel.color"}), (Names{"pass 'cel' writes a field with an empty name"}));
}

TEST(GraphCompilerTest, WritingAFieldTwiceIsAnError) {
    FakeGraph graph;
    graph.addPass("gbuffer", {}, {{"normal"}, {"depth"}, optionalWrite("normal")});

    EXPECT_EQ(compileProblems(graph, {"gbuffer.depth"}), (Names{"pass 'gbuffer' writes 'gbuffer.normal' twice"}));
}

TEST(GraphCompilerTest, BadPassNamesAreErrors) {
    FakeGraph graph;
    graph.addPass("", {}, {{"out"}});
    graph.addPass("post.fx", {}, {{"out"}});
    graph.addPass("ok", {}, {{"out"}});

    EXPECT_EQ(compileProblems(graph, {"ok.out"}),
              (Names{"pass #0 has an empty name",
                     "pass 'post.fx' has a '.' in its name; '.' separates a pass from its field in resource names"}));
}

TEST(GraphCompilerTest, NullPassIsAnError) {
    FakeGraph graph;
    graph.addPass("ok", {}, {{"out"}});
    std::vector<const Pass*> passes = graph.passes();
    passes.push_back(nullptr);

    try {
        compile(passes, {"ok.out"});
        FAIL() << "compile() accepted a null pass";
    } catch (const GraphError& error) {
        EXPECT_EQ(error.problems(), (Names{"pass #1 is null"}));
    }
}

TEST(GraphCompilerTest, NothingRequestedAndNoSideEffectIsAnError) {
    FakeGraph graph;
    addPipeline(graph);

    EXPECT_EQ(compileProblems(graph, {}),
              (Names{"nothing is requested and no pass has a side effect, so the plan would be empty"}));
    EXPECT_EQ(compileProblems(FakeGraph(), {}).size(), 1u);
}

TEST(GraphCompilerTest, ThreeDifferentProblemsAreReportedInOneError) {
    FakeGraph graph;
    graph.addPass("gbuffer", {}, {{"normal"}, {"hull.mask"}});              // 1: writes outside its namespace
    graph.addPass("cel", {"gbuffer.normal", "shademap.ramp"}, {{"color"}}); // 2: reads what nobody writes
    graph.addPass("hull", {"cel.color", "outline.lines"}, {{"color"}});
    graph.addPass("outline", {"hull.color"}, {{"lines"}}); // 3: hull -> outline -> hull

    try {
        graph.compile({"hull.color"});
        FAIL() << "compile() accepted a graph with three problems";
    } catch (const GraphError& error) {
        const std::string message = error.what();
        ASSERT_EQ(error.problems().size(), 3u) << message;
        EXPECT_EQ(message.rfind("GraphCompiler::compile(): 3 problem(s) in the render graph:\n  - ", 0), 0u) << message;
        for (const std::string& problem : error.problems())
            EXPECT_NE(message.find("\n  - " + problem), std::string::npos) << problem;
        EXPECT_NE(message.find("'hull.mask'"), std::string::npos);
        EXPECT_NE(message.find("pass 'cel' reads 'shademap.ramp' but no pass writes it"), std::string::npos);
        EXPECT_NE(message.find("cycle: 'hull' -> 'outline' -> 'hull'"), std::string::npos);
    }
}

TEST(GraphCompilerTest, ErrorMessageListsOneProblemPerLine) {
    FakeGraph graph;
    graph.addPass("a", {"x.in"}, {{"out"}});

    std::string message;
    const Names problems = compileProblems(graph, {"a.out", "b.result"}, &message);
    ASSERT_EQ(problems.size(), 2u);
    EXPECT_EQ(message, "GraphCompiler::compile(): 2 problem(s) in the render graph:\n"
                       "  - pass 'a' reads 'x.in' but no pass writes it\n"
                       "  - requested resource 'b.result' is not written by any pass");
}

TEST(GraphCompilerTest, ProblemsAreReportedInTheSameOrderEveryTime) {
    FakeGraph graph;
    graph.addPass("b", {"zz.out", "a.out"}, {{"out"}, {"bad.field"}});
    graph.addPass("a", {"b.out", "yy.out"}, {{"out"}});
    graph.addPass("a", {}, {{"other"}});

    const Names first = compileProblems(graph, {"a.out", "q.out"});
    ASSERT_EQ(first.size(), 6u);
    for (int i = 0; i < 5; ++i) EXPECT_EQ(compileProblems(graph, {"a.out", "q.out"}), first);
    // Names, then writes, then writers, then reads (registration order), then requests, then cycles.
    EXPECT_NE(first[0].find("pass name 'a'"), std::string::npos);
    EXPECT_NE(first[1].find("'bad.field'"), std::string::npos);
    EXPECT_NE(first[2].find("'zz.out'"), std::string::npos);
    EXPECT_NE(first[3].find("'yy.out'"), std::string::npos);
    EXPECT_NE(first[4].find("'q.out'"), std::string::npos);
    EXPECT_EQ(first[5], "cycle: 'b' -> 'a' -> 'b'");
}

// --- the null executor -----------------------------------------------------------------------------------------------

TEST(GraphCompilerTest, NullExecutorRunsExactlyThePlannedPassesInOrder) {
    FakeGraph graph;
    addPipeline(graph);
    graph.addPass("unused", {"gbuffer.depth"}, {{"out"}});

    const Plan plan = graph.compile({"hull.color"});
    const ExecutionLog& log = graph.execute(plan);
    EXPECT_EQ(log.executed, (Names{"gbuffer", "lambert", "hull"}));
    EXPECT_EQ(log.executed, passNames(plan));
    EXPECT_EQ(culledNames(plan), (Names{"contours", "composite", "unused"}));
    for (const CulledPass& culled : plan.culled)
        EXPECT_EQ(log.liveFields.count(culled.name), 0u) << "'" << culled.name << "' ran although it was culled";
}

TEST(GraphCompilerTest, NullExecutorSeesOnlyLiveFields) {
    FakeGraph graph;
    addPipeline(graph);
    graph.addPass("specular", {"gbuffer.viewVec"}, {{"highlight"}, optionalWrite("mask")});

    const Plan plan = graph.compile({"composite.final", "specular.highlight"});
    const ExecutionLog& log = graph.execute(plan);
    EXPECT_EQ(log.executed, (Names{"gbuffer", "lambert", "hull", "contours", "composite", "specular"}));
    EXPECT_EQ(log.liveFields.at("gbuffer"), (Names{"normal", "depth", "viewVec"}));
    EXPECT_EQ(log.liveFields.at("specular"), (Names{"highlight"}));
    EXPECT_EQ(log.liveFields.at("composite"), (Names{"final"}));
}

} // namespace
} // namespace inkgraph::test
