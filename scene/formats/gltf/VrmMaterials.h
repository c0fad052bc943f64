#pragma once
/** @file A VRM character's MToon materials, read from the glTF model tinygltf parsed: VRM 1.0's per-material
 *  VRMC_materials_mtoon extension as it is, VRM 0.x's root VRM.materialProperties converted to the 1.0 parameters the
 *  way the reference importers (UniVRM, three-vrm) migrate them. docs/mtoon.md lists every conversion and its source.
 *  Internal to the scene layer: only the glTF reader calls it. */

#include "scene/Material.h"
#include "scene/Warning.h"

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace tinygltf {
class Model;
class Value;
} // namespace tinygltf

namespace inkgraph::detail {

/** Turns one texture reference of the file (a glTF `textures` index in range, its TEXCOORD set, and the texture
 *  info's "extensions", null when it has none) into a TextureRef: the glTF reader's own conversion, so the sampler
 *  and KHR_texture_transform are read in one place. */
using VrmTextureResolver =
    std::function<TextureRef(int gltfTextureIndex, int texCoord, const tinygltf::Value* textureInfoExtensions)>;

/** The MToon parameters of glTF material `materialIndex` (in range), or none for a material that is not MToon.
 *  VRM 1.0: the material's "VRMC_materials_mtoon" extension, spec defaults for what it leaves out. VRM 0.x: the entry
 *  of the root "VRM" extension's materialProperties at the same index (UniVRM and three-vrm pair them by index) whose
 *  shader is "VRM/MToon"; its _Color, _MainTex (with its _MainTex scale/offset), _BlendMode, _Cutoff and _CullMode
 *  also replace `material`'s base colour, base colour texture, alpha mode, cutoff and double-sidedness, as both
 *  importers do. A "VRM/Unlit*" entry makes `material` unlit (alpha from the shader's name) and returns none.
 *  Never throws for bad values: a property of the wrong JSON type, non-finite or out of range is reported in
 *  `warnings` (naming the file's material) and its default used; a texture index out of range leaves the texture
 *  out. */
std::optional<MToonMaterial> readVrmMaterial(const tinygltf::Model& model, int materialIndex, Material& material,
                                             const VrmTextureResolver& resolveTexture, std::vector<Warning>& warnings);

/** The sRGB transfer function's inverse (IEC 61966-2-1): an sRGB-encoded component in [0, 1] as a linear one. VRM
 *  0.x stores its colours as Unity's gamma-space values. */
float srgbToLinear(float encoded);

} // namespace inkgraph::detail
