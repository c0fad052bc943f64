#include "app/GeneratedDocs.h"

#include "app/StillOutputs.h"
#include "flags/FlagTable.h"
#include "render/StillRenderer.h"
#include "gl/ShaderLibrary.h"
#include "graph/Pass.h"
#include "graph/Plan.h"
#include "passes/GpuScene.h"
#include "passes/StillGraph.h"
#include "passes/lines/LineTypes.h"
#include "passes/lines/types/SuggestiveLines.h"
#include "passes/shade/ShadingModel.h"
#include "scene/Warning.h"
#include "scene/mesh/Procedural.h"

#include <cctype>
#include <cstring>
#include <set>
#include <stdexcept>

namespace inkgraph {
namespace {

/** `text` as one Markdown table cell: help lines joined, pipes escaped. */
std::string cell(const std::string& text) {
    std::string out;
    for (char c : text) {
        if (c == '\n')
            out += ' ';
        else if (c == '|')
            out += "\\|";
        else
            out += c;
    }
    return out;
}

std::string code(const std::string& text) { return "`" + text + "`"; }

/** `text` with each path of a Markdown doc the help names ("docs/batch.md", "shademaps/README.md") made a link, so the
 *  README's table leads where --help points. */
std::string linkedDocPaths(const std::string& text) {
    const auto partOfPath = [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || std::strchr("_./-", c);
    };
    std::string out;
    std::size_t at = 0;
    while (at < text.size()) {
        const bool startsPath = (at == 0 || !partOfPath(text[at - 1])) &&
                                (text.compare(at, 5, "docs/") == 0 || text.compare(at, 10, "shademaps/") == 0);
        std::size_t end = at;
        while (startsPath && end < text.size() && partOfPath(text[end])) ++end;
        while (end > at && text[end - 1] == '.') --end; // a sentence's full stop is not part of the path
        const std::string path = text.substr(at, end - at);
        if (startsPath && path.size() > 3 && path.compare(path.size() - 3, 3, ".md") == 0) {
            out += "[" + path + "](" + path + ")";
            at = end;
        } else {
            out += text[at++];
        }
    }
    return out;
}

/** Help text as Markdown table text: a cell, with what Markdown would take for markup escaped ('<' of
 *  "lines-<type>.png" would open an HTML tag, the '*' of 'gbuffer.*' emphasis). */
std::string markdownText(const std::string& text) {
    std::string out;
    for (char c : cell(text)) {
        if (c == '<')
            out += "&lt;";
        else if (c == '*')
            out += "\\*";
        else
            out += c;
    }
    return linkedDocPaths(out);
}

/** A flag's label as --help writes it, each name in code: "`-o`, `--output FILE`", "`--TYPE-width PX`". */
std::string flagLabel(const Flag& entry) {
    if (!entry.helpLabel.empty()) return code(cell(entry.helpLabel));
    std::string label;
    for (std::size_t i = 0; i < entry.names.size(); ++i) {
        const bool last = i + 1 == entry.names.size();
        // A value name may hold a '|' ("AZ,EL[,DIST|,xS]"), which would end the cell.
        label += (i == 0 ? "" : ", ") +
                 code(cell(entry.names[i] + (last && !entry.valueName.empty() ? " " + entry.valueName : "")));
    }
    return label;
}

/** A flag's --help text as one cell: its paragraphs run on, each list item ("  auto: ...") on a line of its own. The
 *  items of --lines are left out: they are the line types, which the README's line-types table lists below it. */
std::string flagHelpCell(const Flag& entry) {
    const bool linesFlag = entry.names == std::vector<std::string>{"--lines"};
    std::string text;
    for (const std::string& block : helpBlocks(entry.help)) {
        if (block.rfind("  ", 0) != 0) {
            if (!text.empty()) text += ' ';
            text += markdownText(block);
            continue;
        }
        if (linesFlag) continue;
        const std::string item = block.substr(2);
        const std::size_t colon = item.find(": ");
        text += "<br>";
        text += colon == std::string::npos ? markdownText(item)
                                           : code(item.substr(0, colon)) + ": " + markdownText(item.substr(colon + 2));
    }
    if (linesFlag) text += " (the types: [line types](#line-types) below)";
    return text;
}

/** The flags of `inkgraph render` as --help lists them, a row each, under a row per help section. */
std::string renderFlagsTable() {
    std::string text = "| flag | what it does (`--help`) |\n|---|---|\n";
    for (HelpSection section : helpSections()) {
        const std::string title = helpSectionTitle(section);
        const std::size_t aside = title.find(" (");
        text += "| **" + title.substr(0, aside) + "** |";
        if (aside != std::string::npos) {
            text += ' ';
            text += markdownText(title.substr(aside + 2, title.size() - aside - 3));
        }
        text += " |\n";
        for (const Flag& entry : renderFlags()) {
            if (entry.section != section || entry.help.empty()) continue;
            // A note of the section (no label) goes in a row of its own, under the flags it speaks of.
            const std::string label = entry.names.empty() && entry.helpLabel.empty() ? "" : flagLabel(entry);
            text += "| " + label + " | " + flagHelpCell(entry) + " |\n";
        }
    }
    return text;
}

const char* familyText(LineFamily family) {
    switch (family) {
    case LineFamily::GlDrawn: return "a band GL draws at the output size";
    case LineFamily::ImageSpace: return "in the G-buffer, on the CPU";
    case LineFamily::MeshEdge: return "the mesh's edges, drawn by GL as a skeleton";
    case LineFamily::ObjectSpace: return "on the mesh, on the CPU";
    }
    return "";
}

std::string lineTypesSection() {
    std::string text = "| `--lines` type | found | what it draws (`--help`) | its settings besides `--TYPE-width`, "
                       "`--TYPE-color` |\n|---|---|---|---|\n";
    for (const LineType& type : lineTypes()) {
        std::string settings;
        for (const LineParameter* parameter : type.parameters) {
            if (!settings.empty()) settings += ' ';
            settings += code("--" + parameter->name + " " + parameter->valueName);
        }
        text += "| " + code(type.name) + " | " + familyText(type.family) + " | " + cell(type.help) + " | " +
                (settings.empty() ? "-" : settings) + " |\n";
    }
    return text;
}

std::string storedAs(Format format) {
    switch (format) {
    case Format::RGBA32F:
    case Format::RGBA16F: return "EXR, 4 x float32";
    case Format::R32F:
    case Format::R16F:
    case Format::Depth32F: return "EXR, 1 x float32";
    case Format::RGBA8: return "PNG, 4 x 8-bit sRGB";
    case Format::R8: return "PNG, 1 x 8-bit";
    }
    return "";
}

std::string dumpFilesSection() {
    std::string text = "| file | stored as | resource | what it holds |\n|---|---|---|---|\n";
    for (const DumpFileDoc& file : dumpFileDocs())
        text += "| " + cell(file.file) + " | " + file.storedAs + " | " +
                (file.resource.empty() ? "-" : code(file.resource)) + " | " + cell(file.meaning) + " |\n";
    return text;
}

std::string warningCodesSection() {
    std::string text = "| code | meaning |\n|---|---|\n";
    for (const WarningCode& row : warningCodes())
        text += "| " + code(std::string(row.code)) + " | " + cell(std::string(row.meaning)) + " |\n";
    return text;
}

} // namespace

const std::vector<std::string>& generatedDocSections() {
    static const std::vector<std::string> kSections = {"render-flags", "line-types", "dump-files", "warning-codes"};
    return kSections;
}

std::string generatedDocPath(const std::string& name) {
    return name == "warning-codes" ? "docs/robustness.md" : "README.md";
}

std::string generatedDocSection(const std::string& name) {
    if (name == "render-flags") return renderFlagsTable();
    if (name == "line-types") return lineTypesSection();
    if (name == "dump-files") return dumpFilesSection();
    if (name == "warning-codes") return warningCodesSection();
    std::string names;
    for (const std::string& section : generatedDocSections()) names += (names.empty() ? "" : ", ") + section;
    throw std::invalid_argument("generatedDocSection(): no section '" + name + "' (sections: " + names + ")");
}

std::vector<DumpFileDoc> dumpFileDocs() {
    // A still graph registers every line type's passes and the shading model's; drawing every type and trying each
    // model makes every pass the code has register. Declaring needs no GL: the passes are never prepared or run.
    // Two meshes: surfaces that meet, so the kernels that read triangle ids where they do declare it.
    Scene scene = makeScene(makeUvSphere({0.0f, 0.0f, 0.0f}, 1.0f, 16, 8));
    scene.meshes.push_back(scene.meshes.front());
    const BoundingSphere sphere = computeBoundingSphere(scene);
    // At 2048 rows, so the suggestive contours' own G-buffer registers too, with the fields its kernel reads
    // (passes/lines/types/SuggestiveLines.h).
    CameraRequest request;
    request.width = request.height = 2 * kSuggestiveFieldMinRows;
    const Camera camera = resolveCamera(request, scene);
    ShaderLibrary shaders;
    std::vector<DumpFileDoc> files;
    std::set<std::string> seen;
    // The default look's model first, so the files come in the order a default run writes them.
    std::vector<ShadingModel> models = {Look{}.shading};
    for (const ShadingModelTraits& model : shadingModels())
        if (model.model != models.front()) models.push_back(model.model);
    for (ShadingModel model : models) {
        Look look;
        look.shading = model;
        for (const LineType& type : lineTypes()) look.lines.push_back(type.name);
        const FrameParams frame = frameParamsOf(look, scene, camera, sphere);
        GpuScene gpuScene(scene, sphere.center);
        const StillGraph graph = buildStillGraph({look, shaders, scene, sphere, gpuScene, frame, std::nullopt});
        for (const Pass* pass : graph.view()) {
            PassBuilder builder{std::string(pass->name())};
            pass->declare(builder);
            for (const PassBuilder::Write& write : builder.writes()) {
                if (!write.isImage()) continue; // data without a picture (the strokes) is not dumped
                PlannedResource resource;
                resource.name = builder.passName() + "." + write.field;
                resource.desc = write.desc;
                resource.presentation = write.presentation;
                const std::string file = dumpFileName(resource);
                if (!seen.insert(file).second) continue;
                files.push_back({file, resource.name, storedAs(write.desc.format),
                                 write.presentation.meaning.empty() ? std::string(formatName(write.desc.format))
                                                                    : write.presentation.meaning});
            }
        }
    }
    files.push_back({"manifest.json", "", "JSON", kDumpManifestMeaning});
    return files;
}

} // namespace inkgraph
