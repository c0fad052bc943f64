#pragma once
/** @file The one check of the numbers a model file gives the shaders: material factors, MToon parameters, vertex
 *  colours and texture transforms. The shaders compute in float. A value beyond float's range reaches them as
 *  infinity; one inside it but absurd makes their sums and products overflow (NaN: a black or blank picture), and a
 *  texture offset of 1e7 leaves float no fraction to find a texel with (the texture turns into one flat colour). Every
 *  reader passes each such value through here; whether a value out of range is clamped with a warning or refuses the
 *  file is the reader's policy (scene/README.md, "Refused or reported input"). Internal to the scene layer. */

#include "scene/Material.h"
#include "scene/Warning.h"

#include <glm/glm.hpp>

#include <optional>
#include <string>
#include <vector>

namespace inkgraph::detail {

/** Where a value bound for the shaders makes sense. */
struct ShaderRange {
    double min = 0.0;
    double max = 1.0;
};

/** The largest magnitude of a factor that has no range of its own (an emissive strength, MToon's shading shift or rim
 *  lift, a vertex colour): far beyond what a picture shows (its colours saturate at 1), yet small enough that the
 *  shaders' few products of such values stay finite in float (1e6 cubed is 1e18). */
inline constexpr double kMaxShaderFactor = 1e6;
/** Colours and factors that glTF and VRMC_materials_mtoon define in [0, 1]. */
inline constexpr ShaderRange kUnitRange{0.0, 1.0};
inline constexpr ShaderRange kNonNegativeRange{0.0, kMaxShaderFactor};
inline constexpr ShaderRange kSignedRange{-kMaxShaderFactor, kMaxShaderFactor};

/** `value` as the float the shaders get: as it is inside `range`; else the nearest end of the range (NaN: the lower
 *  end), and `warnings` gets "<what> <value> is outside [<min>, <max>]; <used> is used" (value-out-of-range, about
 *  `item`). */
float shaderValue(double value, ShaderRange range, const std::string& what, std::vector<Warning>& warnings,
                  const std::string& item = "");

/** The largest entry a texture transform may have once its offsets are reduced: texture coordinates in [0, 1] then
 *  stay below 1e4 (2^13.3), where float still resolves 2^-10 of the image, a texel of a 1024-texel one. Beyond it,
 *  an image repeated that often shows only its average colour at any distance. */
inline constexpr double kMaxTextureTransformEntry = 1e4;

/** The matrix the shaders get for a texture transform composed in double (uv' = transform x (u, v, 1), as
 *  KHR_texture_transform's): the offset of u' reduced modulo the period of the sampler's wrapS, that of v' modulo
 *  wrapT's (1 for Repeat, 2 for MirroredRepeat, none for ClampToEdge), which samples the very texels the offset names
 *  (a repeating image looks the same a whole period on) and leaves float its fraction to find them with. Returns
 *  nothing and says why in `problem` when an entry is still beyond kMaxTextureTransformEntry (or not finite). */
std::optional<glm::mat3> shaderTextureTransform(const glm::dmat3& transform, const TextureSampler& sampler,
                                                std::string& problem);

} // namespace inkgraph::detail
