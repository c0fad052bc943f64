// Command-line parsing: defaults, values, and a clear UsageError for every malformed flag. No GL.
#include "tests/app/OptionsTestSupport.h"
#include "flags/Options.h"
#include "app/Cli.h"
#include "app/OutputFiles.h"
#include "app/Render.h"
#include "app/StillOutputs.h"
#include "flags/FlagTable.h"
#include "gl/HeadlessContext.h"
#include "passes/gbuffer/GBufferPass.h"
#include "passes/lines/LineTypes.h"
#include "render/MemoryBudget.h"
#include "scene/TextureImage.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

namespace inkgraph {
namespace {

RenderOptions parse(std::vector<std::string> arguments) { return parseRenderOptions(arguments); }

/** The registered line parameter called `name` (passes/lines/LineTypes.h). */
const LineParameter& lineParameter(const std::string& name) {
    for (const LineParameter* parameter : lineParameters())
        if (parameter->name == name) return *parameter;
    throw std::logic_error("no line parameter '" + name + "'");
}

double parameter(const RenderOptions& options, const std::string& name) {
    return options.look.lineParameters.number(lineParameter(name));
}

std::string stencil(const RenderOptions& options) {
    return options.look.lineParameters.choice(lineParameter("suggestive-stencil"));
}

LineFamily familyOf(const std::string& type) { return findLineType(type)->family; }

using test::usageMessage;

TEST(Options, Defaults) {
    const RenderOptions options = parse({"model.obj", "-o", "out.png"});
    EXPECT_EQ(options.modelPath, "model.obj");
    EXPECT_EQ(options.outputPath, "out.png");
    EXPECT_EQ(options.width, 1024);
    EXPECT_EQ(options.height, 1024);
    EXPECT_FALSE(options.up.has_value());
    EXPECT_FALSE(options.fovYDegrees.has_value());
    EXPECT_EQ(options.look.shading, ShadingModel::Auto) << "auto is the default look";
    EXPECT_FALSE(options.look.ambient.has_value()) << "the model's own ambient by default";
    EXPECT_EQ(options.look.shininess, 32.0);
    EXPECT_FALSE(options.look.bands.has_value());
    EXPECT_EQ(options.look.viewVector, ViewVectorMode::Exact);
    EXPECT_EQ(options.look.faceOrientation, FaceOrientationMethod::Standard);
    EXPECT_EQ(options.look.frontRule, 3);
    EXPECT_EQ(options.look.lines, kDefaultLines); // no model white on white
    EXPECT_EQ(options.look.lines, (std::vector<std::string>{"silhouette", "contour"}));
    for (const LineType& type : lineTypes()) {
        EXPECT_EQ(options.look.styleOf(type.name).widthPixels, 2.0) << type.name;
        EXPECT_EQ(options.look.styleOf(type.name).color, glm::dvec4(0, 0, 0, 1)) << type.name;
    }
    EXPECT_FALSE(options.printPlan);
}

TEST(Options, JobsShareTheUsableCoresWithTheDrawingThread) {
    const int cores = usableCores();
    ASSERT_GE(cores, 1);
    EXPECT_EQ(defaultJobs(), std::min(cores, 16));
    // jobs workers beside the drawing thread: jobs + 1 threads share the cores, each post stage at least one.
    EXPECT_EQ(postStageLoopThreads(0), cores);
    EXPECT_EQ(postStageLoopThreads(1), std::max(1, cores / 2));
    EXPECT_EQ(postStageLoopThreads(cores), 1);
    EXPECT_EQ(postStageLoopThreads(64), 1);
}

TEST(Options, ShadingModesAndTheirFlags) {
    for (const char* mode : {"none", "flat", "gouraud", "lambert", "phong", "cel", "comic"})
        EXPECT_EQ(std::string(traitsOf(parse({"m.obj", "-o", "x.png", "--shading", mode}).look.shading).name), mode);
    const RenderOptions comic =
        parse({"m.obj", "-o", "x.png", "--shading", "comic", "--shininess", "0", "--shademap", "map.png",
               "--view-vector", "constant", "--face-orientation", "during-vertices", "--front-rule", "1"});
    EXPECT_EQ(comic.look.shininess, 0.0);
    EXPECT_EQ(comic.look.shadeMapPath, "map.png");
    EXPECT_EQ(comic.look.viewVector, ViewVectorMode::Constant);
    EXPECT_EQ(comic.look.faceOrientation, FaceOrientationMethod::DuringVertices);
    EXPECT_EQ(comic.look.frontRule, 1);
    EXPECT_EQ(parse({"m.obj", "-o", "x.png", "--shading", "phong", "--shininess", "1e6"}).look.shininess, 1e6);
    EXPECT_EQ(*parse({"m.obj", "-o", "x.png", "--bands", "3"}).look.bands, 3)
        << "auto is the default and draws cel where a material has no MToon, so --bands applies";
}

TEST(Options, ShadingFlagsWithoutEffectAreRefused) {
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--shininess", "8"})
                  .find("--shininess has no effect with "
                        "--shading auto"),
              std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--shading", "comic", "--bands", "4"}).find("--bands"),
              std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--shading", "phong", "--shademap", "a.png"}).find("--shademap"),
              std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--bands", "4", "--shademap", "a.png"}).find("give one"),
              std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--view-vector", "constant"}).find("--view-vector"),
              std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--shading", "comic", "--front-rule", "2"}).find("'standard'"),
              std::string::npos)
        << "the rule needs a vertex method";
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--shading", "comic", "--face-orientation", "during-triangles",
                            "--front-rule", "2"})
                  .find("--front-rule"),
              std::string::npos);
}

TEST(Options, ShadingValuesOutOfRange) {
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--shading", "phong", "--shininess", "-1"}).find("--shininess"),
              std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--shading", "phong", "--shininess", "2e6"}).find("1e6"),
              std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--bands", "1"}).find("--bands"), std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--bands", "2.5"}).find("'2.5'"), std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--bands", "257"}).find("256"), std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--shading", "comic", "--face-orientation", "sideways"})
                  .find("'sideways'"),
              std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--shading", "comic", "--face-orientation", "after-vertices",
                            "--front-rule", "4"})
                  .find("--front-rule"),
              std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--shading", "comic", "--view-vector", "approx"}).find("'approx'"),
              std::string::npos);
}

TEST(Options, LineTypesAndTheirStyles) {
    const RenderOptions options =
        parse({"m.obj", "-o", "x.png", "--lines", "silhouette,outline", "--silhouette-width", "3.5", "--outline-color",
               "1,0,0", "--silhouette-color", "0,0,1,0.5", "--silhouette-object-width", "0.02"});
    EXPECT_EQ(options.look.lines, (std::vector<std::string>{"silhouette", "outline"}));
    EXPECT_EQ(options.look.styleOf("silhouette").widthPixels, 3.5);
    EXPECT_EQ(options.look.styleOf("silhouette").color, glm::dvec4(0, 0, 1, 0.5));
    EXPECT_EQ(options.look.styleOf("outline").color, glm::dvec4(1, 0, 0, 1));
    EXPECT_EQ(options.look.styleOf("outline").widthPixels, 2.0);
    EXPECT_EQ(parameter(options, "silhouette-object-width"), 0.02);

    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--outline-width", "3"}).find("'outline' line type is not drawn"),
              std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--lines", "none", "--silhouette-object-width", "1"})
                  .find("--silhouette-object-width"),
              std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--lines", "outline", "--outline-width", "0"}).find("from 0.001"),
              std::string::npos);
    // A width no single float holds (it reached the stroke stage as 0: an internal error there).
    EXPECT_NE(
        usageMessage({"m.obj", "-o", "x.png", "--lines", "outline", "--outline-width", "1e-46"}).find("from 0.001"),
        std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--lines", "outline", "--outline-width", "300"}).find("256"),
              std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--lines", "outline", "--outline-color", "1,0"}).find("R,G,B"),
              std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--lines", "outline", "--outline-color", "1,0,2"}).find("[0, 1]"),
              std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--lines", "outline,outline"}).find("twice"), std::string::npos);
    // 1e-46 became 0 in the shaders' float (no silhouette, exit 0), 3.5e38 infinity (an internal error).
    for (const char* width : {"-1", "0", "1e-46", "9e-38", "3.5e38", "1.1e38"})
        EXPECT_EQ(usageMessage({"m.obj", "-o", "x.png", "--lines", "silhouette", "--silhouette-object-width", width}),
                  std::string("--silhouette-object-width: model units must lie from 1e-37 to 1e38 (what the shaders' "
                              "float holds), got '") +
                      width + "'")
            << width;
    EXPECT_EQ(parameter(parse({"m.obj", "-o", "x.png", "--lines", "silhouette", "--silhouette-object-width", "1e38"}),
                        "silhouette-object-width"),
              1e38);
}

TEST(Options, PostStageLineTypesAndTheirFlags) {
    const RenderOptions options =
        parse({"m.obj", "-o", "x.png", "--lines",
               "contour,suggestive,depth-edge,normal-edge,crease,border,"
               "mesh-silhouette",
               "--crease-angle", "45", "--depth-jump", "0.1", "--suggestive-threshold", "0.02", "--suggestive-fade",
               "0.5", "--supersample", "3", "--suggestive-width", "1.5"});
    EXPECT_EQ(options.look.lines.size(), 7u);
    EXPECT_EQ(parameter(options, "crease-angle"), 45.0);
    EXPECT_EQ(parameter(options, "depth-jump"), 0.1);
    EXPECT_EQ(parameter(options, "suggestive-threshold"), 0.02);
    EXPECT_EQ(parameter(options, "suggestive-fade"), 0.5);
    EXPECT_EQ(options.look.supersample, 3);
    EXPECT_EQ(options.look.styleOf("suggestive").widthPixels, 1.5);
    for (const char* type : {"contour", "suggestive", "depth-edge", "normal-edge"})
        EXPECT_TRUE((familyOf(type) == LineFamily::ImageSpace)) << type;
    for (const char* type : {"crease", "border", "mesh-silhouette"})
        EXPECT_TRUE((familyOf(type) == LineFamily::MeshEdge)) << type;
    EXPECT_FALSE((familyOf("outline") == LineFamily::ImageSpace));
    EXPECT_FALSE((familyOf("silhouette") == LineFamily::MeshEdge));

    // A flag that changes none of the requested line types is refused, naming the types it applies to.
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--lines", "contour", "--crease-angle", "40"})
                  .find("crease, normal-edge"),
              std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--lines", "crease", "--depth-jump", "0.1"}).find("--depth-jump"),
              std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--lines", "contour", "--suggestive-fade", "1"}).find("suggestive"),
              std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--lines", "outline", "--supersample", "2"}).find("--supersample"),
              std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--lines", "crease", "--crease-angle", "180"}).find("below 180"),
              std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--lines", "contour", "--depth-jump", "0"}).find("--depth-jump"),
              std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--lines", "suggestive", "--suggestive-threshold", "-1"})
                  .find("--suggestive-threshold"),
              std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--lines", "contour", "--supersample", "9"}).find("1 to 8"),
              std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--size", "8192x8192", "--lines", "contour", "--supersample", "4"})
                  .find("largest buffer side"),
              std::string::npos);
}

TEST(Options, MsaaTakesOneTwoFourOrEightSamplesAndNeedsAShadingPass) {
    EXPECT_EQ(parse({"m.obj", "-o", "x.png"}).look.msaa, 1);
    for (const int samples : {1, 2, 4, 8})
        EXPECT_EQ(parse({"m.obj", "-o", "x.png", "--msaa", std::to_string(samples)}).look.msaa, samples);
    for (const char* value : {"0", "3", "16", "4.0", "-4", "four"})
        EXPECT_EQ(usageMessage({"m.obj", "-o", "x.png", "--msaa", value}),
                  std::string("--msaa: expected 1 (off), 2, 4 or 8 samples per pixel, got '") + value + "'");
    EXPECT_EQ(usageMessage({"m.obj", "-o", "x.png", "--shading", "none", "--msaa", "4"}),
              "--msaa has no effect with --shading none (only the shading is multisampled)");
}

TEST(Options, OutlineWidthMapTakesAVertexColourOrATextureChannelAndNeedsAnOutline) {
    EXPECT_FALSE(parse({"m.obj", "-o", "x.png"}).look.outlineWidthMap.enabled());
    const WidthMap colour = parse({"m.obj", "-o", "x.png", "--outline-width-map", "color:A"}).look.outlineWidthMap;
    EXPECT_EQ(colour.source, WidthMap::Source::VertexColor);
    EXPECT_EQ(colour.channel, 3);
    EXPECT_EQ(colour.text(), "color:A");
    // The channel is after the last colon, so a name may hold colons; lower case is taken.
    const WidthMap texture =
        parse({"m.obj", "-o", "x.png", "--outline-width-map", "texture:maps/a:b.png:g"}).look.outlineWidthMap;
    EXPECT_EQ(texture.source, WidthMap::Source::Texture);
    EXPECT_EQ(texture.texture, "maps/a:b.png");
    EXPECT_EQ(texture.channel, 1);
    EXPECT_EQ(texture.text(), "texture:maps/a:b.png:G");
    EXPECT_EQ(parseWidthMap(texture.text()), texture);
    EXPECT_FALSE(parse({"m.obj", "-o", "x.png", "--outline-width-map", "color:R", "--outline-width-map", "none"})
                     .look.outlineWidthMap.enabled());
    // Bad syntax and unknown channels: a usage error (exit 2) naming the flag and quoting the value.
    for (const char* value : {"color", "color:", "color:X", "color:RG", "colour:R", "texture:a.png", "texture::G",
                              "texture:a.png:Q", "vertex:R"}) {
        const std::string message = usageMessage({"m.obj", "-o", "x.png", "--outline-width-map", value});
        EXPECT_EQ(message.rfind("--outline-width-map: ", 0), 0u) << value << ": " << message;
        EXPECT_NE(message.find(std::string("got '") + value + "'"), std::string::npos) << message;
    }
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--outline-width-map", "color:X"}).find("unknown channel 'X'"),
              std::string::npos);
    // It scales outline, silhouette and MToon's outlines: with none of them it has no effect.
    EXPECT_EQ(usageMessage(
                  {"m.obj", "-o", "x.png", "--shading", "cel", "--lines", "contour", "--outline-width-map", "color:R"}),
              "--outline-width-map has no effect: it scales outline and silhouette, neither of which is in --lines, "
              "and MToon's outlines, which --shading cel does not draw");
    EXPECT_TRUE(
        parse({"m.obj", "-o", "x.png", "--shading", "mtoon", "--lines", "contour", "--outline-width-map", "color:R"})
            .look.outlineWidthMap.enabled());
    // Its file is an input, which no output may overwrite (as --shademap's).
    const std::vector<RunInput> inputs =
        inputsNamedBy(parse({"m.obj", "-o", "x.png", "--outline-width-map", "texture:ramp.png:G"}));
    EXPECT_TRUE(std::ranges::any_of(inputs, [](const RunInput& input) {
        return input.path == "ramp.png" && input.what == "the --outline-width-map image";
    }));
}

TEST(Options, GBufferPrecision) {
    EXPECT_EQ(parse({"m.obj", "-o", "x.png"}).look.gbufferPrecision, GBufferPrecision::Float32);
    EXPECT_EQ(parse({"m.obj", "-o", "x.png", "--gbuffer-precision", "half"}).look.gbufferPrecision,
              GBufferPrecision::Float16);
    EXPECT_EQ(parse({"m.obj", "-o", "x.png", "--gbuffer-precision", "float"}).look.gbufferPrecision,
              GBufferPrecision::Float32);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--gbuffer-precision", "double"}).find("(available: float, half)"),
              std::string::npos);
}

TEST(Options, MemoryLimitInMebibytes) {
    EXPECT_FALSE(parse({"m.obj", "-o", "x.png"}).memoryLimitBytes) << "default: half the machine's memory";
    EXPECT_EQ(*parse({"m.obj", "-o", "x.png", "--memory-limit", "64"}).memoryLimitBytes, std::size_t(64) << 20);
    EXPECT_EQ(*parse({"m.obj", "-o", "x.png", "--memory-limit", "16777216"}).memoryLimitBytes, std::size_t(1) << 44);
    for (const char* bad : {"63", "0", "-5", "1.5", "16777217", "lots"})
        EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--memory-limit", bad}).find("--memory-limit"),
                  std::string::npos)
            << bad;
}

TEST(Options, SuggestiveStencil) {
    EXPECT_EQ(stencil(parse({"m.obj", "-o", "x.png", "--lines", "suggestive"})), "3");
    EXPECT_EQ(stencil(parse({"m.obj", "-o", "x.png", "--lines", "suggestive", "--suggestive-stencil", "5"})), "5");
    EXPECT_NE(
        usageMessage({"m.obj", "-o", "x.png", "--lines", "suggestive", "--suggestive-stencil", "4"}).find("3 or 5"),
        std::string::npos);
    EXPECT_NE(
        usageMessage({"m.obj", "-o", "x.png", "--lines", "contour", "--suggestive-stencil", "5"}).find("has no effect"),
        std::string::npos);
}

TEST(Options, SuggestiveSmoothing) {
    // Fractions of the bounding radius; 0 turns smoothing off; a negative value or one above 1 is refused, and the
    // flag without its type has no effect.
    EXPECT_EQ(parameter(parse({"m.obj", "-o", "x.png", "--lines", "suggestive"}), "suggestive-smoothing"), 0.005);
    EXPECT_EQ(parameter(parse({"m.obj", "-o", "x.png", "--lines", "suggestive", "--suggestive-smoothing", "0"}),
                        "suggestive-smoothing"),
              0.0);
    EXPECT_EQ(parameter(parse({"m.obj", "-o", "x.png", "--lines", "suggestive-object"}), "suggestive-object-smoothing"),
              0.01);
    for (const char* bad : {"-0.1", "2", "lots"})
        EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--lines", "suggestive", "--suggestive-smoothing", bad})
                      .find("--suggestive-smoothing"),
                  std::string::npos)
            << bad;
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--lines", "suggestive", "--suggestive-object-smoothing", "0.1"})
                  .find("has no effect"),
              std::string::npos);
}

TEST(Options, SuggestiveClearances) {
    // Sigmas of the smoothing, clear of surface ends (default 0: no band) and of where smooth patches meet (default
    // 2); a negative value or one above 100 is refused, and a flag without its type has no effect.
    for (const auto& [name, byDefault] : {std::pair<std::string, double>{"suggestive-clearance", 0.0},
                                          std::pair<std::string, double>{"suggestive-patch-clearance", 2.0}}) {
        SCOPED_TRACE(name);
        const std::string flag = "--" + name;
        EXPECT_EQ(parameter(parse({"m.obj", "-o", "x.png", "--lines", "suggestive"}), name), byDefault);
        EXPECT_EQ(parameter(parse({"m.obj", "-o", "x.png", "--lines", "suggestive", flag, "3"}), name), 3.0);
        for (const char* bad : {"-1", "101", "wide"})
            EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--lines", "suggestive", flag, bad}).find(flag),
                      std::string::npos)
                << bad;
        EXPECT_NE(
            usageMessage({"m.obj", "-o", "x.png", "--lines", "suggestive-object", flag, "2"}).find("has no effect"),
            std::string::npos);
    }
}

TEST(Options, StrokeFlags) {
    // Issue 19: how line pixels become strokes, for every drawn type.
    const RenderOptions defaults = parse({"m.obj", "-o", "x.png", "--lines", "contour"});
    EXPECT_EQ(defaults.look.strokes.minLength, 0.01);
    EXPECT_FALSE(defaults.look.strokes.weightByDepth);
    EXPECT_FALSE(defaults.look.strokes.weightByStrength);
    EXPECT_FALSE(defaults.look.strokes.taperEnds);
    EXPECT_FALSE(defaults.look.strokes.mergeOverlaps);
    EXPECT_EQ(parse({"m.obj", "-o", "x.png", "--lines", "contour", "--min-stroke-length", "0"}).look.strokes.minLength,
              0.0);
    EXPECT_EQ(
        parse({"m.obj", "-o", "x.png", "--lines", "contour", "--min-stroke-length", "0.02"}).look.strokes.minLength,
        0.02);
    for (const char* bad : {"-1", "2", "x"})
        EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--lines", "contour", "--min-stroke-length", bad})
                      .find("--min-stroke-length"),
                  std::string::npos)
            << bad;

    const StrokeStyle none =
        parse({"m.obj", "-o", "x.png", "--lines", "contour", "--line-weight", "none"}).look.strokes;
    EXPECT_FALSE(none.weightByDepth || none.weightByStrength || none.taperEnds);
    const StrokeStyle depthTaper =
        parse({"m.obj", "-o", "x.png", "--lines", "contour", "--line-weight", "depth,taper"}).look.strokes;
    EXPECT_TRUE(depthTaper.weightByDepth);
    EXPECT_FALSE(depthTaper.weightByStrength);
    EXPECT_TRUE(depthTaper.taperEnds);
    EXPECT_TRUE(parse({"m.obj", "-o", "x.png", "--lines", "contour", "--line-weight", "strength"})
                    .look.strokes.weightByStrength);
    const std::string twice =
        usageMessage({"m.obj", "-o", "x.png", "--lines", "contour", "--line-weight", "depth,depth"});
    EXPECT_NE(twice.find("--line-weight"), std::string::npos) << twice;
    EXPECT_NE(twice.find("'depth' is listed twice"), std::string::npos) << twice;
    const std::string bold = usageMessage({"m.obj", "-o", "x.png", "--lines", "contour", "--line-weight", "bold"});
    EXPECT_NE(bold.find("--line-weight"), std::string::npos) << bold;
    EXPECT_NE(bold.find("depth, strength, taper"), std::string::npos) << bold;
    EXPECT_NE(bold.find("'bold'"), std::string::npos) << bold;

    EXPECT_TRUE(parse({"m.obj", "-o", "x.png", "--lines", "contour", "--overlapping-lines", "merge"})
                    .look.strokes.mergeOverlaps);
    EXPECT_FALSE(parse({"m.obj", "-o", "x.png", "--lines", "contour", "--overlapping-lines", "draw"})
                     .look.strokes.mergeOverlaps);
    const std::string overlap =
        usageMessage({"m.obj", "-o", "x.png", "--lines", "contour", "--overlapping-lines", "hide"});
    EXPECT_NE(overlap.find("--overlapping-lines"), std::string::npos) << overlap;
    EXPECT_NE(overlap.find("'hide'"), std::string::npos) << overlap;

    // Without lines they change nothing, so they are refused.
    for (const std::vector<std::string>& flag : std::vector<std::vector<std::string>>{
             {"--min-stroke-length", "0.02"}, {"--line-weight", "taper"}, {"--overlapping-lines", "merge"}}) {
        const std::string message = usageMessage({"m.obj", "-o", "x.png", "--lines", "none", flag[0], flag[1]});
        EXPECT_NE(message.find(flag[0] + " has no effect"), std::string::npos) << message;
    }
}

TEST(Options, HiddenLinesAddTheirTypesWhicheverComesFirst) {
    using Lines = std::vector<std::string>;
    auto lines = [](std::vector<std::string> flags) {
        std::vector<std::string> arguments = {"m.obj", "-o", "x.png"};
        arguments.insert(arguments.end(), flags.begin(), flags.end());
        return parse(arguments).look.lines;
    };
    EXPECT_EQ(lines({"--lines", "crease", "--hidden-lines", "crease,border"}),
              (Lines{"crease", "hidden-crease", "hidden-border"}));
    // --lines after --hidden-lines keeps what --hidden-lines added; a later --hidden-lines replaces it.
    EXPECT_EQ(lines({"--hidden-lines", "crease", "--lines", "contour"}), (Lines{"hidden-crease", "contour"}));
    EXPECT_EQ(lines({"--hidden-lines", "crease", "--lines", "none"}), (Lines{"hidden-crease"}));
    EXPECT_EQ(lines({"--lines", "crease", "--hidden-lines", "crease", "--hidden-lines", "border"}),
              (Lines{"crease", "hidden-border"}));
    EXPECT_EQ(lines({"--lines", "crease", "--hidden-lines", "crease", "--hidden-lines", "none"}), (Lines{"crease"}));
    // Named by --lines too: once, and --lines' own.
    EXPECT_EQ(lines({"--lines", "hidden-crease", "--hidden-lines", "crease"}), (Lines{"hidden-crease"}));
    EXPECT_EQ(lines({"--hidden-lines", "crease", "--lines", "hidden-crease", "--hidden-lines", "none"}),
              (Lines{"hidden-crease"}));
    const StrokeStyle dash =
        parse({"m.obj", "-o", "x.png", "--hidden-lines", "crease", "--hidden-dash", "5,2.5"}).look.strokes;
    EXPECT_EQ(dash.hiddenDashOn, 5.0);
    EXPECT_EQ(dash.hiddenDashOff, 2.5);
    EXPECT_EQ(
        parse({"m.obj", "-o", "x.png", "--hidden-lines", "crease", "--hidden-dash", "none"}).look.strokes.hiddenDashOff,
        0.0);
    EXPECT_EQ(
        parse({"m.obj", "-o", "x.png", "--hidden-lines", "crease", "--hidden-dash", "1,0"}).look.strokes.hiddenDashOn,
        1.0);
    // Under a pixel, a dash is no dash: a stroke cut into 1e-6-pixel dashes took all the machine's memory.
    for (const char* tiny : {"0.99,4", "6,0.5", "1e-6,1e-6", "0,4", "4097,1", "6,-1"})
        EXPECT_EQ(usageMessage({"m.obj", "-o", "x.png", "--hidden-lines", "crease", "--hidden-dash", tiny}),
                  std::string("--hidden-dash: expected ON,OFF in output pixels (ON 1 to 4096, OFF 0 or 1 to 4096) or "
                              "none, got '") +
                      tiny + "'")
            << tiny;
    EXPECT_EQ(usageMessage({"m.obj", "-o", "x.png", "--hidden-lines", "suggestive"}),
              "--hidden-lines: 'suggestive' has no hidden lines (available: crease, border, intersection, "
              "suggestive-object, mesh-silhouette; or 'none')");
    // 'none' in a list was called a type with no hidden lines, and an unknown line type under --lines.
    for (const char* flagName : {"--hidden-lines", "--lines", "--line-weight"})
        for (const char* list : {"none,crease", "crease,none", "none,none"})
            EXPECT_EQ(usageMessage({"m.obj", "-o", "x.png", "--lines", "crease", flagName, list}),
                      std::string(flagName) + ": 'none' is given alone, not in a list (got '" + list + "')")
                << flagName << ' ' << list;
}

TEST(Options, StrokeLineParameters) {
    // --suggestive-seed (hysteresis, a strength like --suggestive-threshold) and --crease-min-length (a share of the
    // bounding radius), issue 19.
    EXPECT_EQ(parameter(parse({"m.obj", "-o", "x.png", "--lines", "suggestive"}), "suggestive-seed"), 0.04);
    EXPECT_EQ(parameter(parse({"m.obj", "-o", "x.png", "--lines", "suggestive", "--suggestive-seed", "0"}),
                        "suggestive-seed"),
              0.0);
    for (const char* bad : {"-0.1", "2e6", "strong"})
        EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--lines", "suggestive", "--suggestive-seed", bad})
                      .find("--suggestive-seed"),
                  std::string::npos)
            << bad;
    EXPECT_EQ(parameter(parse({"m.obj", "-o", "x.png", "--lines", "crease"}), "crease-min-length"), 0.1);
    EXPECT_EQ(parameter(parse({"m.obj", "-o", "x.png", "--lines", "crease", "--crease-min-length", "0.5"}),
                        "crease-min-length"),
              0.5);
    for (const char* bad : {"-0.1", "101", "long"})
        EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--lines", "crease", "--crease-min-length", bad})
                      .find("--crease-min-length"),
                  std::string::npos)
            << bad;
    EXPECT_NE(
        usageMessage({"m.obj", "-o", "x.png", "--lines", "contour", "--suggestive-seed", "0.1"}).find("has no effect"),
        std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--lines", "contour", "--crease-min-length", "0.2"})
                  .find("has no effect"),
              std::string::npos);
}

TEST(Options, ObjectSpaceSuggestiveContours) {
    const RenderOptions options =
        parse({"m.obj", "-o", "x.png", "--lines", "contour,suggestive-object", "--suggestive-threshold", "0.05",
               "--suggestive-fade", "0", "--suggestive-object-width", "3", "--suggestive-object-color", "0,0,1",
               "--depth-jump", "0.02", "--supersample", "2"});
    EXPECT_EQ(options.look.lines, (std::vector<std::string>{"contour", "suggestive-object"}));
    EXPECT_EQ(parameter(options, "suggestive-threshold"), 0.05);
    EXPECT_EQ(parameter(options, "suggestive-fade"), 0.0);
    EXPECT_EQ(options.look.styleOf("suggestive-object").widthPixels, 3.0);
    EXPECT_EQ(options.look.styleOf("suggestive-object").color, glm::dvec4(0.0, 0.0, 1.0, 1.0));
    EXPECT_TRUE((familyOf("suggestive-object") == LineFamily::ObjectSpace));
    EXPECT_FALSE((familyOf("suggestive-object") == LineFamily::ImageSpace));
    EXPECT_FALSE((familyOf("suggestive-object") == LineFamily::MeshEdge));
    // Composited right after the image-space suggestive contours.
    std::vector<std::string> known;
    for (const LineType& type : lineTypes()) known.push_back(type.name);
    const auto at = std::find(known.begin(), known.end(), "suggestive");
    ASSERT_NE(at, known.end());
    ASSERT_NE(at + 1, known.end());
    EXPECT_EQ(*(at + 1), "suggestive-object");
    EXPECT_NE(renderHelp().find("suggestive-object"), std::string::npos);
    // Its flags without it are refused; its name in a style flag needs it in --lines.
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--lines", "contour", "--suggestive-threshold", "0.1"})
                  .find("suggestive, suggestive-object"),
              std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--lines", "suggestive", "--suggestive-object-width", "2"})
                  .find("'suggestive-object' line type is not drawn"),
              std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--lines", "suggestive-object", "--suggestive-fade", "-1"})
                  .find("--suggestive-fade"),
              std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--lines", "suggestive-objects"}).find("unknown line type"),
              std::string::npos);
}

TEST(Options, EveryValue) {
    const RenderOptions options = parse({"-o",
                                         "a.png",
                                         "m.glb",
                                         "--size",
                                         "640x480",
                                         "--eye",
                                         "1,2,3",
                                         "--target",
                                         "0,0.5,-1e-3",
                                         "--up",
                                         "0,0,1",
                                         "--fov",
                                         "50",
                                         "--light",
                                         "0,0,2",
                                         "--shading",
                                         "none",
                                         "--lines",
                                         "none",
                                         "--dump",
                                         "d",
                                         "--stats",
                                         "s.json",
                                         "--print-plan",
                                         "--request",
                                         "gbuffer.*,gbuffer.depth",
                                         "--background",
                                         "0,0.5,1",
                                         "--egl-platform",
                                         "surfaceless",
                                         "-q"});
    EXPECT_EQ(options.width, 640);
    EXPECT_EQ(options.height, 480);
    EXPECT_EQ(*options.eye, glm::dvec3(1, 2, 3));
    EXPECT_EQ(*options.target, glm::dvec3(0, 0.5, -1e-3));
    EXPECT_EQ(*options.up, glm::dvec3(0, 0, 1));
    EXPECT_EQ(*options.fovYDegrees, 50.0);
    EXPECT_EQ(*options.look.towardLight, glm::dvec3(0, 0, 1)) << "the light direction is normalised";
    EXPECT_EQ(options.look.shading, ShadingModel::None);
    EXPECT_EQ(options.dumpDirectory, "d");
    EXPECT_EQ(options.statsPath, "s.json");
    EXPECT_TRUE(options.printPlan);
    EXPECT_EQ(options.extraOutputs, (std::vector<std::string>{"gbuffer.*", "gbuffer.depth"}));
    EXPECT_EQ(options.look.background, glm::dvec3(0, 0.5, 1));
    EXPECT_EQ(options.eglPlatform, "surfaceless");
    EXPECT_TRUE(options.quiet);
}

TEST(Options, ADashIsNoOutputFile) {
    // `--stats -` wrote a file called '-' without a word (for --list, '-' is standard input).
    // -o, --svg and --strokes refuse it by its extension.
    for (const char* flag : {"--stats", "--dump", "--graphviz"}) {
        const std::string message = usageMessage({"m.obj", "-o", "x.png", "--lines", "contour", flag, "-"});
        EXPECT_NE(message.find(std::string(flag) + " '-': outputs are written to files, not to standard output"),
                  std::string::npos)
            << message;
    }
    EXPECT_EQ(parseRenderOptions({"m.obj", "-o", "x.png", "--stats", "./-"}).statsPath, "./-");
}

TEST(Options, WholeNumbersAreWrittenInDigitsOnly) {
    // "16.0" or "1e1" for a count is a slip (a float pasted from a script), refused rather than read as 16 or 10.
    EXPECT_EQ(usageMessage({"m.obj", "-o", "x.png", "--size", "1e3x64"}),
              "--size: width and height must be whole numbers from 1 to 16384, got '1e3x64'");
    EXPECT_EQ(usageMessage({"m.obj", "-o", "x.png", "--size", "64x64.0"}),
              "--size: width and height must be whole numbers from 1 to 16384, got '64x64.0'");
    EXPECT_EQ(usageMessage({"m.obj", "-o", "x.png", "--size", "-64x64"}),
              "--size: width and height must be whole numbers from 1 to 16384, got '-64x64'");
    EXPECT_EQ(usageMessage({"m.obj", "-o", "x.png", "--size", "+-64x64"}),
              "--size: width and height must be whole numbers from 1 to 16384, got '+-64x64'");
    EXPECT_EQ(usageMessage({"m.obj", "-o", "x.png", "--supersample", "2.0"}),
              "--supersample: expected a whole number from 1 to 8, got '2.0'");
    EXPECT_EQ(usageMessage({"m.obj", "-o", "x.png", "--jobs", "1e1"}),
              "--jobs: expected a whole number from 0 to 64, got '1e1'");
    // Digits still read as before, leading zeros too.
    EXPECT_EQ(parse({"m.obj", "-o", "x.png", "--size", "0064x32", "--supersample", "02"}).look.supersample, 2);
    EXPECT_EQ(parse({"m.obj", "-o", "x.png", "--size", "0064x32"}).width, 64);
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
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--lines", "hatching"}).find("'hatching'"), std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--light", "0,0,0"}).find("--light"), std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--up", "0,0,0"}).find("--up"), std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--background", "2,0,0"}).find("--background"), std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--background", "1,1,1,0"}).find("expected R,G,B"),
              std::string::npos)
        << "a colour, not a point";
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--request", "normal"}).find("--request"), std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--egl-platform", "x11"}).find("x11"), std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--bogus"}).find("'--bogus'"), std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o"}).find("-o: missing value"), std::string::npos);
    EXPECT_NE(usageMessage({"-o", "x.png"}).find("missing MODEL"), std::string::npos);
    EXPECT_NE(usageMessage({"m.obj"}).find("-o"), std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--eye", "1,1,1", "--target", "1,1,1"}).find("differ"),
              std::string::npos);
}

TEST(Options, AValueMayFollowItsFlagAfterAnEqualsSign) {
    // "--size=512x512" was refused as an unknown option '--size=512x512', though getopt_long() takes it everywhere.
    const RenderOptions options =
        parse({"m.obj", "--output=x.png", "--size=64x32", "--orbit=-30,10", "--lines=contour,crease"});
    EXPECT_EQ(options.outputPath, "x.png");
    EXPECT_EQ(options.width, 64);
    EXPECT_EQ(options.height, 32);
    ASSERT_TRUE(options.orbit.has_value());
    EXPECT_EQ(options.orbit->azimuthDegrees, -30.0) << "a value that starts with a minus sign needs no other form";
    EXPECT_EQ(options.look.lines.size(), 2u);
    EXPECT_EQ(parse({"m.obj", "-o", "x.png", "--lines=contour", "--lines", "crease"}).look.lines.size(), 1u)
        << "the two forms are one flag: the last one given wins";
    // A flag's own value is left whole, as before: this output is a file called '--size=1x1.png'.
    EXPECT_EQ(parse({"m.obj", "-o", "--size=1x1.png"}).outputPath, "--size=1x1.png");
    EXPECT_EQ(usageMessage({"m.obj", "-o", "x.png", "--size", "--size=1x1"}),
              "--size: width and height must be whole numbers from 1 to 16384, got '--size=1x1'");
    // What the parser refuses in the two-argument form it refuses in this one, in the same words.
    EXPECT_EQ(usageMessage({"m.obj", "-o", "x.png", "--size=64"}),
              usageMessage({"m.obj", "-o", "x.png", "--size", "64"}));
    EXPECT_EQ(usageMessage({"m.obj", "-o", "x.png", "--size="}), "--size: empty value");
    EXPECT_EQ(usageMessage({"m.obj", "-o", "x.png", "--quiet=1"}), "--quiet: takes no value, got '1'");
    EXPECT_EQ(usageMessage({"m.obj", "-o", "x.png", "--bogus=1"}), "unknown option '--bogus=1'");
    EXPECT_EQ(usageMessage({"m.obj", "-o=x.png"}),
              "'-o=x.png': -o takes its value as the next argument (-o x.png, or --output=x.png)");
    EXPECT_EQ(usageMessage({"m.obj", "-o="}),
              "'-o=': -o takes its value as the next argument (-o FILE, or --output=FILE)");
    EXPECT_EQ(usageMessage({"m.obj", "-o", "x.png", "-q=1"}), "-q: takes no value, got '1'");
    EXPECT_NE(renderHelp().find("--size=512x512"), std::string::npos) << "--help says so";
}

TEST(Options, AFlagGivenTwiceKeepsItsLastValueAndTheListsAdd) {
    // As --help says (kFlagValueForms): a script may append a flag to override what it gave before.
    const RenderOptions twice =
        parse({"m.obj",   "-o",      "a.png",     "--output",       "b.png",        "--stats",       "a.json",
               "--stats", "b.json",  "--size",    "64x64",          "--size=32x16", "--lines",       "contour",
               "--lines", "crease",  "--request", "gbuffer.normal", "--request",    "gbuffer.depth", "--frame",
               "head",    "--frame", "hand"});
    EXPECT_EQ(twice.outputPath, "b.png");
    EXPECT_EQ(twice.statsPath, "b.json");
    EXPECT_EQ(twice.width, 32);
    EXPECT_EQ(twice.look.lines, std::vector<std::string>{"crease"});
    EXPECT_EQ(twice.extraOutputs, (std::vector<std::string>{"gbuffer.normal", "gbuffer.depth"}));
    EXPECT_EQ(twice.frameNodes, (std::vector<std::string>{"head", "hand"}));
    EXPECT_NE(renderHelp().find("A flag given twice keeps its"), std::string::npos);
    EXPECT_NE(renderHelp().find("--request and --frame add to their lists."), std::string::npos);
}

TEST(Options, HelpTextsAreMadeFromTheTablesTheyDescribe) {
    // Each flag's own help text, before --help wraps it.
    const auto helpOf = [](const std::string& name) {
        const Flag* entry = findFlag(name);
        return entry ? entry->help : std::string("(no flag " + name + ")");
    };
    // -o: every extension the flag takes (.tiff and .jpeg were taken but not named).
    for (const char* extension : {".png", ".exr", ".tif", ".tiff", ".jpg", ".jpeg"}) {
        EXPECT_EQ(usageMessage({"m.obj", "-o", std::string("x") + extension}), "(no error)") << extension;
        EXPECT_NE(helpOf("-o").find(extension), std::string::npos) << extension;
    }
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.gif"}).find(".tif, .tiff, .jpg or .jpeg"), std::string::npos);
    // --dump: every G-buffer field's file (meshid, triangleid, barycentric and the z-buffer were left out).
    for (const GBufferPass::Field& field : GBufferPass::fields())
        EXPECT_NE(helpOf("--dump").find(field.fileName), std::string::npos) << field.fileName;
    EXPECT_NE(helpOf("--dump").find(GBufferPass::kZBufferFile), std::string::npos);
    // --size: the one-buffer limit beside the side's.
    EXPECT_EQ(largestFloatRgbaSquareSide(), 11584);
    EXPECT_NE(helpOf("--size").find("at most 11584x11584"), std::string::npos);
    // A number line parameter's range, from its declaration.
    EXPECT_NE(helpOf("--depth-jump").find("; R above 0, up to 100"), std::string::npos);
    EXPECT_NE(helpOf("--crease-angle").find("; DEG above 0 and below 180"), std::string::npos);
    EXPECT_NE(helpOf("--suggestive-smoothing").find("; S from 0 to 1"), std::string::npos);
    EXPECT_NE(helpOf("--silhouette-object-width").find("; D from 1e-37 to 1e38"), std::string::npos);
    for (const LineParameter* parameter : lineParameters()) {
        if (parameter->isChoice()) continue;
        EXPECT_NE(helpOf("--" + parameter->name).find("; " + parameter->valueName + " "), std::string::npos)
            << parameter->name;
    }
    // The lists that come from other layers' tables.
    for (const std::string& name : softwareRasterizerNames())
        EXPECT_NE(helpOf("--post-stage").find(name), std::string::npos) << name;
    EXPECT_NE(helpOf("--outline-width-map").find(kTextureFormatNames), std::string::npos);
    EXPECT_NE(helpOf("--memory-limit").find("64 to 16777216"), std::string::npos);
    EXPECT_NE(helpOf("--shademap").find("for cel, comic and auto"), std::string::npos); // the models' traits
}

TEST(Options, UsageTextsNameEveryFormatTheLoaderReads) {
    // The help and the missing-MODEL message list the reader table's extensions, so a format added there (PLY was
    // left out of both) is named without editing them.
    for (const std::string extension : {".gltf", ".glb", ".vrm", ".obj", ".stl", ".ply"}) {
        EXPECT_NE(modelFileExtensions().find(extension), std::string::npos) << extension;
        EXPECT_NE(renderHelp().find(extension), std::string::npos) << extension;
        EXPECT_NE(usageMessage({"-o", "x.png"}).find(extension), std::string::npos) << extension;
    }
    EXPECT_NE(renderHelp().find("MODEL (" + modelFileExtensions() + ")"), std::string::npos);
}

TEST(Options, ExtremeButFiniteDirectionsKeepTheirDirection) {
    // The length of (1e300, 1e300, 0) overflows and that of (1e-300, 0, 0) underflows in double: scaled first.
    const glm::dvec3 huge = *parse({"m.obj", "-o", "x.png", "--light", "1e300,1e300,0"}).look.towardLight;
    EXPECT_NEAR(huge.x, std::sqrt(0.5), 1e-15);
    EXPECT_NEAR(huge.y, std::sqrt(0.5), 1e-15);
    EXPECT_EQ(huge.z, 0.0);
    EXPECT_EQ(*parse({"m.obj", "-o", "x.png", "--up", "1e-300,0,0"}).up, glm::dvec3(1, 0, 0));
    EXPECT_EQ(*parse({"m.obj", "-o", "x.png", "--up", "0,-5e-324,0"}).up, glm::dvec3(0, -1, 0)); // subnormal
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--up", "0,0,0"}).find("--up: the direction must not be zero"),
              std::string::npos);
}

TEST(Options, ClipAndPointsWithinWhatFloat32AndDoubleHold) {
    EXPECT_EQ(*parse({"m.obj", "-o", "x.png", "--clip", "1e-30,1e-12"}).clipRange, glm::dvec2(1e-30, 1e-12));
    EXPECT_EQ(*parse({"m.obj", "-o", "x.png", "--clip", "1e12,1e30"}).clipRange, glm::dvec2(1e12, 1e30));
    EXPECT_EQ(*parse({"m.obj", "-o", "x.png", "--clip", "1e-15,1e14"}).clipRange, glm::dvec2(1e-15, 1e14));
    for (const char* clip : {"1e-38,10", "1e-31,1e-29", "1,1e31", "1e-20,1e11"})
        EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--clip", clip}).find("FAR/NEAR at most 1e30"),
                  std::string::npos)
            << clip;
    EXPECT_EQ(*parse({"m.obj", "-o", "x.png", "--eye", "1e15,-1e15,0"}).eye, glm::dvec3(1e15, -1e15, 0));
    EXPECT_NE(
        usageMessage({"m.obj", "-o", "x.png", "--target", "0,2e15,0"}).find("--target: coordinates must lie within"),
        std::string::npos);
}

TEST(Options, CameraFileOrAuto) {
    EXPECT_FALSE(parse({"m.obj", "-o", "x.png"}).autoCamera) << "the file's camera by default";
    EXPECT_TRUE(parse({"m.obj", "-o", "x.png", "--camera", "auto"}).autoCamera);
    EXPECT_FALSE(parse({"m.obj", "-o", "x.png", "--camera", "file"}).autoCamera);
    EXPECT_TRUE(cameraRequestOf(parse({"m.obj", "-o", "x.png", "--camera", "auto"})).ignoreFileCamera);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--camera", "orbit"})
                  .find("--camera: unknown value 'orbit' (available: file, auto)"),
              std::string::npos);
}

TEST(Options, SeveralModelsAListAndAShard) {
    const RenderOptions several = parse({"a.obj", "-o", "{name}.png", "b.glb", "c.stl"});
    EXPECT_EQ(several.modelPaths, std::vector<std::string>({"a.obj", "b.glb", "c.stl"}));
    EXPECT_EQ(several.modelPath, "a.obj");
    const RenderOptions listed = parse({"--list", "models.txt", "--shard", "2/5", "-o", "{name}.png"});
    EXPECT_TRUE(listed.modelPaths.empty());
    EXPECT_EQ(listed.listPath, "models.txt");
    ASSERT_TRUE(listed.shard.has_value());
    EXPECT_EQ(listed.shard->index, 2);
    EXPECT_EQ(listed.shard->count, 5);
    EXPECT_NE(usageMessage({"--list", "l.txt", "-o", "x.png", "--shard", "5/5"}).find("--shard"), std::string::npos);
    EXPECT_NE(usageMessage({"--list", "l.txt", "-o", "x.png", "--shard", "-1/5"}).find("--shard"), std::string::npos);
    EXPECT_NE(usageMessage({"--list", "l.txt", "-o", "x.png", "--shard", "1/0"}).find("--shard"), std::string::npos);
    EXPECT_NE(usageMessage({"--list", "l.txt", "-o", "x.png", "--shard", "3"}).find("expected K/N"), std::string::npos);
    EXPECT_NE(usageMessage({"--list", "", "-o", "x.png"}).find("--list: empty value"), std::string::npos);
}

TEST(Options, ContactSheetAndSvgOutputs) {
    const RenderOptions options = parse(
        {"m.obj", "--contact-sheet", "sheet.PNG", "--svg", "l.svg", "--lines", "contour", "--svg-tolerance", "0"});
    EXPECT_EQ(options.contactSheetPath, "sheet.PNG");
    EXPECT_EQ(options.svgPath, "l.svg");
    EXPECT_EQ(options.svgTolerance, 0.0);
    EXPECT_TRUE(rendersImages(options)) << "a contact sheet or an SVG alone renders";
    EXPECT_EQ(parse({"m.obj", "--svg", "l.svg", "--lines", "crease"}).svgTolerance, 0.5);
    EXPECT_NE(usageMessage({"m.obj", "--contact-sheet", "s.jpg"}).find("--contact-sheet: 's.jpg' must be a .png"),
              std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "--svg", "l.png", "--lines", "contour"}).find("must be a .svg"),
              std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "--svg", "l.svg", "--lines", "none"}).find("--svg: no line types"),
              std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--svg-tolerance", "1"}).find("--svg, which is not given"),
              std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "--svg", "l.svg", "--lines", "contour", "--svg-tolerance", "-1"})
                  .find("--svg-tolerance"),
              std::string::npos);
}

TEST(Options, PrintPlanAloneNeedsNoOutput) { EXPECT_NO_THROW(parse({"m.obj", "--print-plan"})); }

TEST(Options, HelpWhereAFlagStandsStopsParsing) {
    EXPECT_TRUE(parse({"m.obj", "-h", "--size", "bad"}).help);
    EXPECT_TRUE(parse({"--help"}).help) << "no model needed for help";
    EXPECT_NE(usageMessage({"m.obj", "--size", "bad", "--help"}).find("--size"), std::string::npos)
        << "a bad value before --help is still reported";
}

TEST(DumpFileName, TheWritersNameElseThePassAndField) {
    auto planned = [](std::string name, Format format, std::string fileName) {
        PlannedResource resource;
        resource.name = std::move(name);
        resource.desc.format = format;
        resource.presentation.fileName = std::move(fileName);
        return resource;
    };
    EXPECT_EQ(dumpFileName(planned("gbuffer.normal", Format::RGBA32F, "normal.exr")), "normal.exr");
    EXPECT_EQ(dumpFileName(planned("shade.color", Format::RGBA8, "shading.png")), "shading.png");
    EXPECT_EQ(dumpFileName(planned("other.thing", Format::R32F, "")), "other-thing.exr");
    EXPECT_EQ(dumpFileName(planned("mesh-edges.crease", Format::R8, "")), "mesh-edges-crease.png");
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

TEST(Options, ClipRange) {
    EXPECT_FALSE(parse({"m.obj", "-o", "x.png"}).clipRange);
    const RenderOptions options = parse({"m.obj", "-o", "x.png", "--clip", "1e-3,1e3"});
    ASSERT_TRUE(options.clipRange);
    EXPECT_EQ(options.clipRange->x, 1e-3);
    EXPECT_EQ(options.clipRange->y, 1e3);
    for (const char* bad : {"1", "1,2,3", "0,1", "-1,1", "2,1", "1,1", "nan,1", "1,inf", "a,1"})
        EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--clip", bad}).find("--clip"), std::string::npos) << bad;
}

} // namespace
} // namespace inkgraph
