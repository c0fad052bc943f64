// Style files (flags/StyleFile.h): parsing, their place before the command line, and messages naming file and line.
#include "flags/Options.h"
#include "flags/StyleFile.h"

#include "tests/support/TestFolder.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <fstream>

namespace inkgraph {
namespace {

std::string usageErrorOf(const std::function<void()>& action) {
    try {
        action();
    } catch (const UsageError& error) {
        return error.what();
    }
    ADD_FAILURE() << "expected a UsageError";
    return {};
}

RenderOptions optionsWith(const SourcedArguments& style, const std::vector<std::string>& commandLine) {
    SourcedArguments all = style;
    for (const std::string& argument : commandLine) {
        all.arguments.push_back(argument);
        all.origins.emplace_back();
    }
    return parseRenderOptions(all.arguments, all.origins);
}

TEST(StyleFile, SettingsBecomeFlagsWithListsCompactedAndCommentsDropped) {
    const SourcedArguments style =
        styleArguments("# house style\r\n\n  shading = comic  # the Winnemöller & Bangay look\n"
                       "shininess=64\nlines = contour, suggestive\n"
                       "contour-color = 0.1, 0.2, 0.3\n",
                       "look.style", "");
    EXPECT_EQ(style.arguments, (std::vector<std::string>{"--shading", "comic", "--shininess", "64", "--lines",
                                                         "contour,suggestive", "--contour-color", "0.1,0.2,0.3"}));
    ASSERT_EQ(style.origins.size(), style.arguments.size());
    EXPECT_EQ(style.origins[0], "--style 'look.style' line 3");
    EXPECT_EQ(style.origins[7], "--style 'look.style' line 6");

    const RenderOptions options = optionsWith(style, {"m.obj", "-o", "o.png"});
    EXPECT_EQ(options.look.shading, ShadingModel::Comic);
    EXPECT_EQ(options.look.shininess, 64.0);
    EXPECT_EQ(options.look.lines, (std::vector<std::string>{"contour", "suggestive"}));
    EXPECT_EQ(options.look.styleOf("contour").color, glm::dvec4(0.1, 0.2, 0.3, 1.0));
}

TEST(StyleFile, StrokeSettings) {
    // Issue 19's stroke flags are style settings like any other, lists compacted.
    const SourcedArguments style =
        styleArguments("lines = contour, suggestive\nmin-stroke-length = 0.02\nline-weight = depth, taper\n"
                       "overlapping-lines = merge\nsuggestive-seed = 0.08\n",
                       "strokes.style", "");
    EXPECT_EQ(style.arguments,
              (std::vector<std::string>{"--lines", "contour,suggestive", "--min-stroke-length", "0.02", "--line-weight",
                                        "depth,taper", "--overlapping-lines", "merge", "--suggestive-seed", "0.08"}));
    const RenderOptions options = optionsWith(style, {"m.obj", "-o", "o.png"});
    EXPECT_EQ(options.look.strokes.minLength, 0.02);
    EXPECT_TRUE(options.look.strokes.weightByDepth);
    EXPECT_FALSE(options.look.strokes.weightByStrength);
    EXPECT_TRUE(options.look.strokes.taperEnds);
    EXPECT_TRUE(options.look.strokes.mergeOverlaps);
}

TEST(StyleFile, TheCommandLineWinsOverTheStyle) {
    const SourcedArguments style = styleArguments("shading = phong\nshininess = 8\n", "s.style", "");
    const RenderOptions options = optionsWith(style, {"m.obj", "-o", "o.png", "--shininess", "100"});
    EXPECT_EQ(options.look.shading, ShadingModel::Phong);
    EXPECT_EQ(options.look.shininess, 100.0);
}

TEST(StyleFile, SettingsTheCommandLineMakesMootAreLeftOut) {
    // A house style used with another look: the command line's --shading, --lines and --shademap win, and the
    // style's settings they leave unused (comic's shininess, the crease's width, the cel bands) are left out, where
    // each was refused as a flag without effect, naming a flag the user never typed.
    const SourcedArguments style = styleArguments(
        "shading = comic\nshininess = 8\nlines = contour, crease\ncrease-width = 3\nbands = 4\n", "house.style", "");
    RenderOptions options = optionsWith(style, {"m.obj", "-o", "o.png", "--shading", "cel", "--lines", "contour"});
    EXPECT_EQ(options.look.shading, ShadingModel::Cel);
    EXPECT_EQ(options.look.lines, (std::vector<std::string>{"contour"}));
    EXPECT_EQ(options.look.bands, 4);
    options = optionsWith(style, {"m.obj", "-o", "o.png", "--shading", "cel", "--shademap", "map.png"});
    EXPECT_EQ(options.look.shadeMapPath, "map.png");
    EXPECT_FALSE(options.look.bands) << "the command line's --shademap wins over the style's bands";
    EXPECT_EQ(options.look.styleOf("crease").widthPixels, 3.0) << "crease is drawn: its width stays";
    // A width for a line type the style's own look leaves out is a default for the looks that draw it.
    EXPECT_NO_THROW(optionsWith(styleArguments("crease-width = 4\n", "s.style", ""), {"m.obj", "-o", "o.png"}));
    // The same flags on the command line are still refused: there the user asked for them.
    EXPECT_EQ(usageErrorOf([&] {
                  optionsWith(style, {"m.obj", "-o", "o.png", "--shading", "cel", "--shininess", "9"});
              }),
              "--shininess has no effect with --shading cel (it applies to phong and comic)");
    EXPECT_NE(
        usageErrorOf([&] {
            optionsWith(style, {"m.obj", "-o", "o.png", "--shading", "cel", "--bands", "2", "--shademap", "map.png"});
        }).find("both choose the cel shade map"),
        std::string::npos);
}

TEST(StyleFile, BlanksInsideAValueStay) {
    // Only the blanks around a list's commas go: "1 5" was read as 15, a texture's "my map.png" as "mymap.png".
    const SourcedArguments style =
        styleArguments("contour-width = 1 5\noutline-width-map = texture:maps/my map.png:R\n", "s.style", "");
    EXPECT_EQ(style.arguments[1], "1 5");
    EXPECT_EQ(style.arguments[3], "texture:maps/my map.png:R");
    EXPECT_EQ(usageErrorOf([&] {
                  optionsWith(style, {"m.obj", "-o", "o.png"});
              }),
              "--style 's.style' line 1: --contour-width: '1 5' is not a number");
}

TEST(StyleFile, ShadeMapPathsAreRelativeToTheStyleFileAndKeepTheirSpaces) {
    const SourcedArguments relative = styleArguments("shademap = maps/my map.png\n", "s.style", "looks");
    EXPECT_EQ(relative.arguments[1], "looks/maps/my map.png");
    const SourcedArguments absolute = styleArguments("shademap = /maps/a.png\n", "s.style", "looks");
    EXPECT_EQ(absolute.arguments[1], "/maps/a.png");
}

TEST(StyleFile, BadLinesNameTheFileTheLineAndTheProblem) {
    auto message = [](const std::string& text) {
        return usageErrorOf([&] { styleArguments(text, "look.style", ""); });
    };
    EXPECT_EQ(message("shading comic\n"), "--style 'look.style' line 1: expected NAME = VALUE, got 'shading comic'");
    EXPECT_NE(message("\n\neye = 0,0,5\n").find("line 3: 'eye' is not a style setting"), std::string::npos);
    EXPECT_NE(message("output = x.png\n").find("'output' is not a style setting"), std::string::npos);
    EXPECT_NE(message("shading = cel\nshading = comic\n").find("line 2: 'shading' is set twice"), std::string::npos);
    EXPECT_NE(message("bands =   \n").find("'bands' has no value"), std::string::npos);
    EXPECT_NE(message(std::string("bands = 4\0", 10)).find("NUL"), std::string::npos);
    // CR line ends (classic Mac OS) joined the lines into one setting: 'comiclines=contour', which the file lacks.
    EXPECT_EQ(message("shading = comic\rlines = contour\r"),
              "--style 'look.style' line 1: a carriage return inside the line (CR line ends?); a style's lines end "
              "with LF or CRLF");
}

TEST(StyleFile, ValueProblemsFoundByTheFlagParserCarryTheStyleLine) {
    const SourcedArguments style = styleArguments("shading = comic\nshininess = lots\n", "look.style", "");
    const std::string message = usageErrorOf([&] { optionsWith(style, {"m.obj", "-o", "o.png"}); });
    EXPECT_EQ(message, "--style 'look.style' line 2: --shininess: 'lots' is not a number");
}

TEST(StyleFile, EveryStyleSettingIsAFlagTheParserKnows) {
    // A style setting the parser did not know would fail every style that uses it.
    for (const std::string& name : styleSettingNames()) {
        const std::string message = usageErrorOf([&] { parseRenderOptions({"m.obj", "-o", "o.png", "--" + name}); });
        EXPECT_EQ(message, "--" + name + ": missing value") << name;
    }
}

class StyleFileOnDisk : public test::TestFolder {};

TEST_F(StyleFileOnDisk, ExpandPutsTheSettingsFirstAndKeepsTheFlagForTheRecord) {
    const std::string path = (directory / "look.style").string();
    std::ofstream(path) << "shading = flat\n";
    const SourcedArguments expanded = expandStyleFile({"m.obj", "--style", path, "-o", "o.png"});
    EXPECT_EQ(expanded.arguments,
              (std::vector<std::string>{"--shading", "flat", "m.obj", "--style", path, "-o", "o.png"}));
    const RenderOptions options = parseRenderOptions(expanded.arguments, expanded.origins);
    EXPECT_EQ(options.look.shading, ShadingModel::Flat);
    EXPECT_EQ(options.stylePath, path);
}

TEST_F(StyleFileOnDisk, StyleEqualsFileIsTheStyleFlag) {
    const std::string path = (directory / "look.style").string();
    std::ofstream(path) << "shading = flat\n";
    const SourcedArguments expanded = expandStyleFile({"m.obj", "--style=" + path, "--size=64x64", "-o", "o.png"});
    EXPECT_EQ(expanded.arguments, (std::vector<std::string>{"--shading", "flat", "m.obj", "--style", path, "--size",
                                                            "64x64", "-o", "o.png"}));
    EXPECT_EQ(expanded.origins.size(), expanded.arguments.size());
    EXPECT_EQ(parseRenderOptions(expanded.arguments, expanded.origins).look.shading, ShadingModel::Flat);
    EXPECT_EQ(usageErrorOf([&] {
                  expandStyleFile({"--style=" + path, "--style", path});
              }),
              "--style: given twice ('" + path + "', '" + path + "')");
}

TEST_F(StyleFileOnDisk, UnreadableOversizedOrRepeatedStylesAreUsageErrors) {
    EXPECT_EQ(usageErrorOf([&] {
                  expandStyleFile({"--style", (directory / "none").string()});
              }),
              "--style: '" + (directory / "none").string() + "': file not found");
    EXPECT_NE(usageErrorOf([&] {
                  expandStyleFile({"--style", directory.string()});
              }).find("not a regular file"),
              std::string::npos);
    const std::string big = (directory / "big.style").string();
    std::ofstream(big) << std::string(70000, '#');
    EXPECT_NE(usageErrorOf([&] { expandStyleFile({"--style", big}); }).find("is 70000 bytes"), std::string::npos);
    EXPECT_NE(usageErrorOf([&] {
                  expandStyleFile({"--style", big, "--style", big});
              }).find("given twice"),
              std::string::npos);
    EXPECT_EQ(usageErrorOf([&] { expandStyleFile({"m.obj", "--style"}); }), "--style: missing FILE");
    EXPECT_EQ(usageErrorOf([&] { expandStyleFile({"m.obj", "--style="}); }), "--style: empty value");
}

} // namespace
} // namespace inkgraph
