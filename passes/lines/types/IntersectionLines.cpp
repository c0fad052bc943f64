// intersection: where two surfaces cross (Pencil+'s intersection lines, Blender Line Art's intersection lines), found
// exactly on the mesh (scene/mesh/MeshIntersections.h: triangle-triangle segments, between meshes and within one) once
// per scene, and each frame projected and hidden with the G-buffer depth like every object-space line
// (passes/lines/ProjectedSegments.h); hidden-intersection keeps the hidden samples of the same segments.
#include "passes/FrameParams.h"
#include "passes/GpuScene.h"
#include "passes/lines/LineType.h"
#include "passes/lines/ProjectedSegments.h"

#include <nlohmann/json.hpp>

namespace inkgraph {
namespace {

using line_parameters::kDepthJump;

class IntersectionKernel : public LineKernel {
public:
    IntersectionKernel(std::string gbuffer, double depthJump, GpuScene& scene, const FrameParams& frame,
                       SegmentVisibility keep)
        : mGBuffer(std::move(gbuffer)), mDepthJump(depthJump), mScene(scene), mFrame(frame), mKeep(keep) {}
    std::vector<std::string> inputs() const override { return {mGBuffer + ".depth"}; }
    /** The segments (SceneImport::kIntersections): view-independent, derived once per scene. */
    std::vector<std::string> sceneImports() const override { return {SceneImport::kIntersections}; }
    /** The renderer derived the segments already (its importer); a run without one derives them here, untimed. */
    void prepare() override { mScene.meshIntersections(); }
    LineSkeleton find(const std::vector<cv::Mat>& inputs) override {
        SegmentProjector projector(mFrame.camera, inputs[0], mDepthJump, mKeep);
        for (const IntersectionSegment& segment : mScene.meshIntersections().segments)
            projector.add(segment.ends[0], segment.ends[1], 1.0, 1.0, int(segment.meshes[0]),
                          long(segment.triangles[0]));
        return projector.take();
    }
    void describe(nlohmann::ordered_json& entry) const override {
        // The search is once per scene, before any pass's clock: kernel_ms is the projection alone, per view.
        if (!mScene.meshIntersectionsComputed()) return;
        const MeshIntersections& found = mScene.meshIntersections();
        const IntersectionReport& report = found.report;
        entry["segments"] = report.segments;
        entry["self_segments"] = report.selfSegments;
        entry["triangles"] = report.triangles;
        entry["box_pairs"] = report.boxPairs;
        entry["shared_vertex_pairs"] = report.sharedVertexPairs;
        entry["pairs_tested"] = report.pairsTested;
        entry["index_nodes"] = report.indexNodes;
        entry["index_ms"] = report.indexMilliseconds;
        entry["search_ms"] = report.searchMilliseconds;
        entry["segment_bytes"] = found.bytes();
    }

private:
    std::string mGBuffer;
    double mDepthJump;
    GpuScene& mScene;
    const FrameParams& mFrame;
    SegmentVisibility mKeep;
};

LineType intersectionType(std::string name, std::string help, SegmentVisibility keep) {
    LineType type;
    type.name = std::move(name);
    type.family = LineFamily::ObjectSpace;
    type.help = std::move(help);
    type.hiddenLines = keep == SegmentVisibility::Hidden;
    type.parameters = {&kDepthJump};
    type.build = [keep](const std::string& typeName, LineGraphBuilder& builder) {
        const LineGraphSetup& setup = builder.setup();
        builder.addLayer(typeName, std::make_unique<IntersectionKernel>(setup.gbuffer,
                                                                        setup.look.lineParameters.number(kDepthJump),
                                                                        setup.scene, setup.frame, keep));
    };
    type.describe = [](const LineStatsSource& source, nlohmann::ordered_json& entry) {
        entry["depth_jump"] = source.look.lineParameters.number(kDepthJump);
        entry["supersample"] = source.look.supersample;
    };
    return type;
}

} // namespace

LineType intersectionLineType() {
    return intersectionType("intersection",
                            "where two surfaces cross (object space): triangle-triangle intersections\n"
                            "between meshes and within one (self-intersections: hair cards, clothing), found\n"
                            "once per scene, drawn where the G-buffer depth shows them (within --depth-jump)",
                            SegmentVisibility::Visible);
}

LineType hiddenIntersectionLineType() {
    return intersectionType("hidden-intersection",
                            "the occluded part of intersection's lines: the same samples, kept\n"
                            "where the G-buffer depth hides them (beyond --depth-jump)",
                            SegmentVisibility::Hidden);
}

} // namespace inkgraph
