// Command-line parsing: defaults, values, and a clear UsageError for every malformed flag. No GL.
#include "app/Options.h"
#include "app/Render.h"

#include <gtest/gtest.h>

namespace inkgraph {
namespace {

RenderOptions parse(std::vector<std::string> arguments) { return parseRenderOptions(arguments); }

std::string usageMessage(std::vector<std::string> arguments) {
    try {
        parseRenderOptions(arguments);
    } catch (const UsageError& error) {
        return error.what();
    }
    return "(no error)";
}

TEST(Options, Defaults) {
    const RenderOptions options = parse({"model.obj", "-o", "out.png"});
    EXPECT_EQ(options.modelPath, "model.obj");
    EXPECT_EQ(options.outputPath, "out.png");
    EXPECT_EQ(options.width, 1024);
    EXPECT_EQ(options.height, 1024);
    EXPECT_FALSE(options.up.has_value());
    EXPECT_FALSE(options.fovYDegrees.has_value());
    EXPECT_EQ(options.shading, ShadingMode::Lambert);
    EXPECT_TRUE(options.lines.empty());
    EXPECT_FALSE(options.printPlan);
}

TEST(Options, EveryValue) {
    const RenderOptions options =
        parse({"-o", "a.png", "m.glb", "--size", "640x480", "--eye", "1,2,3", "--target", "0,0.5,-1e-3", "--up",
               "0,0,1", "--fov", "50", "--light", "0,0,2", "--shading", "none", "--lines", "none", "--dump", "d",
               "--stats", "s.json", "--print-plan", "--request", "gbuffer.*,gbuffer.depth", "--background",
               "0,0.5,1", "--egl-platform", "surfaceless", "-q"});
    EXPECT_EQ(options.width, 640);
    EXPECT_EQ(options.height, 480);
    EXPECT_EQ(*options.eye, glm::dvec3(1, 2, 3));
    EXPECT_EQ(*options.target, glm::dvec3(0, 0.5, -1e-3));
    EXPECT_EQ(*options.up, glm::dvec3(0, 0, 1));
    EXPECT_EQ(*options.fovYDegrees, 50.0);
    EXPECT_EQ(*options.towardLight, glm::dvec3(0, 0, 1)) << "the light direction is normalised";
    EXPECT_EQ(options.shading, ShadingMode::None);
    EXPECT_EQ(options.dumpDirectory, "d");
    EXPECT_EQ(options.statsPath, "s.json");
    EXPECT_TRUE(options.printPlan);
    EXPECT_EQ(options.extraOutputs, (std::vector<std::string>{"gbuffer.*", "gbuffer.depth"}));
    EXPECT_EQ(options.background, glm::dvec3(0, 0.5, 1));
    EXPECT_EQ(options.eglPlatform, "surfaceless");
    EXPECT_TRUE(options.quiet);
}

TEST(Options, MalformedValuesNameTheFlag) {
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--size", "100"}).find("--size"), std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--size", "0x10"}).find("--size"), std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--size", "99999x10"}).find("--size"), std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--size", "12.5x10"}).find("--size"), std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--eye", "1,2"}).find("--eye"), std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--eye", "1,b,2"}).find("'b'"), std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--eye", "1,nan,2"}).find("--eye"), std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--fov", "180"}).find("--fov"), std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--fov", "-5"}).find("--fov"), std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--fov", "1e-300"}).find("--fov"), std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.docx"}).find("'x.docx'"), std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--request", "a.b.c"}).find("'a.b.c'"), std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "--print-plan", "--stats", "s.json"}).find("--stats"), std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--shading", "toon"}).find("'toon'"), std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--lines", "contour"}).find("'contour'"), std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--light", "0,0,0"}).find("--light"), std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--up", "0,0,0"}).find("--up"), std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--background", "2,0,0"}).find("--background"), std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--request", "normal"}).find("--request"), std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--egl-platform", "x11"}).find("x11"), std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--bogus"}).find("'--bogus'"), std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o"}).find("-o: missing value"), std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "n.obj", "-o", "x.png"}).find("'n.obj'"), std::string::npos);
    EXPECT_NE(usageMessage({"-o", "x.png"}).find("missing MODEL"), std::string::npos);
    EXPECT_NE(usageMessage({"m.obj"}).find("-o"), std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--eye", "1,1,1", "--target", "1,1,1"}).find("differ"),
              std::string::npos);
}

TEST(Options, PrintPlanAloneNeedsNoOutput) {
    EXPECT_NO_THROW(parse({"m.obj", "--print-plan"}));
}

TEST(Options, HelpWhereAFlagStandsStopsParsing) {
    EXPECT_TRUE(parse({"m.obj", "-h", "--size", "bad"}).help);
    EXPECT_TRUE(parse({"--help"}).help) << "no model needed for help";
    EXPECT_NE(usageMessage({"m.obj", "--size", "bad", "--help"}).find("--size"), std::string::npos)
        << "a bad value before --help is still reported";
}

TEST(DumpFileName, FixedNamesForTheIssueFiles) {
    EXPECT_EQ(dumpFileName("gbuffer.normal", true, ""), "normal.exr");
    EXPECT_EQ(dumpFileName("gbuffer.view", true, ""), "view.exr");
    EXPECT_EQ(dumpFileName("gbuffer.wVec", true, ""), "w.exr");
    EXPECT_EQ(dumpFileName("gbuffer.nDotV", true, ""), "ndotv.exr");
    EXPECT_EQ(dumpFileName("gbuffer.depth", true, ""), "depth.exr");
    EXPECT_EQ(dumpFileName("shade.color", false, "shade.color"), "shading.png");
    EXPECT_EQ(dumpFileName("composite.final", false, "shade.color"), "final.png");
    EXPECT_EQ(dumpFileName("contour.lines", false, ""), "lines-contour.png");
    EXPECT_EQ(dumpFileName("other.thing", true, ""), "other-thing.exr");
}

TEST(CommandLine, HelpAndUsageExitCodes) {
    std::ostringstream out, err;
    const char* help[] = {"inkgraph", "render", "--help"};
    EXPECT_EQ(runCommandLine(3, help, out, err), kExitOk);
    EXPECT_NE(out.str().find("--size WxH"), std::string::npos);
    const char* nothing[] = {"inkgraph"};
    EXPECT_EQ(runCommandLine(1, nothing, out, err), kExitUsage);
    const char* unknown[] = {"inkgraph", "paint"};
    EXPECT_EQ(runCommandLine(2, unknown, out, err), kExitUsage);
    EXPECT_NE(err.str().find("unknown command 'paint'"), std::string::npos);
    const char* badFlag[] = {"inkgraph", "render", "m.obj", "-o", "x.png", "--size", "wide"};
    EXPECT_EQ(runCommandLine(7, badFlag, out, err), kExitUsage);
    std::ostringstream helpOut;
    const char* helpRender[] = {"inkgraph", "help", "render"};
    EXPECT_EQ(runCommandLine(3, helpRender, helpOut, err), kExitOk);
    EXPECT_NE(helpOut.str().find("--size WxH"), std::string::npos);
    // As the value of -o, "--help" is a (bad) file name, not a request for help.
    std::ostringstream valueOut, valueErr;
    const char* helpAsValue[] = {"inkgraph", "render", "m.obj", "-o", "--help"};
    EXPECT_EQ(runCommandLine(5, helpAsValue, valueOut, valueErr), kExitUsage);
    EXPECT_EQ(valueOut.str(), "");
}

} // namespace
} // namespace inkgraph
