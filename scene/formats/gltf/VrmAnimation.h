#pragma once
/** @file VRM Animation files (.vrma: a GLB with VRMC_vrm_animation) retargeted onto a VRM model through the humanoid
 *  bones, after the VRMC_vrm_animation-1.0 specification and three-vrm-animation: each bone's sampled rotation is
 *  made normalized with the .vrma's own rest pose, then posed on the model as a humanoid pose (VrmHumanoid.h); the
 *  hips' position is scaled by the ratio of the two rest hips heights. Expressions and lookAt are not applied.
 *  Internal to the glTF reader. */

#include "scene/Warning.h"
#include "scene/formats/gltf/GltfPose.h"
#include "scene/formats/gltf/VrmHumanoid.h"

#include <string>
#include <vector>

namespace tinygltf {
class Model;
} // namespace tinygltf

namespace inkgraph::detail {

/** Whether LoadOptions::animation names a VRM Animation file: it ends in ".vrma" (any case) and is an existing
 *  regular file. Otherwise it is the name or index of an animation in the model. */
bool isVrmAnimationFile(const std::string& animation);

/** Poses `poses` (the model's nodes, `rest` their own transforms) by the VRM Animation file `vrmaPath` sampled at
 *  `time` seconds (its first animation; none: its rest pose): each humanoid bone both files have turns by the
 *  .vrma's normalized rotation (P * raw * R^-1 * P^-1 with the .vrma's parent rest world rotation P and rest local
 *  rotation R), and, when the animation moves the .vrma's hips, the model's hips move to their world position times
 *  (the model's rest hips height / the .vrma's). Bones the model lacks are skipped. Throws SceneError naming the .vrma
 * for a file that cannot be read, is not a GLB with VRMC_vrm_animation, or whose animation cannot be sampled. */
void applyVrmAnimation(const std::string& vrmaPath, double time, const tinygltf::Model& model, const Humanoid& humanoid,
                       const std::vector<NodePose>& rest, std::vector<NodePose>& poses, MeshBudget& budget,
                       std::vector<Warning>& warnings);

} // namespace inkgraph::detail
