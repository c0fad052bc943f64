// Docs that cannot drift (issue 32): the generated sections of README.md and docs/robustness.md are what the code
// generates now (app/GeneratedDocs.h), and every registered line type, flag, shading model, G-buffer field and dump
// file is named in the doc that lists it. A failure names the section or the missing name, and the fix.
#include "flags/FlagTable.h"
#include "app/GeneratedDocs.h"
#include "passes/gbuffer/GBufferPass.h"
#include "passes/lines/LineTypes.h"
#include "passes/shade/ShadingModel.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace inkgraph {
namespace {

std::string readDoc(const std::string& relative) {
    std::ifstream in(std::string(INKGRAPH_SOURCE_ROOT) + "/" + relative, std::ios::binary);
    EXPECT_TRUE(in.good()) << "cannot read " << relative;
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

const std::string kEnd = "<!-- end generated -->\n";
std::string beginMarker(const std::string& section) { return "<!-- generated: " + section + " -->\n"; }

/** The text between a section's markers in `doc`, or an error message. */
struct Region {
    bool found = false;
    std::string text;
    std::string problem;
};
Region regionOf(const std::string& doc, const std::string& section) {
    const std::string begin = beginMarker(section);
    const std::size_t start = doc.find(begin);
    if (start == std::string::npos) return {false, "", "no line '" + begin.substr(0, begin.size() - 1) + "'"};
    if (doc.find(begin, start + 1) != std::string::npos) return {false, "", "the section is there twice"};
    const std::size_t from = start + begin.size();
    const std::size_t end = doc.find(kEnd, from);
    if (end == std::string::npos) return {false, "", "no '<!-- end generated -->' after its start"};
    return {true, doc.substr(from, end - from), ""};
}

std::vector<std::string> linesOf(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
}

/** A diff-like account of the first difference: the line number within the section, what the code generates and
 *  what the doc has. */
std::string firstDifference(const std::string& generated, const std::string& doc) {
    const std::vector<std::string> want = linesOf(generated), have = linesOf(doc);
    for (std::size_t i = 0; i < std::max(want.size(), have.size()); ++i) {
        const std::string wanted = i < want.size() ? want[i] : "(nothing)";
        const std::string had = i < have.size() ? have[i] : "(nothing)";
        if (wanted != had)
            return "first difference at line " + std::to_string(i + 1) + " of the section:\n- " + had + "\n+ " +
                   wanted + "\n(" + std::to_string(have.size()) + " lines in the doc, " + std::to_string(want.size()) +
                   " generated)";
    }
    return "they differ in whitespace only";
}

/** Whether `name` occurs in `doc` as a whole token: not inside a longer name of letters, digits, '-', '_' or '.'. */
bool namesToken(const std::string& doc, const std::string& name) {
    const auto partOfName = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_'; };
    for (std::size_t at = doc.find(name); at != std::string::npos; at = doc.find(name, at + 1)) {
        const bool startsToken = at == 0 || !partOfName(doc[at - 1]);
        const std::size_t after = at + name.size();
        const bool endsToken = after == doc.size() || !partOfName(doc[after]);
        if (startsToken && endsToken) return true;
    }
    return false;
}

TEST(GeneratedDocs, ReadmeSectionsAreWhatTheCodeGenerates) {
    for (const std::string& section : generatedDocSections()) {
        const std::string path = generatedDocPath(section);
        const Region region = regionOf(readDoc(path), section);
        if (!region.found) {
            ADD_FAILURE() << path << ": generated section '" << section << "': " << region.problem;
            continue;
        }
        const std::string generated = generatedDocSection(section);
        EXPECT_TRUE(region.text == generated)
            << path << ": generated section '" << section << "' differs from what the code generates; run "
            << "scripts/update-docs.sh (it rewrites the section from 'inkgraph help --docs " << section << "'). "
            << firstDifference(generated, region.text);
    }
}

TEST(GeneratedDocs, EverySectionHasAName) {
    EXPECT_THROW(generatedDocSection("no-such-section"), std::invalid_argument);
    for (const std::string& section : generatedDocSections()) EXPECT_FALSE(generatedDocSection(section).empty());
}

TEST(DocsComplete, EveryLineTypeIsInTheReadmeAndHasARowInLinesMd) {
    const std::string readme = readDoc("README.md"), lines = readDoc("docs/lines.md");
    for (const LineType& type : lineTypes()) {
        EXPECT_TRUE(namesToken(readme, "`" + type.name + "`")) << "README.md does not name line type " << type.name;
        EXPECT_NE(lines.find("\n| " + type.name + " |"), std::string::npos)
            << "docs/lines.md's table has no row '| " << type.name << " |'";
    }
}

TEST(DocsComplete, EveryFlagIsInTheReadme) {
    // A flag is named by one of its names, in code quotes ("`-o FILE`"); the flags a pattern stands for
    // (--outline-width for --TYPE-width) are named by the pattern, which is a help-only entry's label.
    const std::string readme = readDoc("README.md");
    for (const Flag& flag : renderFlags()) {
        std::vector<std::string> names = flag.names;
        if (flag.names.empty() || flag.help.empty()) {
            if (flag.helpLabel.empty()) continue; // a flag a pattern entry stands for: the pattern is checked
            names = {flag.helpLabel.substr(0, flag.helpLabel.find(' '))};
        }
        bool named = false;
        for (const std::string& name : names) named = named || namesToken(readme, "`" + name);
        std::string all;
        for (const std::string& name : names) all += (all.empty() ? "" : " or ") + name;
        EXPECT_TRUE(named) << "README.md does not name the render flag " << all
                           << " (flags/FlagTable.cpp; the Rendering table lists every flag)";
    }
}

TEST(DocsComplete, EveryShadingModelIsInShadingMd) {
    const std::string shading = readDoc("docs/shading.md");
    // Its table of models has a row per model ("| cel (default) |").
    for (const ShadingModelTraits& model : shadingModels())
        EXPECT_TRUE(namesToken(shading, std::string("\n| ") + model.name))
            << "docs/shading.md's table of models has no row '| " << model.name << " |'";
}

TEST(DocsComplete, EveryGBufferFieldIsInApiMdsBufferTable) {
    const std::string api = readDoc("docs/api.md");
    for (const GBufferPass::Field& field : GBufferPass::fields())
        EXPECT_NE(api.find(std::string("| `gbuffer.") + field.name + "` |"), std::string::npos)
            << "docs/api.md's buffer table has no row for gbuffer." << field.name;
}

TEST(DocsComplete, EveryDumpFileIsInTheReadme) {
    const std::string readme = readDoc("README.md");
    const std::vector<DumpFileDoc> files = dumpFileDocs();
    ASSERT_FALSE(files.empty());
    for (const DumpFileDoc& file : files)
        EXPECT_TRUE(namesToken(readme, file.file)) << "README.md does not name --dump's file " << file.file;
}

/** The dump files cover what the registries hold: every G-buffer field, every line type's layer, shading, final. */
TEST(DocsComplete, TheDumpFilesComeFromEveryPass) {
    std::vector<std::string> resources;
    for (const DumpFileDoc& file : dumpFileDocs()) resources.push_back(file.resource);
    const auto has = [&resources](const std::string& resource) {
        return std::find(resources.begin(), resources.end(), resource) != resources.end();
    };
    for (const GBufferPass::Field& field : GBufferPass::fields())
        EXPECT_TRUE(has(std::string("gbuffer.") + field.name)) << field.name;
    EXPECT_TRUE(has(std::string("gbuffer.") + GBufferPass::kZBuffer));
    for (const LineType& type : lineTypes()) EXPECT_TRUE(has("strokes." + type.name)) << type.name;
    EXPECT_TRUE(has("shade.color"));
    EXPECT_TRUE(has("composite.final"));
}

} // namespace
} // namespace inkgraph
