#pragma once
/** @file Shading: every shading model of Winnemöller & Bangay 2002 and Qu, Chen & Zwicker in one pass, chosen at
 *  construction. Forward by default: it draws the meshes itself with its own depth attachment, so a plan without lines
 *  needs no G-buffer. Deferred when the compiler finds the G-buffer running for the lines anyway (declare() asks
 *  PassBuilder::liveFieldsAnyway(): one compile decides) and nothing in the model or the scene needs more than the
 *  per-pixel normal, view vector and base colour: one full-screen triangle then shades the G-buffer's fields, and the
 *  meshes are drawn once instead of twice (docs/shading.md).
 *
 *  | resource      | format | need     | content                                                            |
 *  |---------------|--------|----------|--------------------------------------------------------------------|
 *  | reads         |        |          | forward: nothing from the graph (meshes from GpuScene, sets from    |
 *  |               |        |          | GpuScene::cpuOrientation() for the CPU face-orientation methods)    |
 *  |               |        |          | but, with ShadeSettings::materialOutlines, <outlines>.color and     |
 *  |               |        |          | <outlines>.depth (MToonOutlinePass), laid in after the opaque draws |
 *  |               |        |          | deferred: gbuffer.normal (a = coverage); gbuffer.baseColor unless   |
 *  |               |        |          | the scene has one base colour; gbuffer.view for phong and comic     |
 *  |               |        |          | with the exact view vector                                          |
 *  | <name>.color  | rgba8  | required | sRGB colour, a = coverage (0 off the model); with msaa, the average |
 *  |               |        |          | of each pixel's samples: edges take a share of fill and background  |
 *
 *  Models (docs/shading.md; n, l, v unit, v surface -> eye, r = reflect(-l, n)):
 *  - flat:    face normal from the derivatives of the view position, ambient + diffuse
 *  - gouraud: ambient + diffuse per vertex, colour interpolated
 *  - lambert: ambient + diffuse per fragment, interpolated normals
 *  - phong:   ambient + diffuse + specular max(r.v, 0)^n per fragment, specular 0 where n.l <= 0
 *  - cel:     1-D shade map indexed by the half-Lambert q = (n.l + 1)/2 per fragment
 *  - mtoon:   the materials' MToon (common/mtoon.glsl, docs/mtoon.md)
 *  - auto:    mtoon's colour for the materials with MToon, cel's for the others
 *  - comic:   2-D shade map indexed by (max(n.l, 0), max(r.v, 0)^n) per fragment, specular 0 where n.l <= 0;
 *             with a constant view vector the specular term uses V_c; with a CPU face-orientation method the
 *             front sets are drawn with the per-vertex (s, t) the CPU computed (Winnemöller & Bangay 2002, Listing 1)
 *  Shininess 0 gives specular 1 (where n.l > 0); large shininess is evaluated as exp(n log(r.v)) with log(r.v) from
 *  |r - v|^2, so 1e6 gives neither NaN nor speckle (specularTerm in shaders/common/lighting.glsl).
 *
 *  Per-mesh shade maps (cel, comic; ShadeSettings::meshShadeMaps): each mesh may bring its own map in place of the
 *  default one. Every distinct map (equal texels count as one) is uploaded once in prepare() and bound per draw.
 *  Comic's row-band fast path takes the largest border count of the maps in use as its SPECULAR_ROW_BANDS, and a map
 *  with fewer borders is padded with borders no x = |r - v|^2 / 2 >= 0 reaches (-1): each mesh then gets exactly the
 *  rows its map alone would give, so a scene whose meshes share one map renders as the single-map pass, bit for bit.
 *  Only when some map has more than kMaxSpecularRowBands borders do all meshes take the generic exp(n log(r.v)) path
 *  (one program per pass), which can differ from the comparisons by one row at a band border.
 *
 *  Ambient + diffuse is base x (ambient + (1 - ambient) max(n.l, 0)), per channel of FrameParams::ambientLight;
 *  phong adds specularStrength x specular in white; cel and comic multiply the decoded texel with the base colour.
 * Light: FrameParams::towardLightView(). No culling, a nearer depth test (GL_GREATER: reversed-Z, gl/GlObjects.h): seen
 * from behind (open meshes, holes), interpolated and flat normals turn toward the viewer; gouraud lights the vertex
 * normal as stored, so back faces show the lighting of their front side. The flat normal is turned toward the eye by
 * geometry (dot with -p), so it does not depend on the render target's y direction. */

#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "gl/GlPass.h"
#include "passes/FrameParams.h"
#include "passes/GpuScene.h"
#include "passes/gbuffer/GBufferPass.h"
#include "passes/orientation/SceneOrientation.h"
#include "passes/shade/ShadeMap.h"
#include "passes/shade/ShadingModel.h"
#include "scene/mesh/FaceOrientation.h"

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace inkgraph {

/** Forward: the pass draws the meshes. Deferred: it shades the G-buffer's fields on a full-screen triangle. */
enum class ShadeMode { Forward, Deferred };

struct ShadeSettings {
    ShadingModel model = ShadingModel::Cel;
    double shininess = 32.0;       ///< phong and comic; >= 0
    float specularStrength = 0.5f; ///< phong: white specular weight
    ViewVectorChoice view;         ///< comic: constant or exact (from chooseViewVector())
    /** comic: the CPU face-orientation method whose front sets are drawn (Standard: the GPU culls); deferred shading
     *  cannot draw them: the sets' per-vertex (s, t) are not in the G-buffer. */
    FaceOrientationMethod faceOrientation = FaceOrientationMethod::Standard;
    /** cel and comic: entry i, when present, is GpuScene mesh i's own shade map, checked like the default one (a
     *  missing entry, or a mesh past the end, uses the default map). Ignored by the models without a map. */
    std::vector<std::optional<ShadeMap>> meshShadeMaps{};
    /** A model with the materialOutlines trait (mtoon): the pass whose layer of material outlines (its `color` and
     *  `depth`, passes/mtoon/MToonOutlinePass.h) forward shading lays in after the opaque surfaces; empty: none. The
     *  still graph names it only when some material asks for an outline, so the layer's pass is otherwise culled. */
    std::string materialOutlines{};
    /** Samples per pixel of forward shading (--msaa: 1, 2, 4 or 8). Above 1 the pass draws into a multisampled
     *  colour and depth target of its own and resolves it into `<name>.color` (the average of each pixel's samples);
     *  the material outlines' layer then has as many samples, laid in sample by sample. Deferred shading cannot
     *  multisample (the G-buffer is single-sample), so it is a reason to shade forward. */
    int msaa = 1;
    /** The G-buffer deferred shading may read when it runs anyway: its pass name, supersampling and precision (a
     *  supersampled or float16 G-buffer would shade other normals than forward). An empty name: always forward. */
    struct DeferredSource {
        std::string gbuffer;
        int supersample = 1;
        GBufferPrecision precision = GBufferPrecision::Float32;
    } deferred{};
};

class ShadePass : public GlPass {
public:
    /** `shadeMap` is required for cel and comic (a copy is uploaded in prepare()); it is the default for meshes
     *  without one of their own in `settings.meshShadeMaps`. Comic draws the front sets of `scene.cpuOrientation()`
     *  when the scene has one (asked when the pass runs). Throws std::invalid_argument for a missing map, a cel map
     *  (default or per mesh) of more than one row, a map that is not CV_8UC4, more per-mesh maps than the scene has
     *  meshes, a negative or non-finite shininess or specular strength, or a comic constant
     *  view vector that is not unit. */
    ShadePass(std::string name, ShaderLibrary& shaders, GpuScene& scene, const FrameParams& frame,
              ShadeSettings settings, std::optional<ShadeMap> shadeMap);
    ~ShadePass() override;

    std::string_view name() const override { return mName; }
    void declare(PassBuilder& builder) const override;
    void prepare(GlPassContext& context) override;
    void execute(GlPassContext& context) override;

    /** The distinct shade maps the meshes use (1 for a single map, 0 for the models without one): the textures
     *  prepare() uploads. */
    std::size_t distinctShadeMapCount() const;

    /** The one rule of forward or deferred: why the pass shades forward when `liveFields` are the fields of the
     *  G-buffer that run anyway, or empty for deferred. Deferred when settings.deferred names a G-buffer, `liveFields`
     *  is not empty (the G-buffer runs anyway) and none of these holds, else forward with the first that does as the
     *  reason: the model is not perPixel (flat, gouraud, mtoon); comic draws a CPU face orientation's sets; the
     *  shading is multisampled (msaa); the G-buffer is supersampled or float16; a material blends, is emissive or unlit
     * (the G-buffer holds none of it); the meshes use more than one distinct shade map; the fields deferred reads would
     * make the G-buffer draw the meshes a second time. The facts of the scene are taken once, at construction. */
    std::string forwardReason(const std::vector<std::string>& liveFields) const;
    /** The mode a compiled plan runs the pass in: deferred when it reads the G-buffer. */
    ShadeMode modeIn(const Plan& plan) const;
    /** Why `plan` runs the pass forward (forwardReason() of the G-buffer fields live in it); empty when deferred. */
    std::string forwardReasonIn(const Plan& plan) const;
    /** The G-buffer fields deferred shading reads: normal (whose alpha is the coverage), baseColor unless
     *  sceneBaseColor() has one, and view for phong and comic with the exact view vector. */
    std::vector<std::string> deferredFields() const;
    /** The base colour when it is one constant over the whole scene (every mesh untextured, without vertex colours,
     *  with the same factor): deferred shading then takes it as a uniform, exactly as forward shading has it, and the
     *  G-buffer does not store it. */
    std::optional<glm::vec4> sceneBaseColor() const;

private:
    /** One distinct shade map: the default or a mesh's own, uploaded once in prepare(). */
    struct MapSlot {
        ShadeMap map;
        SpecularRowBands rowBands;      ///< comic: the map's row bands for this shininess (computed once)
        std::vector<float> borderLimit; ///< comic row bands: rowBands' limits padded to mSpecularBorderCount with -1
        std::vector<int> bandRow;       ///< comic row bands: rowBands' first rows padded to mSpecularBorderCount + 1
        bool used = false;              ///< some mesh draws with it (the default may be replaced on every mesh)
        std::unique_ptr<GlTexture> texture; ///< GL row 0 is the map's bottom row, t = 0
    };

    /** The entry of mMaps holding texels equal to `map`'s, adding one when none does. */
    std::size_t slotOf(ShadeMap map);

    /** The model's row of the trait table: every question about what the pass does for the model asks it. */
    const ShadingModelTraits& traits() const { return traitsOf(mSettings.model); }
    /** The model takes a constant view vector (traits().constantView) and the settings give one. */
    bool usesConstantView() const { return traits().constantView && mSettings.view.constant; }
    /** Draws the front sets of a CPU face-orientation method (traits().orientationSets: comic) instead of the whole
     *  meshes. */
    bool drawsOrientationSets() const;
    /** Lays the material outlines' layer (ShadeSettings::materialOutlines) into the bound target after the opaque
     *  surfaces: a full-screen triangle writes each shell pixel's colour at its depth (gl_FragDepth) under the
     *  strictly-nearer test and writes the depth, as the shell drawn here would (shaders/shade/outlines.frag). */
    void layMaterialOutlines(GlPassContext& gl);
    /** MODEL_* and variant defines for the one program of this pass. */
    std::vector<std::string> defines() const;
    /** Why deferred shading would not give the forward picture whatever the G-buffer writes (the model, the
     *  shading's samples, the G-buffer's resolution and precision, the materials, the shade maps), or empty; taken at
     *  construction. */
    std::string sceneBlocker() const;
    /** The uniforms both modes share: light, ambient, shininess, specular strength, comic's constant view. */
    void setShadingUniforms(const GlProgram& program) const;
    /** Binds `slot`'s shade map to unit 0 and, for comic's row bands, sets its borders and rows. */
    void bindShadeMap(const GlProgram& program, const MapSlot& slot) const;
    void executeForward(GlPassContext& gl);
    /** The multisampled colour target forward shading draws into with msaa, kept between runs of the same size. */
    const GlTexture& multisampledColor(int width, int height);
    void executeDeferred(GlPassContext& gl);
    /** A model with traits().specularRowBands (comic) on the GPU with maps of at most kMaxSpecularRowBands + 1 row
     *  bands: rows found by comparisons. */
    bool usesSpecularRowBands() const;

    static constexpr int kMaxSpecularRowBands = 8; ///< borders; a map with more falls back to exp(n log(r.v))
    /** Deferred: the texture units of the G-buffer fields (0 is the shade map; the materials' units are unused). */
    static constexpr GLuint kNormalUnit = 1;
    static constexpr GLuint kBaseColorUnit = 2;
    static constexpr GLuint kViewUnit = 3;
    /** Forward: the texture units of the material outlines' layer, past the shade map's (0) and the materials' (1-4).
     */
    static constexpr GLuint kOutlineColorUnit = 5;
    static constexpr GLuint kOutlineDepthUnit = 6;

    std::string mName;
    ShaderLibrary& mShaders;
    GpuScene& mScene;
    const FrameParams& mFrame;
    ShadeSettings mSettings;
    std::vector<MapSlot> mMaps;                    ///< cel, comic: [0] the default map, then each distinct per-mesh map
    std::vector<std::size_t> mMeshMap;             ///< cel, comic: per GpuScene mesh, its entry of mMaps
    std::size_t mSpecularBorderCount = 0;          ///< comic: the most row-band borders of a map in use
    std::unique_ptr<GlProgram> mProgram;           ///< the one program of this model and variant
    std::unique_ptr<GlProgram> mOutlineProgram;    ///< lays the material outlines in, when the settings name a layer
    PassDepthBuffer mDepth;                        ///< the pass's own depth attachment, kept between runs
    std::unique_ptr<GlTexture> mMultisampledColor; ///< msaa > 1: what forward shading draws, resolved into color
    ShadeMode mMode = ShadeMode::Forward;          ///< the plan being run's (prepare())
    ShadeMode mProgramMode = ShadeMode::Forward;   ///< the mode mProgram was built for
    std::optional<glm::vec4> mSceneBaseColor;      ///< sceneBaseColor(), taken at construction
    std::string mSceneBlocker;                     ///< sceneBlocker(), taken at construction
};

} // namespace inkgraph
