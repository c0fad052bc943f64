#pragma once
/** @file A VRM character's humanoid skeleton and the poses given by its bones: the humanoid bone map of VRM 1.0
 *  (VRMC_vrm.humanoid.humanBones, {boneName: {node}}) and VRM 0.x (VRM.humanoid.humanBones, [{bone, node}]), the
 *  built-in and file poses of LoadOptions::pose, and their rotations applied to the nodes' local transforms in the
 *  VRM normalized pose convention (three-vrm's normalized humanoid). Internal to the glTF reader. */

#include "scene/Warning.h"
#include "scene/formats/gltf/GltfPose.h"

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace tinygltf {
class Model;
} // namespace tinygltf

namespace inkgraph::detail {

/** The humanoid bone names of VRM 1.0's specification, in its order (torso, head, legs, arms, fingers). A VRM 0.x
 *  file's bones are read under these names: its thumbs' Proximal, Intermediate and Distal are 1.0's Metacarpal,
 *  Proximal and Distal, as three-vrm migrates them; every other 0.x name is the same. */
const std::vector<std::string>& humanoidBoneNames();

/** A VRM model's humanoid: which node each bone is. */
struct Humanoid {
    std::map<std::string, int> nodeOfBone; ///< 1.0 bone name -> node index (in range)
    /** VRM 0.x: the character faces -Z (1.0's face +Z), so a normalized rotation, given in 1.0's frame, is turned
     *  half a turn about Y onto it. */
    bool facesMinusZ = false;
};

/** The file's humanoid from VRMC_vrm (preferred) or VRM, or nullopt when it has neither extension. A bone entry
 *  whose name is not the specification's, whose node index is missing or out of range, is skipped with a warning. */
std::optional<Humanoid> readHumanoid(const tinygltf::Model& model, std::vector<Warning>& warnings);

/** The humanoid of `extension`.humanoid.humanBones given as VRM 1.0 gives it, {boneName: {node}} (VRMC_vrm, and
 *  VRMC_vrm_animation in a .vrma), or nullopt when the file has no such extension; bad entries as readHumanoid(). */
std::optional<Humanoid> readHumanBonesObject(const tinygltf::Model& model, const std::string& extension,
                                             std::vector<Warning>& warnings);

/** A pose of the humanoid: bone name -> rotation in the VRM normalized pose convention (the rotation of the bone
 *  from the rest T-pose, about world-aligned axes of a character facing +Z, as three-vrm's normalized bones take
 *  it; identity is the rest pose). The same pose poses every VRM alike. */
using HumanoidPose = std::map<std::string, glm::dquat>;

/** LoadOptions::pose's built-in pose name. */
inline constexpr const char* kAPoseName = "a-pose";
/** How far "a-pose" lowers each upper arm from the T-pose, in degrees. */
inline constexpr double kAPoseArmDegrees = 45.0;

/** "a-pose": both upper arms lowered by kAPoseArmDegrees about the forward axis (left about -Z, right about +Z in
 *  1.0's frame, so both hands go down). */
HumanoidPose aPose();

/** A pose file's JSON, `{"boneName": [x, y, z, w], ...}` (unit quaternions; any non-zero length is normalised).
 *  Throws SceneError through throwLoadError() naming `posePath` for malformed JSON, a value that is not four finite
 *  numbers of non-zero length, or a bone name outside humanoidBoneNames() (listing them); `function` starts the
 *  messages. */
HumanoidPose parsePoseFile(const std::string& posePath, const std::string& content,
                           std::string_view function = "loadScene()");

/** The whole of a file the load reads besides the model (a pose file, a VRM Animation), its size charged to `budget`;
 *  `kind` names it in the refusals ("cannot open the pose file for reading"), which name the file and start with
 *  `function`. */
std::string readSideFile(const std::string& path, const std::string& kind, MeshBudget& budget,
                         std::string_view function = "loadScene()");

/** LoadOptions::pose: aPose() for kAPoseName, else the pose file at that path, read (its size charged to `budget`)
 *  and parsed by parsePoseFile(). Throws SceneError naming the file when it cannot be read. */
HumanoidPose humanoidPose(const std::string& pose, MeshBudget& budget, std::string_view function = "loadScene()");

/** Sets the local rotation of each posed bone's node in `poses` so the model takes `pose`: the normalized rotation
 *  q, composed with the rest pose (`rest`, the nodes' own transforms) as raw = P^-1 * q * P * R, where P is the world
 *  rotation of the node's parent and R the node's local rotation at rest. Bones the model's humanoid lacks, and bone
 *  nodes given as a matrix, are skipped with a warning. */
void applyHumanoidPose(const tinygltf::Model& model, const Humanoid& humanoid, const HumanoidPose& pose,
                       const std::vector<NodePose>& rest, std::vector<NodePose>& poses, std::vector<Warning>& warnings);

/** Every node's parent (-1 for a root and for a node in a malformed hierarchy, which the reader's walk refuses). */
std::vector<int> nodeParents(const tinygltf::Model& model);

/** The world matrix of `node` in `poses`: its ancestors' local transforms and its own, composed. */
glm::dmat4 worldMatrix(const std::vector<NodePose>& poses, const std::vector<int>& parents, int node);

/** The world rotation of `node` in `poses`: its ancestors' local rotations and its own, composed (a node given as a
 *  matrix contributes its matrix's rotation). */
glm::dquat worldRotation(const std::vector<NodePose>& poses, const std::vector<int>& parents, int node);

} // namespace inkgraph::detail
