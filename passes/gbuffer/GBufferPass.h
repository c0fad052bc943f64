#pragma once
/** @file The G-buffer: float32 view-space data of the visible surface, one MRT draw (two when more than the 8 draw
 *  buffers GL guarantees are live), no MSAA.
 *
 *  | resource           | format  | need     | content                                                           |
 *  |--------------------|---------|----------|-------------------------------------------------------------------|
 *  | gbuffer.normal     | rgba32f | optional | unit view-space normal (turned toward the viewer), a = coverage   |
 *  | gbuffer.view       | rgba32f | optional | unit view vector, surface -> eye, a = coverage                    |
 *  | gbuffer.wVec       | rgba32f | optional | w = v - (n.v) n, unnormalised so |w| = sin(theta), a = coverage   |
 *  | gbuffer.nDotV      | r32f    | optional | n . v                                                             |
 *  | gbuffer.depth      | r32f    | optional | linear view depth (distance along -z in view space), 0 off-model  |
 *  | gbuffer.coverage   | r8      | optional | 255 where the model covers the pixel centre                       |
 *  | gbuffer.baseColor  | rgba8   | optional | sRGB-encoded material base colour, a = coverage                   |
 *  | gbuffer.radial     | rgba32f | optional | (n.(c - p), (J w).x, (J w).y, |w|^2) with v = c - p unnormalised, |
 *  |                    |         |          | lengths in units of FrameParams::radialLengthUnit (J w: pixels)   |
 *  | gbuffer.materialId | r32f    | optional | GpuScene's material id + 1 as an exact float (scene/MaterialIds.h:|
 *  |                    |         |          | equal for meshes of one material), 0 off-model                    |
 *  | gbuffer.objectId   | r32f    | optional | the mesh's object index + 1 as an exact float (scene/ObjectIds.h: |
 *  |                    |         |          | one object per node instance), 0 off-model                        |
 *  | gbuffer.meshId     | r32f    | optional | the mesh's number + 1 (scene/MeshNumbering.h: skipped meshes keep |
 *  |                    |         |          | theirs) as an exact float, 0 off-model                            |
 *  | gbuffer.triangleId | r32f    | optional | the global triangle index + 1 (meshes by number, each its         |
 *  |                    |         |          | file's triangles: scene/MeshLabels.h; gl_PrimitiveID mapped by    |
 *  |                    |         |          | GpuScene::triangleIdMap()), exact up to 2^24 triangles (the       |
 *  |                    |         |          | renderer warns above), 0 off-model                                |
 *  | gbuffer.barycentric| rgba32f | optional | perspective-correct barycentric weights of the visible point in   |
 *  |                    |         |          | its triangle's corners (the file's order), a = its id, 0 off-model|
 *  | gbuffer.zBuffer    | depth32f| optional | the depth test's own buffer: window depth of the nearest drawn    |
 *  |                    |         |          | face, reversed-Z (gl/GlObjects.h), far plane 0 off-model          |
 *
 *  `zBuffer` is the pass's depth attachment published, not a shader output: the silhouette pass tests its hull
 *  against it instead of drawing the model's depth again (passes/StillGraph.cpp chooses when:
 *  zBufferHoldsEveryFace()). Without a reader it stays the pass's private attachment.
 *
 *  GBufferPrecision::Float16 stores normal, view, wVec, nDotV and radial as rgba16f / r16f instead (read back as
 *  float32): half the memory and bandwidth, about 3 decimal digits. It exists to measure what float32 buys
 *  (bench/TradeoffSweep, docs/accuracy.md). Depth stays r32f: linear depth overflows float16 at 65504 and the
 *  relative depth-break test needs its precision; the ids (material, object, mesh, triangle) stay r32f, since they
 *  must be exact, and barycentric stays rgba32f.
 *
 *  `barycentric` is drawn with a geometry stage (gbuffer.geom), in a draw of its own before the others (so they and
 *  the z-buffer are bit for bit what they are without it), that gives each triangle's corners unit weights; the
 *  rasteriser interpolates them perspective-correctly at the pixel centre (no MSAA here), and the fragment stage
 *  clamps and renormalises away the interpolation's rounding. The positions are the ones the GPU draws (skinning and
 *  morphs are applied on the CPU before the upload), so the weights hold for the posed mesh.
 *
 *  `radial` is what suggestive contours read (postfx/SuggestiveContours.h): n.v with the unnormalised view vector
 *  (DeCarlo's form, whose zero set of D_w(n.v) is exactly kappa_r = 0), the image-space direction of w as perspective
 *  maps it (J is the Jacobian of pixel coordinates, x right and y down, so J w = -(n.v) J n), and |w|^2, packed so
 *  one readback serves the kernel.
 *
 *  Reads: nothing from the graph; the meshes come from GpuScene. Background pixels are all zero. Every field is
 *  `supersample` times the frame size (--supersample renders the data buffers larger).
 *  Only live outputs are bound as draw buffers, and the shader is compiled with matching OUT_* defines. */

#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "gl/GlPass.h"
#include "passes/FrameParams.h"
#include "passes/GpuScene.h"
#include "passes/gbuffer/GBufferPrecision.h"

#include <algorithm>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace inkgraph {

class GBufferPass : public GlPass {
public:
    struct Field {
        const char* name; ///< "normal"
        Format format;
        const char* define;    ///< "NORMAL": OUT_NORMAL / LOC_NORMAL in gbuffer.frag
        const char* fileName;  ///< --dump's file name, "normal.exr"
        Appearance appearance; ///< how --contact-sheet shows it
        const char* meaning;   ///< what it holds, for README's --dump table (Presentation::meaning)
    };
    /** Every field the pass can write, in attachment order (the shader's outputs; the z-buffer is not one). */
    static const std::vector<Field>& fields();
    /** The field that publishes the depth attachment: "zBuffer". */
    static constexpr const char* kZBuffer = "zBuffer";
    /** --dump's file of the z-buffer. */
    static constexpr const char* kZBufferFile = "zbuffer.exr";
    /** The linear depth field, which the stroke stage weighs lines by: "depth". */
    static constexpr const char* kDepth = "depth";
    /** The field drawn with a geometry stage, in a draw of its own: "barycentric". */
    static constexpr const char* kBarycentric = "barycentric";

    /** `supersample` >= 1 scales every field, and `divisor` >= 1 divides it (a field coarser than the frame, for a
     *  kernel that samples the surface at one size whatever the picture's: TextureDesc::divisor); throws
     *  std::invalid_argument otherwise. */
    GBufferPass(std::string name, ShaderLibrary& shaders, GpuScene& scene, const FrameParams& frame,
                int supersample = 1, GBufferPrecision precision = GBufferPrecision::Float32, int divisor = 1);

    /** The format `field` is stored in at this pass's precision. */
    Format formatOf(const Field& field) const;
    /** Declares only these fields (short names, "radial"; kZBuffer for the z-buffer) instead of every one: a G-buffer
     *  drawn for one kernel, whose other fields no one reads. Throws std::invalid_argument naming an unknown field. */
    void declareOnly(std::vector<std::string> fieldNames);
    int supersample() const { return mSupersample; }
    int divisor() const { return mDivisor; }
    /** True when the z-buffer is the depth of every face of every mesh, as a pass that draws the model's depth with
     *  no face culled and no cut-out would make it: no material is single-sided (the G-buffer culls their back faces)
     *  and none is masked or blended. */
    bool zBufferHoldsEveryFace() const;
    GBufferPrecision precision() const { return mPrecision; }
    /** How many times the pass draws the meshes for these live fields (short names, "normal"): once per
     *  kMaxDrawBuffers of them, and once more for barycentric, which has a draw of its own. */
    static int drawCount(const std::vector<std::string>& liveFields) {
        const std::size_t own = std::size_t(std::count(liveFields.begin(), liveFields.end(), kBarycentric));
        const std::size_t shared = liveFields.size() - own;
        return int(own + (shared + kMaxDrawBuffers - 1) / kMaxDrawBuffers);
    }

    std::string_view name() const override { return mName; }
    void declare(PassBuilder& builder) const override;
    void prepare(GlPassContext& context) override;
    void execute(GlPassContext& context) override;

private:
    /** The live fields in attachment order, in groups of at most kMaxDrawBuffers: one draw each, barycentric alone
     *  first; one empty group when only the z-buffer is live. */
    static std::vector<std::vector<const Field*>> liveGroups(const GlPassContext& context);
    /** --dump's file name of a field: as given, or after the pass's name at a divisor above 1. */
    std::string fileNameOf(const char* fileName) const;
    bool declares(std::string_view fieldName) const;
    /** What a field holds, for --dump's table: as given, or at a divisor above 1 the field it repeats coarser. */
    std::string meaningOf(const char* fileName, const char* meaning) const;
    /** OUT_* and LOC_* defines for one group's draw. */
    std::vector<std::string> definesFor(const std::vector<const Field*>& group) const;
    void drawGroup(GlPassContext& gl, const std::vector<const Field*>& group);
    static constexpr std::size_t kMaxDrawBuffers = 8; ///< GL 4.5's guaranteed GL_MAX_DRAW_BUFFERS (llvmpipe's 8)
    /** The storage-buffer binding of GpuScene::TriangleIdMap::fileTriangles (the shader's FILE_TRIANGLES_BINDING). */
    static constexpr GLuint kFileTrianglesBinding = 0;
    GlProgram& programFor(const std::vector<std::string>& defines);

    std::string mName;
    ShaderLibrary& mShaders;
    GpuScene& mScene;
    const FrameParams& mFrame;
    std::map<std::string, std::unique_ptr<GlProgram>> mPrograms; ///< keyed by the live-output defines
    int mSupersample;
    GBufferPrecision mPrecision;
    int mDivisor;
    std::vector<std::string> mOnlyFields; ///< declareOnly()'s; empty: every field
    PassDepthBuffer mDepth;               ///< the pass's own depth attachment, kept between runs
};

} // namespace inkgraph
