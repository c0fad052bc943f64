#pragma once
/** @file The shapes of glTF's core values, judged on the JSON before tinygltf reads it: tinygltf takes a value of the
 *  wrong type or length for absent, so a node's matrix of 15 numbers, a projective matrix, a `scale` given as a
 *  string or an `extensionsRequired` written as one string were read as their defaults without a word, and a file of
 *  another major version as glTF 2.0. What changes the geometry or what the file requires is refused naming where it
 *  is; a material value of the wrong type, which tinygltf reads as its default, and morph weights whose count is not
 *  the targets' are warned about. Internal to the glTF reader. */

#include "scene/Warning.h"

#include <nlohmann/json_fwd.hpp>

#include <string>
#include <string_view>
#include <vector>

namespace inkgraph::detail {

/** Refuses (SceneError naming `path`) a GLB whose header's version is not 2: version 1 is glTF 1.0's binary form,
 *  laid out otherwise. */
void judgeGlbHeader(const std::string& path, std::string_view content);

/** What judgeValueShapes() found that the load goes on with. */
struct ValueShapes {
    std::vector<Warning> warnings;
    /** JSON pointers ("/materials/0/emissiveFactor") of the values warned about, to drop before tinygltf reads the
     *  file: it would read some as absent and refuse others (an `emissiveFactor` of 2 numbers), so each is read as
     *  absent, as the warning says. */
    std::vector<std::string> dropped;
};

/** Refuses (SceneError naming `path` and the value's place, "nodes[3].matrix") a top-level member such as `materials`
 * that is not an array, an `asset.version` or `asset.minVersion`
 * of another major version than 2, an `extensionsRequired` or `extensionsUsed` that is not an array of strings, a
 * buffer view's `byteStride` other than a multiple of 4 from 4 to 252 (tinygltf told 512 as "must be the multiple of
 * 4"), and a node `matrix`, `translation`, `rotation` or `scale` that is not 16, 3, 4 or 3 finite numbers, or a
 * `matrix` whose bottom row is not 0 0 0 1 (glTF's nodes are affine). Returns the warnings and the values to drop: a
 * material value of the wrong type or length (MaterialValueInvalid; the default is used) and morph weights that are
 * not one number per target (MorphWeightsMismatched; weights that are not numbers are dropped). `document` is the
 * file's JSON with its integers as integers (forTinygltf()). */
ValueShapes judgeValueShapes(const std::string& path, const nlohmann::json& document);

/** Removes the values at `pointers` (ValueShapes::dropped) from `document`, those it holds. */
void dropValues(nlohmann::json& document, const std::vector<std::string>& pointers);

} // namespace inkgraph::detail
