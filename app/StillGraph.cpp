#include "app/StillGraph.h"

#include "passes/composite/CompositePass.h"
#include "passes/edges/MeshEdgesPass.h"
#include "passes/gbuffer/GBufferPass.h"
#include "passes/lines/LineLayerPass.h"
#include "passes/outline/OutlinePass.h"
#include "passes/shade/ShadePass.h"
#include "passes/silhouette/SilhouettePass.h"

#include <algorithm>

namespace inkgraph {

std::vector<const Pass*> StillGraph::view() const {
    std::vector<const Pass*> result;
    for (const auto& pass : passes) result.push_back(pass.get());
    return result;
}

std::vector<Pass*> StillGraph::mutableView() const {
    std::vector<Pass*> result;
    for (const auto& pass : passes) result.push_back(pass.get());
    return result;
}

namespace {

ShadingModel shadingModelOf(ShadingMode mode) {
    switch (mode) {
    case ShadingMode::Flat: return ShadingModel::Flat;
    case ShadingMode::Gouraud: return ShadingModel::Gouraud;
    case ShadingMode::Lambert: return ShadingModel::Lambert;
    case ShadingMode::Phong: return ShadingModel::Phong;
    case ShadingMode::Cel: return ShadingModel::Cel;
    case ShadingMode::Comic: return ShadingModel::Comic;
    case ShadingMode::None: break;
    }
    throw std::logic_error("shadingModelOf(): --shading none has no shading model");
}

cv::Vec4f displayColor(const glm::dvec4& color) {
    return cv::Vec4f(float(color.r), float(color.g), float(color.b), float(color.a));
}

} // namespace

StillGraph buildStillGraph(const StillGraphSetup& setup) {
    const RenderOptions& options = setup.options;
    StillGraph graph;
    const bool comic = options.shading == ShadingMode::Comic;

    OrientationSettings orientationSettings;
    orientationSettings.method = comic ? options.faceOrientation : FaceOrientationMethod::Standard;
    orientationSettings.viewVector = options.viewVector;
    orientationSettings.frontRule = options.frontRule;
    orientationSettings.shininess = options.shininess;
    graph.orientation =
        std::make_unique<SceneOrientation>(setup.scene, setup.gpuScene, setup.frame, orientationSettings);
    SceneOrientation* cpuOrientation = graph.orientation->usesCpuMarking() ? graph.orientation.get() : nullptr;

    graph.passes.push_back(std::make_unique<GBufferPass>("gbuffer", setup.shaders, setup.gpuScene, setup.frame,
                                                         options.supersample, options.gbufferPrecision));
    graph.radialLengthUnit = setup.frame.radialLengthUnit;

    if (options.shading != ShadingMode::None) {
        ShadeSettings settings;
        settings.model = shadingModelOf(options.shading);
        settings.shininess = options.shininess;
        if (comic)
            settings.view = chooseViewVector(options.viewVector, setup.frame.camera.eye, setup.sphere.center,
                                             setup.sphere.radius);
        std::optional<ShadeMap> shadeMap = setup.shadeMap;
        if (!shadeMap && options.shading == ShadingMode::Cel) shadeMap = makeBandShadeMap(options.bands.value_or(5));
        if (!shadeMap && comic) shadeMap = makeDefaultComicShadeMap();
        if (shadeMap) graph.shadeMapSource = shadeMap->source;
        if (options.shading == ShadingMode::Cel || comic) {
            // Per-mesh maps replace the run's map on their meshes; the models without a map have nothing to replace.
            settings.meshShadeMaps = setup.meshShadeMaps;
            for (std::size_t i = 0; i < setup.meshShadeMaps.size() && i < setup.scene.meshes.size(); ++i)
                if (setup.meshShadeMaps[i])
                    graph.meshShadeMapSources.emplace_back(setup.scene.meshes[i].name, setup.meshShadeMaps[i]->source);
        }
        graph.passes.push_back(std::make_unique<ShadePass>("shade", setup.shaders, setup.gpuScene, setup.frame,
                                                           settings, std::move(shadeMap), cpuOrientation));
        graph.shadingResource = "shade.color";
    }

    // Both line passes are always registered: one the composite does not read is culled, and --stats says so.
    auto outline = std::make_unique<OutlinePass>("outline", setup.shaders, setup.gpuScene, setup.frame,
                                                 float(options.lineStyles.at("outline").widthPixels), cpuOrientation);
    graph.outline = outline.get();
    graph.passes.push_back(std::move(outline));
    HullSettings hull;
    hull.widthPixels = float(options.lineStyles.at("silhouette").widthPixels);
    if (options.silhouetteObjectWidth) hull.objectWidth = float(*options.silhouetteObjectWidth);
    auto silhouette = std::make_unique<SilhouettePass>("silhouette", setup.shaders, setup.gpuScene, setup.frame, hull);
    graph.silhouette = silhouette.get();
    graph.passes.push_back(std::move(silhouette));

    // Object-space edges: one GL pass draws the one-pixel skeletons the requested types read.
    MeshEdgesSettings edgeSettings;
    edgeSettings.creaseAngleDegrees = float(options.creaseAngleDegrees);
    edgeSettings.supersample = options.supersample;
    auto meshEdges = std::make_unique<MeshEdgesPass>("mesh-edges", setup.shaders, setup.gpuScene, setup.frame,
                                                     edgeSettings);
    graph.meshEdges = meshEdges.get();
    graph.passes.push_back(std::move(meshEdges));

    // The post-stage line types, each a CPU pass that finds a skeleton (in the G-buffer, or in a mesh-edges output)
    // and strokes it; registered whether or not requested.
    const float depthJump = float(options.depthJump);
    for (const std::string& type : knownLineTypes()) {
        if (!isImageSpaceLineType(type) && !isMeshEdgeLineType(type) && !isObjectSpaceLineType(type)) continue;
        LineLayerSettings settings;
        settings.widthPixels = float(options.lineStyles.at(type).widthPixels);
        settings.supersample = options.supersample;
        if (isMeshEdgeLineType(type)) {
            settings.source = LineSource::Skeleton;
            settings.skeletonResource = std::string("mesh-edges.") + (type == "mesh-silhouette" ? "silhouette" : type);
        } else if (type == "contour") {
            settings.source = LineSource::Contour;
            settings.contour.depthJump = depthJump;
        } else if (type == "suggestive" || type == "suggestive-object") {
            // Both suggestive types share one meaning of the threshold, fade and feature size.
            settings.source = type == "suggestive" ? LineSource::Suggestive : LineSource::SuggestiveObject;
            settings.suggestive.depthJump = depthJump;
            // fs in model units for the object-space type, which works on the mesh; gbuffer.radial is in units of
            // the bounding radius (FrameParams::radialLengthUnit), so the image-space fs is too.
            const double featureSize = kSuggestiveFeatureSizeFraction * setup.sphere.radius;
            settings.suggestive.featureSize =
                float(type == "suggestive" ? featureSize / setup.frame.radialLengthUnit : featureSize);
            if (options.suggestiveThreshold) settings.suggestive.threshold = float(*options.suggestiveThreshold);
            if (options.suggestiveFade) settings.suggestive.fade = float(*options.suggestiveFade);
            if (options.suggestiveStencil == 5) settings.suggestive.stencil = DifferenceStencil::Central5;
        } else if (type == "depth-edge") {
            settings.source = LineSource::DepthEdge;
            settings.depthEdge.relativeJump = depthJump;
        } else {
            settings.source = LineSource::NormalEdge;
            settings.normalEdge.creaseAngleDegrees = float(options.creaseAngleDegrees);
            settings.normalEdge.depthJump = depthJump;
        }
        auto pass = std::make_unique<LineLayerPass>(type, settings, LineSceneInputs{&setup.gpuScene, &setup.frame});
        graph.lineLayers[type] = pass.get();
        graph.passes.push_back(std::move(pass));
    }

    std::vector<CompositePass::LineInput> lines;
    for (const std::string& type : knownLineTypes())
        if (std::find(options.lines.begin(), options.lines.end(), type) != options.lines.end())
            lines.push_back({type + ".lines", displayColor(options.lineStyles.at(type).color)});
    graph.passes.push_back(
        std::make_unique<CompositePass>("composite", setup.frame, graph.shadingResource, std::move(lines)));
    return graph;
}

std::vector<std::string> expandWildcards(const std::vector<std::string>& requests, const StillGraph& graph) {
    std::vector<std::string> expanded;
    for (const std::string& request : requests) {
        const ResourceName name = ResourceName::split(request);
        if (name.field != "*") {
            expanded.push_back(request);
            continue;
        }
        bool found = false;
        for (const Pass* pass : graph.view()) {
            if (pass->name() != name.pass) continue;
            PassBuilder builder{name.pass};
            pass->declare(builder);
            for (const auto& write : builder.writes()) expanded.push_back(name.pass + "." + write.field);
            found = true;
        }
        if (!found) throw UsageError("--request: no pass named '" + name.pass + "' in this render graph");
    }
    return expanded;
}

} // namespace inkgraph
