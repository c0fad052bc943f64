// Typed CPU object resources, declared working memory and compile data (a second round of declarations that knows
// what runs anyway), on passes made of lambdas: no GL.
#include "graph/GraphCompiler.h"

#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <vector>

namespace inkgraph::test {
namespace {

/** A pass whose declare() is a function of its builder (and so of the compile data it asks for). */
class LambdaPass final : public Pass {
public:
    LambdaPass(std::string name, std::function<void(PassBuilder&)> declare)
        : mName(std::move(name)), mDeclare(std::move(declare)) {}
    std::string_view name() const override { return mName; }
    void declare(PassBuilder& builder) const override { mDeclare(builder); }

private:
    std::string mName;
    std::function<void(PassBuilder&)> mDeclare;
};

ObjectDesc skeletonDesc(int scale = 1) {
    ObjectDesc desc;
    desc.type = "line-skeleton";
    desc.bytesPerPixel = 2;
    desc.scale = scale;
    desc.hasPicture = true;
    return desc;
}

bool mentions(const GraphError& error, const std::string& text) {
    return std::string(error.what()).find(text) != std::string::npos;
}

TEST(ObjectResources, AreCulledOrderedAndDescribedLikeTextures) {
    LambdaPass source("source", [](PassBuilder& b) { b.write("depth", {Format::R32F}); });
    LambdaPass layer("contour", [](PassBuilder& b) {
        b.read("source.depth");
        b.writeObject("skeleton", skeletonDesc(2));
        b.scratch(14, 2);
    });
    LambdaPass unused("crease", [](PassBuilder& b) {
        b.read("source.depth");
        b.writeObject("skeleton", skeletonDesc());
    });
    LambdaPass strokes("strokes", [](PassBuilder& b) {
        b.readObject("contour.skeleton", "line-skeleton");
        b.write("contour", {Format::R8});
    });
    const Plan plan = compile({&source, &layer, &unused, &strokes}, {"strokes.contour"});
    ASSERT_EQ(plan.passes.size(), 3u);
    EXPECT_EQ(plan.passes[1].name, "contour");
    ASSERT_EQ(plan.culled.size(), 1u);
    EXPECT_EQ(plan.culled[0].name, "crease");
    const PlannedResource* skeleton = plan.findResource("contour.skeleton");
    ASSERT_NE(skeleton, nullptr);
    EXPECT_EQ(skeleton->kind, ResourceKind::Object);
    EXPECT_EQ(skeleton->object.type, "line-skeleton");
    EXPECT_EQ(skeleton->object.scale, 2);
    EXPECT_EQ(skeleton->readers, (std::vector<std::string>{"strokes"}));
    EXPECT_TRUE(plan.isObject("contour.skeleton"));
    EXPECT_FALSE(plan.isObject("source.depth"));
    // The pass's declared working memory reaches the plan, for the memory budget.
    ASSERT_EQ(plan.passes[1].scratch.size(), 1u);
    EXPECT_EQ(plan.passes[1].scratch[0].bytesPerPixel, 14u);
    EXPECT_EQ(plan.passes[1].scratch[0].scale, 2);
    EXPECT_NE(plan.describe().find("contour.skeleton(line-skeleton x2)"), std::string::npos) << plan.describe();
}

TEST(ObjectResources, ACoarserFieldAndItsSkeletonCarryTheirDivisor) {
    // A kernel's field sampled at half the frame's sides, and the skeleton found on it: the plan keeps the divisor
    // and says it, so the executor sizes them and the memory budget charges a quarter of the frame.
    LambdaPass source("coarse", [](PassBuilder& b) { b.write("depth", {Format::R32F, 1, 1, 2}); });
    LambdaPass layer("suggestive", [](PassBuilder& b) {
        b.read("coarse.depth");
        ObjectDesc desc = skeletonDesc();
        desc.divisor = 2;
        b.writeObject("skeleton", desc);
        b.scratch(14, 1, 2);
    });
    const Plan plan = compile({&source, &layer}, {"suggestive.skeleton"});
    ASSERT_EQ(plan.passes.size(), 2u);
    EXPECT_EQ(plan.findResource("coarse.depth")->desc.divisor, 2);
    EXPECT_EQ(plan.findResource("suggestive.skeleton")->object.divisor, 2);
    EXPECT_EQ(plan.findResource("suggestive.skeleton")->desc.divisor, 2) << "its picture is at the same size";
    EXPECT_EQ(plan.passes[1].scratch[0].divisor, 2);
    EXPECT_NE(plan.describe().find("coarse.depth(r32f /2)"), std::string::npos) << plan.describe();
    EXPECT_NE(plan.describe().find("suggestive.skeleton(line-skeleton /2)"), std::string::npos) << plan.describe();
}

TEST(ObjectResources, AReaderNamingAnotherTypeOrKindIsACompileError) {
    LambdaPass layer("contour", [](PassBuilder& b) { b.writeObject("skeleton", skeletonDesc()); });
    LambdaPass texture("band", [](PassBuilder& b) { b.write("lines", {Format::R8}); });
    LambdaPass wrongType("a", [](PassBuilder& b) {
        b.readObject("contour.skeleton", "drawn-strokes");
        b.write("out", {Format::R8});
    });
    LambdaPass objectAsTexture("b", [](PassBuilder& b) {
        b.read("contour.skeleton");
        b.write("out", {Format::R8});
    });
    LambdaPass textureAsObject("c", [](PassBuilder& b) {
        b.readObject("band.lines", "line-skeleton");
        b.write("out", {Format::R8});
    });
    try {
        compile({&layer, &texture, &wrongType, &objectAsTexture, &textureAsObject}, {"a.out"});
        FAIL() << "compiled a graph whose readers name the wrong kinds";
    } catch (const GraphError& error) {
        EXPECT_EQ(error.problems().size(), 3u) << error.what();
        EXPECT_TRUE(mentions(error, "pass 'a' reads 'contour.skeleton' as a 'drawn-strokes' object, but 'contour' "
                                    "writes a 'line-skeleton'"))
            << error.what();
        EXPECT_TRUE(mentions(error, "pass 'b' reads 'contour.skeleton' as a texture, but it is a 'line-skeleton'"))
            << error.what();
        EXPECT_TRUE(mentions(error, "pass 'c' reads 'band.lines' as a 'line-skeleton' object, but it is a texture"))
            << error.what();
    }
}

/** The still graph's question, in small: shading reads the G-buffer's normal only when the G-buffer runs anyway. */
struct ShadingGraph {
    LambdaPass gbuffer{"gbuffer", [](PassBuilder& b) {
                           b.write("normal", {Format::RGBA32F}, Need::Optional);
                           b.write("depth", {Format::R32F}, Need::Optional);
                       }};
    LambdaPass shade{"shade", [](PassBuilder& b) {
                         if (b.runsAnyway("gbuffer")) b.read("gbuffer.normal"); // deferred
                         b.write("color", {Format::RGBA8});
                     }};
    LambdaPass lines{"lines", [](PassBuilder& b) {
                         b.read("gbuffer.depth");
                         b.write("mask", {Format::R8});
                     }};
    LambdaPass composite;
    explicit ShadingGraph(bool drawLines)
        : composite("composite", [drawLines](PassBuilder& b) {
              b.read("shade.color");
              if (drawLines) b.read("lines.mask");
              b.write("final", {Format::RGBA8});
          }) {}
    std::vector<const Pass*> passes() const { return {&gbuffer, &shade, &lines, &composite}; }
};

bool reads(const Plan& plan, const std::string& pass, const std::string& resource) {
    const PlannedPass* planned = plan.findPass(pass);
    return planned && std::find(planned->reads.begin(), planned->reads.end(), resource) != planned->reads.end();
}

TEST(CompileData, APassReadsWhatRunsAnywayWithoutMakingItRun) {
    const ShadingGraph withLines(true);
    const Plan deferred = compile(withLines.passes(), {"composite.final"});
    EXPECT_TRUE(reads(deferred, "shade", "gbuffer.normal"));
    EXPECT_EQ(deferred.findPass("gbuffer")->liveWrites, (std::vector<std::string>{"gbuffer.normal", "gbuffer.depth"}));

    const ShadingGraph withoutLines(false);
    const Plan forward = compile(withoutLines.passes(), {"composite.final"});
    EXPECT_FALSE(reads(forward, "shade", "gbuffer.normal"));
    EXPECT_EQ(forward.findPass("gbuffer"), nullptr) << "asking what runs anyway must not make the G-buffer run";
}

TEST(CompileData, DecidingRequestsKeepAnExtraRequestFromChangingTheDecision) {
    const ShadingGraph withoutLines(false);
    // Requested on its own, the G-buffer's depth makes it run, and shading would go deferred...
    const Plan decidedByAll = compile(withoutLines.passes(), {"composite.final", "gbuffer.depth"});
    EXPECT_TRUE(reads(decidedByAll, "shade", "gbuffer.normal"));
    // ...unless the decision is taken for the final picture alone, as the still graph does.
    const Plan decidedByFinal =
        compile(withoutLines.passes(), {"composite.final", "gbuffer.depth"}, {"composite.final"});
    EXPECT_FALSE(reads(decidedByFinal, "shade", "gbuffer.normal"));
    EXPECT_NE(decidedByFinal.findResource("gbuffer.depth"), nullptr);
}

TEST(CompileData, LiveFieldsAnywayNameTheFirstRoundsLiveFields) {
    std::vector<std::string> seen;
    LambdaPass gbuffer("gbuffer", [](PassBuilder& b) {
        b.write("normal", {Format::RGBA32F}, Need::Optional);
        b.write("depth", {Format::R32F}, Need::Optional);
    });
    LambdaPass lines("lines", [](PassBuilder& b) {
        b.read("gbuffer.depth");
        b.write("mask", {Format::R8});
    });
    LambdaPass asker("asker", [&seen](PassBuilder& b) {
        seen = b.liveFieldsAnyway("gbuffer");
        b.read("lines.mask");
        b.write("out", {Format::R8});
    });
    compile({&gbuffer, &lines, &asker}, {"asker.out"});
    EXPECT_EQ(seen, (std::vector<std::string>{"depth"})); // the second round's answer: normal is not live
}

} // namespace
} // namespace inkgraph::test

namespace inkgraph::test {
namespace {

TEST(SceneImports, OnlyTheLivePassesImportsAreInThePlanEachOnce) {
    LambdaPass gbuffer("gbuffer", [](PassBuilder& b) {
        b.import("scene.meshes");
        b.write("depth", {Format::R32F});
    });
    LambdaPass edges("mesh-edges", [](PassBuilder& b) {
        b.import("scene.meshes");
        b.import("scene.edge-adjacency");
        b.import("scene.edge-adjacency"); // declared twice, listed once
        b.write("crease", {Format::R8});
    });
    LambdaPass hull("silhouette", [](PassBuilder& b) {
        b.import("scene.hulls");
        b.write("lines", {Format::R8});
    });
    const Plan plan = compile({&gbuffer, &edges, &hull}, {"gbuffer.depth", "mesh-edges.crease"});
    EXPECT_EQ(plan.findPass("mesh-edges")->imports, (std::vector<std::string>{"scene.meshes", "scene.edge-adjacency"}));
    // The culled silhouette's hulls are not derived.
    EXPECT_EQ(plan.imports(), (std::vector<std::string>{"scene.meshes", "scene.edge-adjacency"}));
    EXPECT_NE(plan.describe().find("imports: scene.meshes scene.edge-adjacency"), std::string::npos) << plan.describe();
}

} // namespace
} // namespace inkgraph::test
