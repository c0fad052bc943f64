#include "app/GeneratedDocs.h"

#include "app/StillOutputs.h"
#include "render/StillRenderer.h"
#include "gl/ShaderLibrary.h"
#include "graph/Pass.h"
#include "graph/Plan.h"
#include "passes/GpuScene.h"
#include "passes/StillGraph.h"
#include "passes/lines/LineTypes.h"
#include "passes/shade/ShadingModel.h"
#include "scene/Warning.h"
#include "scene/mesh/Procedural.h"

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
        for (const LineParameter* parameter : type.parameters)
            settings += (settings.empty() ? "" : " ") + code("--" + parameter->name + " " + parameter->valueName);
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
    static const std::vector<std::string> kSections = {"line-types", "dump-files", "warning-codes"};
    return kSections;
}

std::string generatedDocPath(const std::string& name) {
    return name == "warning-codes" ? "docs/robustness.md" : "README.md";
}

std::string generatedDocSection(const std::string& name) {
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
    const Scene scene = makeScene(makeUvSphere({0.0f, 0.0f, 0.0f}, 1.0f, 16, 8));
    const BoundingSphere sphere = computeBoundingSphere(scene);
    const Camera camera = resolveCamera(CameraRequest{}, scene);
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
