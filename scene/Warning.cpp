#include "scene/Warning.h"

#include <stdexcept>

namespace inkgraph {

const std::vector<WarningCode>& warningCodes() {
    using K = WarningKind;
    // One line of meaning each: docs/robustness.md prints it as is.
    static const std::vector<WarningCode> kCodes = {
        {K::TextureMissing, "texture-missing",
         "a texture file the model names is missing or not a regular file; the material is drawn without it"},
        {K::TextureUndecodable, "texture-undecodable",
         "a texture image that is corrupt, truncated, empty or of a format not read; the material is drawn without "
         "it"},
        {K::TextureWithoutCoreImage, "texture-without-core-image",
         "a glTF texture has no PNG, JPEG or WebP source (only an extension's, e.g. KHR_texture_basisu's KTX2); drawn "
         "untextured"},
        {K::TextureCoordinateSetUnsupported, "texture-coordinate-set-unsupported",
         "a texture reads a coordinate set other than TEXCOORD_0 and TEXCOORD_1; drawn untextured"},
        {K::TextureCoordinatesMissing, "texture-coordinates-missing",
         "a mesh's texture reads a TEXCOORD set the mesh does not have; drawn without that texture"},
        {K::TextureTransformDropped, "texture-transform-dropped",
         "a VRM _MainTex or expression texture transform the shaders' float cannot follow; the textures are drawn "
         "without it"},
        {K::TextureDownscaled, "texture-downscaled",
         "an image larger than the driver's largest texture; downscaled to fit"},
        {K::MaskIgnored, "mask-ignored", "an MTL map_d that is not the map_Kd image; ignored"},
        {K::ValueOutOfRange, "value-out-of-range", "a material or colour value outside its range; clamped into it"},
        {K::MaterialValueInvalid, "material-value-invalid",
         "a glTF alpha mode, alpha cutoff or sampler value the specification does not define, or a material value of "
         "the wrong type or length; the default is used"},
        {K::ExtrasKeyIgnored, "extras-key-ignored", "a key of a material's extras.inkgraph other than 'shademap'"},
        {K::VrmPropertyInvalid, "vrm-property-invalid",
         "a VRM property (a material's, an expression's, the humanoid's, the version) of the wrong type or value; its "
         "default is used or it is ignored"},
        {K::MToonFeatureNotDrawn, "mtoon-feature-not-drawn", "MToon features the material uses that are not drawn"},
        {K::MToonOutlineWidth, "mtoon-outline-width",
         "an MToon outline width that covers most of the picture, or too large to place (no outline)"},
        {K::MaterialLibraryMissing, "material-library-missing",
         "an OBJ mtllib that is missing or cannot be read; its materials are drawn in the default grey"},
        {K::MaterialStatementIgnored, "material-statement-ignored", "an MTL statement that cannot be read; ignored"},
        {K::MaterialRedefined, "material-redefined", "an MTL material defined again; the first definition is kept"},
        {K::MaterialUndefined, "material-undefined",
         "OBJ usemtl names materials no library defines; their faces are drawn in the default grey"},
        {K::MaterialInvisible, "material-invisible",
         "a material that draws nothing (an MTL d or 1 - Tr under 1/510, a glTF MASK alpha under its cutoff or "
         "BLEND alpha under 1/510): its faces are not drawn"},
        {K::WhiteEmissionIgnored, "white-emission-ignored",
         "an MTL 'Ke 1 1 1' without a map_Ke (a white emission colour exporters write at strength 0): read as no "
         "emission, as Blender's importer reads it"},
        {K::PrimitiveSkipped, "primitive-skipped", "a glTF primitive of points or lines, or without POSITION; skipped"},
        {K::IndicesIncomplete, "indices-incomplete", "trailing indices of an incomplete triangle; ignored"},
        {K::MeshDegenerate, "mesh-degenerate", "a mesh whose triangles are all degenerate; skipped"},
        {K::DetailsMerged, "details-merged",
         "more than 1% of a mesh's triangles are smaller than the weld distance (1e-6 of the model's size) and "
         "collapsed when their corners merged; dropped"},
        {K::MeshInsideOut, "mesh-inside-out",
         "a closed surface of a two-sided mesh wound inside out (clockwise seen from outside); its winding, and its "
         "normals where they point inward too, reversed so the hull silhouette and the outline are drawn"},
        {K::WindingMixed, "winding-mixed",
         "a two-sided mesh's faces wound against their neighbours (a flipped patch of a scan); turned to agree with "
         "the given normals, else with most of their surface"},
        {K::NormalsInward, "normals-inward",
         "a two-sided mesh's given normals point against its faces' winding on over 90% of its area; turned round"},
        {K::TextureIgnored, "texture-ignored",
         "a PLY file's texture coordinates or TextureFile image; PLY is drawn untextured"},
        {K::VertexValuesIgnored, "vertex-values-ignored",
         "OBJ 'v' lines with values after x y z that are neither w nor a colour; ignored"},
        {K::NormalsMissing, "normals-missing", "OBJ faces without normals; the normals are recomputed"},
        {K::TexcoordsMissing, "texcoords-missing",
         "OBJ faces without texture coordinates in a mesh whose other faces have them; their corners take (0, 0)"},
        {K::TexcoordsNonFinite, "texcoords-non-finite", "texture coordinates not finite in float; read as (0, 0)"},
        {K::ColoursNonFinite, "colours-non-finite", "vertex colour components not finite; read as 1"},
        {K::ElementsSkipped, "elements-skipped", "OBJ line and point elements (l, p); skipped"},
        {K::PolygonsFanned, "polygons-fanned",
         "OBJ or PLY polygons that cross themselves (or beyond the work one file may spend cutting concave ones); "
         "fanned from their first corner, so their outline may be wrong"},
        {K::TrailingDataIgnored, "trailing-data-ignored", "bytes or text after a PLY's or STL's last element; ignored"},
        {K::StlSolidIncomplete, "stl-solid-incomplete", "an ASCII STL without its 'solid' or 'endsolid' line"},
        {K::CameraIgnored, "camera-ignored", "a glTF camera that is not perspective; ignored"},
        {K::CameraAspectIgnored, "camera-aspect-ignored", "a glTF camera's aspectRatio that is not finite and > 0"},
        {K::LightIgnored, "light-ignored", "a KHR_lights_punctual light that is not directional; ignored"},
        {K::AnimationIgnored, "animation-ignored", "an animation asked of a format that has none"},
        {K::AnimationChannelIgnored, "animation-channel-ignored",
         "a glTF animation channel that cannot be applied (its path, a node with a matrix or without morph targets, a "
         "target naming no node: KHR_animation_pointer's)"},
        {K::PoseBoneMissing, "pose-bone-missing",
         "a pose turns a humanoid bone the model lacks (or whose node is a matrix); that bone is left as it is"},
        {K::MorphAttributeIgnored, "morph-attribute-ignored",
         "a morph target moves an attribute other than POSITION and NORMAL, which is not applied"},
        {K::MorphWeightsMismatched, "morph-weights-mismatched",
         "a glTF mesh's or node's morph weights that are not one number per morph target; a target without one is "
         "not applied"},
        {K::SkinWeightsUnnormalised, "skin-weights-unnormalised",
         "a skinned glTF primitive whose vertices' joint weights do not sum to 1 (within 0.02): each vertex's are "
         "scaled to sum 1, and one whose weights are all 0 follows its mesh's node, unskinned"},
        {K::TimeUnused, "time-unused",
         "--time without --animation on a model none of whose materials has a MToon UV animation: it moves nothing"},
        {K::GltfParserMessage, "gltf-parser-message", "what tinygltf reported about a file it still read"},
        {K::ShadeMapUnused, "shade-map-unused", "meshes name shade maps, which the --shading model does not use"},
        {K::LookSettingUnused, "look-setting-unused",
         "a look setting (--ambient, --bands, --shademap) that --shading auto leaves unused on this model's materials"},
        {K::ModelOutsideView, "model-outside-view", "the camera sees none of the model: the picture is blank paper"},
        {K::WidthMapUnread, "width-map-unread",
         "a mesh lacks the vertex colours or texture coordinates --outline-width-map reads; its widths stay unscaled"},
        {K::TriangleIdInexact, "triangle-id-inexact",
         "the scene's files give more than 2^24 triangles, and the triangle ids (float32: the triangleId field, the "
         "barycentric alpha) round above 2^24"},
        {K::LinesSkipped, "lines-skipped",
         "a line type asked for is not drawn in this view: the eye is inside the model (or the silhouette's hull), "
         "where its bands would cover the whole picture"},
        {K::LinesEmpty, "lines-empty",
         "a line type asked for shows nothing in this view because of a setting given: its colour's alpha is 0, "
         "--min-stroke-length or its seed setting dropped every stroke it had, or at its own settings given it found "
         "none"},
    };
    return kCodes;
}

std::string_view warningCode(WarningKind kind) {
    const std::vector<WarningCode>& codes = warningCodes();
    const auto index = std::size_t(kind);
    // The table is in WarningKind's order (WarningTest checks); a kind past it is a missing row.
    if (index >= codes.size() || codes[index].kind != kind)
        throw std::logic_error("warningCode(): kind " + std::to_string(index) + " has no row in warningCodes()");
    return codes[index].code;
}

Warning makeWarning(WarningKind kind, std::string message, std::string file, std::string item) {
    return {std::string(warningCode(kind)), std::move(message), std::move(file), std::move(item)};
}

std::ostream& operator<<(std::ostream& out, const Warning& warning) {
    out << "[" << warning.code << "] " << warning.message;
    if (!warning.file.empty() || !warning.item.empty())
        out << " (file '" << warning.file << "', item '" << warning.item << "')";
    return out;
}

} // namespace inkgraph
