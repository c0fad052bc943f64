// The flag table and the registries it is generated from: every registered line type, line parameter and shading
// model gets its flags, style names, help and refusals without code of its own in app/.
#include "tests/app/OptionsTestSupport.h"
#include "flags/FlagTable.h"
#include "flags/Options.h"
#include "flags/StyleFile.h"
#include "passes/lines/LineTypes.h"
#include "passes/shade/ShadingModel.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <regex>
#include <set>

namespace inkgraph {
namespace {

using test::usageMessage;

bool isStyleName(const std::string& name) {
    const std::vector<std::string>& names = styleSettingNames();
    return std::find(names.begin(), names.end(), name) != names.end();
}

TEST(LineTypeRegistry, NamesAreUniqueAndEveryTypeCanBuildAndDescribeItself) {
    std::set<std::string> names;
    for (const LineType& type : lineTypes()) {
        EXPECT_TRUE(names.insert(type.name).second) << type.name << " registered twice";
        EXPECT_TRUE(bool(type.build)) << type.name;
        EXPECT_FALSE(type.help.empty()) << type.name;
        EXPECT_EQ(findLineType(type.name), &type);
    }
    EXPECT_EQ(findLineType("no-such-type"), nullptr);
    EXPECT_TRUE(names.count("material-boundary"));
}

TEST(LineTypeRegistry, ParametersAreListedOnceWithTheTypesThatUseThem) {
    const std::vector<const LineParameter*> parameters = lineParameters();
    std::set<std::string> names;
    for (const LineParameter* parameter : parameters) EXPECT_TRUE(names.insert(parameter->name).second);
    EXPECT_EQ(lineTypesUsing(&line_parameters::kCreaseAngle),
              (std::vector<std::string>{"hidden-crease", "normal-edge", "crease"}));
    // --supersample applies to every type stroked on the CPU: all but the two GL-drawn ones.
    const std::vector<std::string> supersampled = lineTypesUsing(nullptr);
    EXPECT_EQ(supersampled.size(), lineTypes().size() - 2);
    EXPECT_EQ(std::count(supersampled.begin(), supersampled.end(), "outline"), 0);
    EXPECT_EQ(std::count(supersampled.begin(), supersampled.end(), "material-boundary"), 1);
}

TEST(FlagTable, EveryLineTypeHasItsFlagsStyleNamesAndHelp) {
    const std::string help = renderHelp();
    for (const LineType& type : lineTypes()) {
        for (const char* property : {"-width", "-color"}) {
            const std::string flag = "--" + type.name + property;
            EXPECT_NE(findFlag(flag), nullptr) << flag;
            EXPECT_TRUE(isStyleName(type.name + property)) << flag;
        }
        EXPECT_NE(help.find("  " + type.name + ": "), std::string::npos) << type.name << " is not in --help";
        // A width flag without its type in --lines is refused, naming the type.
        EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--lines", "none", "--" + type.name + "-width", "3"})
                      .find("'" + type.name + "' line type is not drawn"),
                  std::string::npos)
            << type.name;
    }
    for (const LineParameter* parameter : lineParameters()) {
        EXPECT_NE(findFlag("--" + parameter->name), nullptr) << parameter->name;
        EXPECT_TRUE(isStyleName(parameter->name)) << parameter->name;
        EXPECT_NE(help.find("--" + parameter->name + " " + parameter->valueName), std::string::npos) << parameter->name;
    }
}

TEST(FlagTable, ParametersAreRangeCheckedFromTheirDeclaration) {
    for (const LineParameter* parameter : lineParameters()) {
        if (parameter->isChoice()) {
            EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--lines", lineTypesUsing(parameter).front(),
                                    "--" + parameter->name, "bogus"})
                          .find("--" + parameter->name + ": expected"),
                      std::string::npos);
            continue;
        }
        // Just outside the lower bound (or on it, when open) is refused with the declared words.
        const std::string low =
            parameter->lowOpen ? std::to_string(parameter->low) : std::to_string(parameter->low - 1);
        const std::string message = usageMessage(
            {"m.obj", "-o", "x.png", "--lines", lineTypesUsing(parameter).front(), "--" + parameter->name, low});
        EXPECT_NE(message.find(parameter->rangeText), std::string::npos) << parameter->name << ": " << message;
    }
}

/** A value in a parameter's range that the line kernels' float holds only as 0 or a denormal (--depth-jump 1e-46)
 *  reached them as 0 and failed inside the render with an internal error; it is refused as a usage error. */
TEST(FlagTable, ParametersRefuseWhatTheKernelsFloatCannotHold) {
    for (const LineParameter* parameter : lineParameters()) {
        if (parameter->isChoice() || parameter->low > 0.0 || parameter->high < 1e-40) continue;
        for (const std::string tiny : {"1e-46", "1e-300", "4e-39"}) {
            const std::string message = usageMessage(
                {"m.obj", "-o", "x.png", "--lines", lineTypesUsing(parameter).front(), "--" + parameter->name, tiny});
            EXPECT_NE(message.find("--" + parameter->name + ": '" + tiny + "' is under 1.2e-38"), std::string::npos)
                << message;
        }
    }
    const std::string message = usageMessage({"m.obj", "-o", "x.png", "--depth-jump", "1e-30"});
    EXPECT_EQ(message.find("1.2e-38"), std::string::npos) << "a float holds 1e-30: " << message;
}

/** What is wrong with a number is said: '+2' is 2, blanks and words are named as such, and 1e-400 as beyond a
 *  double (all were "not a finite number"). */
TEST(FlagTable, ANumbersProblemIsNamed) {
    EXPECT_DOUBLE_EQ(parseFlagNumber("--x", "+2"), 2.0);
    EXPECT_DOUBLE_EQ(parseFlagNumber("--x", "+.5e+1"), 5.0);
    EXPECT_DOUBLE_EQ(parseFlagNumber("--x", "-0.25"), -0.25);
    const auto messageOf = [](const std::string& text) {
        try {
            parseFlagNumber("--x", text);
        } catch (const std::invalid_argument& error) {
            return std::string(error.what());
        }
        return std::string("(accepted)");
    };
    EXPECT_EQ(messageOf(" 2"), "--x: ' 2' has blanks around the number");
    EXPECT_EQ(messageOf("2\t"), "--x: '2\t' has blanks around the number");
    EXPECT_EQ(messageOf("+-2"), "--x: '+-2' is not a number");
    EXPECT_EQ(messageOf("++2"), "--x: '++2' is not a number");
    EXPECT_EQ(messageOf("0x10"), "--x: '0x10' is not a number");
    EXPECT_EQ(messageOf(""), "--x: '' is not a number");
    EXPECT_EQ(messageOf("1e-400"), "--x: '1e-400' lies beyond a double's range (about 1e-308 to 1e308)");
    EXPECT_EQ(messageOf("1e400"), "--x: '1e400' lies beyond a double's range (about 1e-308 to 1e308)");
    EXPECT_EQ(messageOf("nan"), "--x: 'nan' is not a finite number");
    EXPECT_EQ(messageOf("-inf"), "--x: '-inf' is not a finite number");
    EXPECT_EQ(usageMessage({"m.obj", "-o", "x.png", "--contour-width", "+3"}), "(no error)");
    // Whole numbers take the '+' too (and still no point or exponent).
    const RenderOptions plus = parseRenderOptions(
        {"m.obj", "-o", "x.png", "--size", "+64x+32", "--supersample", "+2", "--seed", "+7", "--views", "+3"});
    EXPECT_EQ(plus.width, 64);
    EXPECT_EQ(plus.height, 32);
    EXPECT_EQ(plus.look.supersample, 2);
    EXPECT_EQ(plus.viewSampling.seed, 7u);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--supersample", "+-2"}).find("expected a whole number"),
              std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--seed", "+-2"}).find("expected a whole number"),
              std::string::npos);
    EXPECT_NE(usageMessage({"m.obj", "-o", "x.png", "--supersample", "+"}).find("expected a whole number"),
              std::string::npos);
}

TEST(FlagTable, ParametersStateTheirDeclaredDefaultInTheHelp) {
    // The default is written once, in the declaration; the help says "{default}" where --help writes it.
    const std::regex typedDefault(R"(default [0-9])");
    std::size_t numbersWithDefaults = 0;
    for (const LineParameter* parameter : lineParameters()) {
        EXPECT_FALSE(std::regex_search(parameter->help, typedDefault))
            << parameter->name << " types its default into its help; write {default}";
        const Flag* entry = findFlag("--" + parameter->name);
        ASSERT_NE(entry, nullptr) << parameter->name;
        EXPECT_EQ(entry->help.find("{default}"), std::string::npos) << parameter->name;
        if (parameter->isChoice() || !parameter->defaultNumber) continue;
        ++numbersWithDefaults;
        EXPECT_NE(parameter->help.find("default {default}"), std::string::npos)
            << parameter->name << " has a default its help does not state";
    }
    EXPECT_GE(numbersWithDefaults, 9u);
}

TEST(FlagTable, ShadingFlagsFollowTheTraitTable) {
    // --shininess is refused for every model without the specular trait, with the models that take it named.
    for (const ShadingModelTraits& model : shadingModels()) {
        const std::string message = usageMessage({"m.obj", "-o", "x.png", "--shading", model.name, "--shininess", "4"});
        if (model.specular)
            EXPECT_EQ(message, "(no error)") << model.name;
        else
            EXPECT_EQ(message, std::string("--shininess has no effect with --shading ") + model.name +
                                   " (it applies to phong and comic)");
        EXPECT_NE(renderHelp().find(model.name), std::string::npos);
    }
    EXPECT_EQ(shadingModelsWith(&ShadingModelTraits::shadeMap), "cel, comic and auto");
    EXPECT_EQ(findShadingModel("comic")->model, ShadingModel::Comic);
    EXPECT_EQ(findShadingModel("toon"), nullptr);
}

TEST(FlagTable, HelpKeepsItsColumns) {
    // Every help line fits 120 columns; flag descriptions start at column 25.
    const std::string help = renderHelp();
    std::size_t start = 0;
    while (start < help.size()) {
        const std::size_t end = help.find('\n', start);
        const std::string line = help.substr(start, end - start);
        EXPECT_LE(line.size(), 120u) << line;
        start = end == std::string::npos ? help.size() : end + 1;
    }
    EXPECT_NE(help.find("\n  --size WxH" + std::string(13, ' ') + "image size"), std::string::npos);
    EXPECT_NE(help.find("\n  -o, --output FILE" + std::string(6, ' ') + "the final picture"), std::string::npos);
    // A label too long for the column puts its description on the next line, at the column.
    EXPECT_NE(help.find("\n  --contact-sheet FILE.png\n" + std::string(25, ' ') + "every buffer"), std::string::npos);
}

} // namespace
} // namespace inkgraph
