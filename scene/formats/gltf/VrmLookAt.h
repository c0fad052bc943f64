#pragma once
/** @file A VRM character looking at a point (LoadOptions::lookAt): VRM 1.0's VRMC_vrm.lookAt and VRM 0.x's
 *  firstPerson look-at settings, after specification/VRMC_vrm-1.0/lookAt.md (the look-at space, yaw and pitch, the
 *  range maps, the eye bones' rotation or the look expressions' weights). docs/vrm.md describes it. Internal to the
 *  glTF reader. */

#include "scene/Warning.h"

#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace tinygltf {
class Model;
} // namespace tinygltf

namespace inkgraph::detail {

struct Humanoid;
struct NodePose;
class VrmExpressions;

/** The yaw and pitch (degrees; yaw > 0 to the character's left, pitch > 0 down) of `target` seen from the look-at
 *  space, and what they became. */
struct VrmGaze {
    double yawDegrees = 0.0;
    double pitchDegrees = 0.0;
    bool setExpressions = false; ///< the look expressions were set (type expression), not the eye bones
};

/** Makes the character of `model` look at `target` (world coordinates of the file): for look-at type bone
 *  ("Bone" in 0.x) the leftEye and rightEye humanoid bones of `poses` are turned; for type expression ("BlendShape")
 *  the weights of lookUp, lookDown, lookLeft and lookRight in `expressions` are set (those the file has). The bones
 *  are `humanoid`'s (VrmHumanoid.h readHumanoid(); null: none). The look-at space hangs from the head bone as `poses`
 *  place it, turned back by its rest rotation (`restPoses`). Throws SceneError through throwLoadError() for a file
 *  without VRM look-at settings or without the bones they need. A setting that would turn the eyes beyond any
 *  direction (an offset from the head past its hips, a bone map's output past 180 degrees) is said in `warnings`
 *  (vrm-property-invalid) and its default taken. */
VrmGaze applyVrmLookAt(const std::string& path, const tinygltf::Model& model, const Humanoid* humanoid,
                       const glm::dvec3& target, const std::vector<NodePose>& restPoses, std::vector<NodePose>& poses,
                       VrmExpressions& expressions, std::vector<Warning>& warnings);

} // namespace inkgraph::detail
