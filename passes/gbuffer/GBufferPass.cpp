#include "passes/gbuffer/GBufferPass.h"

#include "passes/ViewUniforms.h"

#include "gl/GraphExecutor.h"

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <stdexcept>
#include <string_view>

namespace inkgraph {
namespace {

/** The radial field's focal lengths in pixels, (width/2 P[0][0], height/2 P[1][1]), for gbuffer.frag's closed form of
 *  the image Jacobian, which holds for perspective projections only: throws std::logic_error for another form. */
glm::vec2 focalPixels(const glm::mat4& clipFromView, int width, int height) {
    const glm::mat4& p = clipFromView; // p[column][row]
    const bool perspective = p[0][3] == 0.0f && p[1][3] == 0.0f && p[2][3] == -1.0f && p[3][3] == 0.0f &&
                             p[1][0] == 0.0f && p[3][0] == 0.0f && p[0][1] == 0.0f && p[3][1] == 0.0f;
    if (!perspective)
        throw std::logic_error("GBufferPass::execute(): the 'radial' field needs a perspective projection "
                               "(w row 0, 0, -1, 0; x and y rows without shear or translation)");
    return {0.5f * float(width) * p[0][0], 0.5f * float(height) * p[1][1]};
}

} // namespace

const std::vector<GBufferPass::Field>& GBufferPass::fields() {
    static const std::vector<Field> kFields = {
        {"normal", Format::RGBA32F, "NORMAL", "normal.exr", Appearance::UnitVector,
         "unit view-space normal, turned toward the eye; alpha 1 where covered, 0 elsewhere"},
        {"view", Format::RGBA32F, "VIEW", "view.exr", Appearance::UnitVector,
         "unit view vector (surface to eye), view space; alpha 1 where covered"},
        {"wVec", Format::RGBA32F, "WVEC", "w.exr", Appearance::UnitVector,
         "w = v − (n·v)n, unnormalised so |w| = sin θ; alpha 1 where covered"},
        {"nDotV", Format::R32F, "NDOTV", "ndotv.exr", Appearance::SignedScalar, "n·v, in [-1, 1]"},
        {"depth", Format::R32F, "DEPTH", "depth.exr", Appearance::Depth,
         "linear view depth (distance along the view axis), 0 off the model"},
        {"coverage", Format::R8, "COVERAGE", "coverage.png", Appearance::Mask,
         "255 where the model covers the pixel centre"},
        {"baseColor", Format::RGBA8, "BASECOLOR", "basecolor.png", Appearance::Color,
         "the material's textured base colour, sRGB"},
        {"radial", Format::RGBA32F, "RADIAL", "radial.exr", Appearance::Data,
         "what suggestive contours read: n·(c − p) with the unnormalised view vector, the image-space direction of w "
         "(J w, pixels, x right, y down), |w|²"},
        {"materialId", Format::R32F, "MATERIAL_ID", "materialid.exr", Appearance::Data,
         "the material's id + 1 as an exact float (equal for meshes of one material), 0 off the model"},
        {"objectId", Format::R32F, "OBJECT_ID", "objectid.exr", Appearance::Data,
         "the object's id (its index + 1, one object per node instance, as the manifest lists them) as an exact "
         "float, 0 off the model"},
        {"meshId", Format::R32F, "MESH_ID", "meshid.exr", Appearance::Data,
         "the mesh's id (its index + 1 among the file's meshes, as the manifest's meshes list them; a mesh a pose "
         "collapses keeps its id, drawing nothing) as an exact float, 0 off the model"},
        {"triangleId", Format::R32F, "TRIANGLE_ID", "triangleid.exr", Appearance::Data,
         "the triangle's id: its index + 1 over the file's meshes in order, each mesh's triangles as its file gives "
         "them (the manifest's meshes give each mesh's first_triangle), as a float exact below 2^24 triangles, 0 off "
         "the model"},
        {"barycentric", Format::RGBA32F, "BARYCENTRIC", "barycentric.exr", Appearance::Data,
         "the visible point's perspective-correct barycentric weights in its triangle (rgb: the weights of its 1st, "
         "2nd and 3rd corner in the file's order, summing to 1); alpha the id of the triangle the weights are of (its "
         "global index + 1, as triangleId has it, from the same draw), all 0 off the model"},
    };
    return kFields;
}

GBufferPass::GBufferPass(std::string name, ShaderLibrary& shaders, GpuScene& scene, const FrameParams& frame,
                         int supersample, GBufferPrecision precision, int divisor)
    : mName(std::move(name)), mShaders(shaders), mScene(scene), mFrame(frame), mSupersample(supersample),
      mPrecision(precision), mDivisor(divisor), mDepth(mName + " depth test") {
    if (supersample < 1)
        throw std::invalid_argument("GBufferPass(): 'supersample' must be at least 1, got " +
                                    std::to_string(supersample));
    if (divisor < 1)
        throw std::invalid_argument("GBufferPass(): 'divisor' must be at least 1, got " + std::to_string(divisor));
}

Format GBufferPass::formatOf(const Field& field) const {
    // Depth needs float32's range and precision; material, object, mesh and triangle ids must stay exact integers
    // (float16 holds only 2048), and barycentric weights are labels a data set is read at full precision.
    const std::string_view name = field.name;
    if (mPrecision == GBufferPrecision::Float32 || name == "depth" || name == "materialId" || name == "objectId" ||
        name == "meshId" || name == "triangleId" || name == "barycentric")
        return field.format;
    if (field.format == Format::RGBA32F) return Format::RGBA16F;
    if (field.format == Format::R32F) return Format::R16F;
    return field.format;
}

void GBufferPass::declareOnly(std::vector<std::string> fieldNames) {
    for (const std::string& name : fieldNames)
        if (name != kZBuffer &&
            std::none_of(fields().begin(), fields().end(), [&](const Field& field) { return name == field.name; }))
            throw std::invalid_argument("GBufferPass::declareOnly(): '" + mName + "' has no field '" + name + "'");
    mOnlyFields = std::move(fieldNames);
}

bool GBufferPass::declares(std::string_view fieldName) const {
    return mOnlyFields.empty() || std::find(mOnlyFields.begin(), mOnlyFields.end(), fieldName) != mOnlyFields.end();
}

void GBufferPass::declare(PassBuilder& builder) const {
    builder.import(SceneImport::kMeshes);
    for (const Field& field : fields())
        if (declares(field.name))
            builder.write(field.name, {formatOf(field), mSupersample, 1, mDivisor}, Need::Optional,
                          {fileNameOf(field.fileName), field.appearance, meaningOf(field.fileName, field.meaning)});
    if (declares(kZBuffer))
        builder.write(
            kZBuffer, {Format::Depth32F, mSupersample, 1, mDivisor}, Need::Optional,
            {fileNameOf(kZBufferFile), Appearance::Data,
             meaningOf(kZBufferFile, "the depth test's own buffer: window depth of the nearest face, reversed-Z "
                                     "(1 at near, 0 at far and off the model)")});
}

std::string GBufferPass::fileNameOf(const char* fileName) const {
    // A coarser G-buffer runs beside the picture's own: --dump names its files apart ("suggestive-field-radial.exr").
    return mDivisor == 1 ? std::string(fileName) : mName + "-" + fileName;
}

std::string GBufferPass::meaningOf(const char* fileName, const char* meaning) const {
    if (mDivisor == 1) return meaning;
    return "as " + std::string(fileName) + ", at the picture's sides over a whole divisor: the G-buffer '" + mName +
           "', which a line kernel reads at one size whatever the picture's";
}

bool GBufferPass::zBufferHoldsEveryFace() const {
    const std::vector<Mesh>& meshes = mScene.scene().meshes;
    return std::all_of(meshes.begin(), meshes.end(), [](const Mesh& mesh) {
        return mesh.drawsBackFaces() && mesh.material.alphaMode == AlphaMode::Opaque;
    });
}

GlProgram& GBufferPass::programFor(const std::vector<std::string>& defines) {
    std::string key;
    for (const std::string& define : defines) key += define + ";";
    auto& program = mPrograms[key];
    if (!program) {
        // The barycentric weights come from a geometry stage that gives each triangle's corners unit weights; the
        // rasteriser's perspective-correct interpolation makes them the visible point's. Only its draw pays for it.
        const bool barycentric = std::find(defines.begin(), defines.end(), "OUT_BARYCENTRIC 1") != defines.end();
        program = std::make_unique<GlProgram>(mShaders.build({mName,
                                                              "gbuffer/gbuffer.vert",
                                                              "gbuffer/gbuffer.frag",
                                                              defines,
                                                              {"common/color.glsl", "common/material.glsl"},
                                                              barycentric ? "gbuffer/gbuffer.geom" : ""}));
    }
    return *program;
}

std::vector<std::vector<const GBufferPass::Field*>> GBufferPass::liveGroups(const GlPassContext& context) {
    std::vector<std::vector<const Field*>> groups;
    // The barycentric field's geometry stage changes how llvmpipe sets up a triangle (its window depth differs in the
    // last bits at a few pixels): it gets a draw of its own, first, so every other field and the z-buffer (the last
    // draw's depth) come from draws without it, bit for bit as without the labels.
    const auto needsGeometryStage = [](const Field& field) { return std::string_view(field.name) == kBarycentric; };
    for (const Field& field : fields())
        if (needsGeometryStage(field) && context.isLive(field.name)) groups.push_back({&field});
    const std::size_t ownGroups = groups.size();
    for (const Field& field : fields()) {
        if (!context.isLive(field.name) || needsGeometryStage(field)) continue;
        if (groups.size() == ownGroups || groups.back().size() == kMaxDrawBuffers) groups.emplace_back();
        groups.back().push_back(&field);
    }
    if (groups.empty() && context.isLive(kZBuffer)) groups.emplace_back(); // depth only
    return groups;
}

std::vector<std::string> GBufferPass::definesFor(const std::vector<const Field*>& group) const {
    std::vector<std::string> defines;
    int slot = 0;
    for (const Field* field : group) {
        defines.push_back(std::string("OUT_") + field->define + " 1");
        defines.push_back(std::string("LOC_") + field->define + " " + std::to_string(slot++));
    }
    defines.push_back("FILE_TRIANGLES_BINDING " + std::to_string(kFileTrianglesBinding));
    if (mScene.hasTransparency()) {
        defines.push_back("MATERIAL_ALPHA 1");
        defines.push_back("MATERIAL_SOLID_ONLY 1");
    }
    return defines;
}

void GBufferPass::prepare(GlPassContext& context) {
    for (const std::vector<const Field*>& group : liveGroups(context)) programFor(definesFor(group));
    mScene.meshes();
}

void GBufferPass::execute(GlPassContext& gl) {
    // GL guarantees 8 draw buffers: more live fields are drawn in a second draw of the same meshes with the same
    // vertex shader (gl_Position is invariant) and depth test, which rasterises exactly the same fragments.
    for (const std::vector<const Field*>& group : liveGroups(gl)) drawGroup(gl, group);
}

void GBufferPass::drawGroup(GlPassContext& gl, const std::vector<const Field*>& group) {
    GlFramebuffer framebuffer(mName);
    std::vector<int> drawSlots;
    // Every field shares one scale, so any live field gives the size of the attachments.
    const std::string sizeField = group.empty() ? kZBuffer : group.front()->name;
    const int width = gl.widthOf(sizeField);
    const int height = gl.heightOf(sizeField);
    for (const Field* field : group) {
        const int slot = static_cast<int>(drawSlots.size());
        framebuffer.attachColor(slot, gl.outputTexture(field->name));
        drawSlots.push_back(slot);
    }
    // A reader of the z-buffer gets this draw's depth attachment itself (each group redraws the same depth).
    if (gl.isLive(kZBuffer))
        framebuffer.attachDepth(gl.outputTexture(kZBuffer));
    else
        framebuffer.attachDepth(mDepth.sized(width, height));
    framebuffer.finish(drawSlots);
    GlProgram& program = programFor(definesFor(group));
    framebuffer.bind();
    glViewport(0, 0, width, height);
    // A field only read where the model covers the frame (ReadExtent::CoveredPixels: every reader tells the covered
    // pixels from the depth field or the z-buffer, which are cleared) keeps whatever its texture held there: on
    // llvmpipe the clears of the comic look's normal and radial fields were a tenth of the G-buffer's time.
    const float background[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    for (std::size_t slot = 0; slot < group.size(); ++slot)
        if (gl.backgroundIsRead(group[slot]->name)) glClearBufferfv(GL_COLOR, GLint(slot), background);
    glClearBufferfv(GL_DEPTH, 0, &kFarDepth);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(kDepthNearer);
    glDisable(GL_BLEND);
    const glm::mat4 clipFromView = mFrame.clipFromView();
    program.use();
    setViewUniforms(program, mFrame);
    if (std::any_of(group.begin(), group.end(),
                    [](const Field* field) { return std::string_view(field->name) == "radial"; })) {
        glUniform2fv(program.uniform("focalPixels"), 1, glm::value_ptr(focalPixels(clipFromView, width, height)));
        glUniform1f(program.uniform("radialLengthScale"), float(1.0 / mFrame.radialLengthUnit));
    }
    const GLint materialIdLocation = program.uniform("materialId");   // -1 unless the field is live: ignored
    const GLint objectIndexLocation = program.uniform("objectIndex"); // likewise
    const GLint meshNumberLocation = program.uniform("meshNumber");   // likewise
    const GLint firstTriangleLocation = program.uniform("firstTriangle");
    // Colour only for the baseColor field; the others need the material only where it cuts out.
    const MaterialUse use = std::any_of(group.begin(), group.end(),
                                        [](const Field* field) { return std::string_view(field->name) == "baseColor"; })
                                ? MaterialUse::Colour
                                : MaterialUse::Coverage;
    const GLint fileTrianglesAtLocation = program.uniform("fileTrianglesAt");
    const std::vector<GpuScene::DrawMesh>& meshes = mScene.meshes();
    // gl_PrimitiveID counts the triangles of one draw: the mesh's first global index, and its file's numbers where
    // the loader dropped some of its triangles, make it the scene's triangle id.
    const GpuScene::TriangleIdMap* triangleIds = firstTriangleLocation >= 0 ? &mScene.triangleIdMap() : nullptr;
    if (triangleIds != nullptr)
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kFileTrianglesBinding, triangleIds->fileTriangles.id());
    for (std::size_t index = 0; index < meshes.size(); ++index) {
        const GpuScene::DrawMesh& mesh = meshes[index];
        mScene.bindMaterial(program, index, use);
        glUniform1ui(materialIdLocation, mesh.materialId);
        glUniform1ui(objectIndexLocation, mesh.objectIndex);
        glUniform1ui(meshNumberLocation, mesh.meshNumber);
        if (triangleIds != nullptr) {
            glUniform1ui(firstTriangleLocation, triangleIds->firstTriangle[index]);
            glUniform1ui(fileTrianglesAtLocation, triangleIds->fileTrianglesAt[index]);
        }
        setFaceCulling(mesh.drawsBackFaces);
        mesh.vertexArray.bind();
        glDrawElements(GL_TRIANGLES, mesh.indexCount, GL_UNSIGNED_INT, nullptr);
    }
    // What is read only where covered need not come back beyond the scene's bounds: on llvmpipe the read-backs are
    // copies on this thread, and the bounds are about half the frame for an auto-framed model.
    const PixelRect scenePixels = mFrame.scenePixels(width, height);
    for (const Field* field : group)
        if (!gl.backgroundIsRead(field->name)) gl.limitReadback(field->name, scenePixels);
    glDisable(GL_CULL_FACE);
    glBindVertexArray(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDisable(GL_DEPTH_TEST);
}

} // namespace inkgraph
