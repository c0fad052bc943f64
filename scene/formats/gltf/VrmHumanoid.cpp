/** @file VRM humanoid bones (VRM 1.0 specification, VRMC_vrm "humanoid"; VRM 0.x "humanoid") and poses in the
 *  normalized pose convention (three-vrm's VRMHumanoidRig: a normalized bone's rotation is about world-aligned axes
 *  relative to the rest pose). */

#include "scene/formats/gltf/VrmHumanoid.h"

#include "scene/formats/FormatReaders.h"
#include "scene/formats/gltf/GltfPose.h"

#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <set>

namespace inkgraph::detail {

namespace {

/** VRM 0.x's thumb names that 1.0 renamed: 0.x counts the thumb's bones from the proximal, 1.0 from the metacarpal. */
const std::map<std::string, std::string> kThumbsOf0x = {
    {"leftThumbProximal", "leftThumbMetacarpal"},
    {"leftThumbIntermediate", "leftThumbProximal"},
    {"rightThumbProximal", "rightThumbMetacarpal"},
    {"rightThumbIntermediate", "rightThumbProximal"},
};

bool isHumanoidBone(const std::string& name) {
    return std::ranges::find(humanoidBoneNames(), name) != humanoidBoneNames().end();
}

std::string boneNameList() {
    std::string list;
    for (const std::string& name : humanoidBoneNames()) list += (list.empty() ? "" : ", ") + name;
    return list;
}

/** Records `node` for `bone` (1.0's name), refusing an index outside the file's nodes. */
void addBone(const tinygltf::Model& model, const std::string& where, const std::string& bone,
             const tinygltf::Value& node, Humanoid& humanoid, std::vector<Warning>& warnings) {
    if (!isHumanoidBone(bone)) {
        warnings.push_back(
            makeWarning(WarningKind::VrmPropertyInvalid,
                        where + ": '" + excerptForMessage(bone) + "' is not a VRM humanoid bone; ignored", "", where));
        return;
    }
    if (!node.IsNumber()) {
        warnings.push_back(makeWarning(WarningKind::VrmPropertyInvalid,
                                       where + " '" + bone + "' has no node index; ignored", "", where));
        return;
    }
    const int index = node.GetNumberAsInt();
    if (index < 0 || std::size_t(index) >= model.nodes.size()) {
        // A warning, not a refusal: the humanoid is read for every VRM, and a model that renders without it must.
        warnings.push_back(makeWarning(WarningKind::VrmPropertyInvalid,
                                       where + " '" + bone + "': node index " + std::to_string(index) +
                                           " out of range (file has " + std::to_string(model.nodes.size()) +
                                           " nodes); ignored",
                                       "", where));
        return;
    }
    // The first of a bone given twice, or of two bones on one node, is kept, and the second said: the last one
    // replaced the first without a word.
    if (const auto given = humanoid.nodeOfBone.find(bone); given != humanoid.nodeOfBone.end()) {
        warnings.push_back(makeWarning(WarningKind::VrmPropertyInvalid,
                                       where + " '" + bone + "' is given twice (node " + std::to_string(given->second) +
                                           ", then node " + std::to_string(index) + "); the first is kept",
                                       "", where));
        return;
    }
    for (const auto& [other, otherNode] : humanoid.nodeOfBone) {
        if (otherNode != index) continue;
        warnings.push_back(makeWarning(WarningKind::VrmPropertyInvalid,
                                       where + " '" + bone + "': node " + std::to_string(index) + " is already bone '" +
                                           other + "' (a node is one bone); ignored",
                                       "", where));
        return;
    }
    humanoid.nodeOfBone[bone] = index;
}

glm::dquat rotationOf(const NodePose& pose) {
    if (!pose.matrix) return pose.rotation;
    // A matrix's rotation: its columns without their scale (a mirroring matrix keeps its reflection out of it).
    glm::dmat3 linear(*pose.matrix);
    for (int column = 0; column < 3; ++column) {
        const double length = glm::length(linear[column]);
        if (length > 0.0) linear[column] /= length;
    }
    if (glm::determinant(linear) < 0.0) linear[0] = -linear[0];
    return glm::normalize(glm::quat_cast(linear));
}

} // namespace

const std::vector<std::string>& humanoidBoneNames() {
    static const std::vector<std::string> kNames = [] {
        std::vector<std::string> names = {"hips", "spine",   "chest",    "upperChest", "neck",
                                          "head", "leftEye", "rightEye", "jaw"};
        for (const char* side : {"left", "right"}) {
            for (const char* bone : {"UpperLeg", "LowerLeg", "Foot", "Toes"}) names.push_back(side + std::string(bone));
        }
        for (const char* side : {"left", "right"}) {
            for (const char* bone : {"Shoulder", "UpperArm", "LowerArm", "Hand"}) {
                names.push_back(side + std::string(bone));
            }
        }
        for (const char* side : {"left", "right"}) {
            for (const char* bone : {"ThumbMetacarpal", "ThumbProximal", "ThumbDistal"}) {
                names.push_back(side + std::string(bone));
            }
            for (const char* finger : {"Index", "Middle", "Ring", "Little"}) {
                for (const char* part : {"Proximal", "Intermediate", "Distal"}) {
                    names.push_back(side + std::string(finger) + part);
                }
            }
        }
        return names;
    }();
    return kNames;
}

std::optional<Humanoid> readHumanBonesObject(const tinygltf::Model& model, const std::string& extension,
                                             std::vector<Warning>& warnings) {
    const auto found = model.extensions.find(extension);
    if (found == model.extensions.end()) return std::nullopt;
    Humanoid humanoid;
    const tinygltf::Value& root = found->second;
    const tinygltf::Value& bones = root.IsObject() && root.Has("humanoid") && root.Get("humanoid").IsObject() &&
                                           root.Get("humanoid").Has("humanBones")
                                       ? root.Get("humanoid").Get("humanBones")
                                       : tinygltf::Value();
    if (bones.IsObject()) {
        for (const std::string& bone : bones.Keys()) {
            const tinygltf::Value& entry = bones.Get(bone);
            addBone(model, extension + ".humanoid.humanBones", bone,
                    entry.IsObject() && entry.Has("node") ? entry.Get("node") : tinygltf::Value(), humanoid, warnings);
        }
    } else if (bones.Type() != tinygltf::NULL_TYPE) {
        warnings.push_back(makeWarning(WarningKind::VrmPropertyInvalid,
                                       extension + ".humanoid.humanBones is not an object" +
                                           (bones.IsArray() ? " (an array, as VRM 0.x's VRM writes it)" : "") +
                                           "; ignored",
                                       "", extension + ".humanoid.humanBones"));
    }
    return humanoid;
}

std::optional<Humanoid> readHumanoid(const tinygltf::Model& model, std::vector<Warning>& warnings) {
    if (std::optional<Humanoid> vrm1 = readHumanBonesObject(model, "VRMC_vrm", warnings)) return vrm1;
    Humanoid humanoid;
    const auto vrm0 = model.extensions.find("VRM");
    if (vrm0 == model.extensions.end()) return std::nullopt;
    humanoid.facesMinusZ = true;
    const tinygltf::Value& vrm = vrm0->second;
    const tinygltf::Value& bones =
        vrm.IsObject() && vrm.Has("humanoid") && vrm.Get("humanoid").IsObject() && vrm.Get("humanoid").Has("humanBones")
            ? vrm.Get("humanoid").Get("humanBones")
            : tinygltf::Value();
    if (!bones.IsArray()) {
        // An object is 1.0's form; without this the file was told it has no head bone.
        if (bones.Type() != tinygltf::NULL_TYPE)
            warnings.push_back(
                makeWarning(WarningKind::VrmPropertyInvalid,
                            std::string("VRM.humanoid.humanBones is not an array") +
                                (bones.IsObject() ? " (an object, as VRM 1.0's VRMC_vrm writes it)" : "") + "; ignored",
                            "", "VRM.humanoid.humanBones"));
        return humanoid;
    }
    for (std::size_t i = 0; i < bones.ArrayLen(); ++i) {
        const tinygltf::Value& entry = bones.Get(int(i));
        const std::string where = "VRM.humanoid.humanBones[" + std::to_string(i) + "]";
        if (!entry.IsObject() || !entry.Has("bone") || !entry.Get("bone").IsString()) {
            warnings.push_back(
                makeWarning(WarningKind::VrmPropertyInvalid, where + " has no bone name; ignored", "", where));
            continue;
        }
        const std::string name = entry.Get("bone").Get<std::string>();
        const auto renamed = kThumbsOf0x.find(name);
        addBone(model, where, renamed != kThumbsOf0x.end() ? renamed->second : name,
                entry.Has("node") ? entry.Get("node") : tinygltf::Value(), humanoid, warnings);
    }
    return humanoid;
}

HumanoidPose aPose() {
    const double angle = glm::radians(kAPoseArmDegrees);
    // In 1.0's frame the character's left arm points along +X: a turn about -Z takes it down, and about +Z the
    // right arm (along -X).
    return {{"leftUpperArm", glm::angleAxis(angle, glm::dvec3(0.0, 0.0, -1.0))},
            {"rightUpperArm", glm::angleAxis(angle, glm::dvec3(0.0, 0.0, 1.0))}};
}

HumanoidPose parsePoseFile(const std::string& posePath, const std::string& content, std::string_view function) {
    nlohmann::json document;
    // The parsed object keeps a bone's last value only; a bone given twice is found while parsing, as a style file
    // refuses a setting given twice.
    std::set<std::string> bones;
    std::optional<std::string> twice;
    const auto findTwice = [&](int depth, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
        if (event == nlohmann::json::parse_event_t::key && depth == 1 && !twice &&
            !bones.insert(parsed.get<std::string>()).second)
            twice = parsed.get<std::string>();
        return true;
    };
    // JSON text holds no NUL byte; the parser took one as the end of the input, so what followed was never read.
    if (const std::size_t nul = content.find('\0'); nul != std::string::npos)
        throwLoadError(posePath, "not a pose file: a NUL byte at byte " + std::to_string(nul) + " (JSON is text)",
                       function);
    try {
        document = nlohmann::json::parse(content, findTwice);
    } catch (const nlohmann::json::exception& error) {
        throwLoadError(posePath, std::string("not a pose file: invalid JSON (") + excerptForMessage(error.what()) + ")",
                       function);
    }
    if (twice)
        throwLoadError(posePath, "'" + excerptForMessage(*twice) + "' is given twice (a bone takes one quaternion)",
                       function);
    if (!document.is_object()) {
        throwLoadError(posePath,
                       "not a pose file: expected a JSON object of humanoid bone names to quaternions "
                       "[x, y, z, w]",
                       function);
    }
    HumanoidPose pose;
    for (const auto& [bone, value] : document.items()) {
        if (!isHumanoidBone(bone)) {
            throwLoadError(posePath,
                           "unknown humanoid bone '" + excerptForMessage(bone) +
                               "' (VRM's humanoid bones: " + boneNameList() + ")",
                           function);
        }
        const std::string where = "'" + bone + "'";
        if (!value.is_array() || value.size() != 4 ||
            !std::ranges::all_of(value, [](const nlohmann::json& number) { return number.is_number(); })) {
            throwLoadError(posePath, where + ": expected a quaternion [x, y, z, w] of four numbers", function);
        }
        const std::optional<glm::dquat> rotation = unitQuaternion(value[0].get<double>(), value[1].get<double>(),
                                                                  value[2].get<double>(), value[3].get<double>());
        if (!rotation)
            throwLoadError(posePath, where + ": the quaternion must be finite and of non-zero length", function);
        pose[bone] = *rotation;
    }
    return pose;
}

std::string readSideFile(const std::string& path, const std::string& kind, MeshBudget& budget,
                         std::string_view function) {
    // Judged before opening: a FIFO would block the open for ever, and a device has no end.
    std::error_code error;
    const std::filesystem::file_status status = std::filesystem::status(path, error);
    if (error && error != std::errc::no_such_file_or_directory)
        throwLoadError(path, "the " + kind + " cannot be looked at (" + error.message() + ")", function);
    if (!std::filesystem::exists(status)) throwLoadError(path, "the " + kind + " cannot be found", function);
    if (!std::filesystem::is_regular_file(status))
        throwLoadError(path, "the " + kind + " is not a regular file (a folder, FIFO or device)", function);
    std::ifstream file(path, std::ios::binary | std::ios::ate);
    if (!file) throwLoadError(path, "cannot open the " + kind + " for reading", function);
    const std::streamoff size = file.tellg();
    if (size < 0) throwLoadError(path, "cannot determine the " + kind + "'s size", function);
    budget.chargeFile(std::size_t(size));
    std::string content(std::size_t(size), '\0');
    file.seekg(0);
    if (!file.read(content.data(), size)) throwLoadError(path, "read error", function);
    return content;
}

HumanoidPose humanoidPose(const std::string& pose, MeshBudget& budget, std::string_view function) {
    if (pose == kAPoseName) return aPose();
    return parsePoseFile(pose, readSideFile(pose, "pose file", budget, function), function);
}

std::vector<int> nodeParents(const tinygltf::Model& model) {
    std::vector<int> parents(model.nodes.size(), -1);
    std::vector<bool> claimed(model.nodes.size(), false);
    for (std::size_t i = 0; i < model.nodes.size(); ++i) {
        for (const int child : model.nodes[i].children) {
            if (child < 0 || std::size_t(child) >= model.nodes.size() || claimed[std::size_t(child)]) continue;
            claimed[std::size_t(child)] = true;
            parents[std::size_t(child)] = int(i);
        }
    }
    return parents;
}

glm::dmat4 worldMatrix(const std::vector<NodePose>& poses, const std::vector<int>& parents, int node) {
    glm::dmat4 world(1.0);
    for (std::size_t steps = 0; node >= 0 && steps < poses.size(); ++steps) { // bounded as worldRotation()
        world = poses[std::size_t(node)].local() * world;
        node = parents[std::size_t(node)];
    }
    return world;
}

glm::dquat worldRotation(const std::vector<NodePose>& poses, const std::vector<int>& parents, int node) {
    glm::dquat world(1.0, 0.0, 0.0, 0.0);
    // Bounded by the node count: a cycle (refused later by the walk) must not loop here.
    for (std::size_t steps = 0; node >= 0 && steps < poses.size(); ++steps) {
        world = rotationOf(poses[std::size_t(node)]) * world;
        node = parents[std::size_t(node)];
    }
    return glm::normalize(world);
}

void applyHumanoidPose(const tinygltf::Model& model, const Humanoid& humanoid, const HumanoidPose& pose,
                       const std::vector<NodePose>& rest, std::vector<NodePose>& poses,
                       std::vector<Warning>& warnings) {
    const std::vector<int> parents = nodeParents(model);
    // Half a turn about Y takes 1.0's frame onto 0.x's: (x, y, z, w) -> (-x, y, -z, w), as three-vrm-animation turns
    // its tracks for a 0.x model.
    const auto inModelFrame = [&](const glm::dquat& q) {
        return humanoid.facesMinusZ ? glm::dquat(q.w, -q.x, q.y, -q.z) : q;
    };
    for (const auto& [bone, rotation] : pose) {
        const auto found = humanoid.nodeOfBone.find(bone);
        if (found == humanoid.nodeOfBone.end()) {
            warnings.push_back(makeWarning(WarningKind::PoseBoneMissing,
                                           "the pose turns '" + bone + "', which the model's humanoid lacks; ignored",
                                           "", bone));
            continue;
        }
        const int node = found->second;
        if (poses[std::size_t(node)].matrix) {
            warnings.push_back(makeWarning(WarningKind::PoseBoneMissing,
                                           "the pose turns '" + bone + "', whose node " + std::to_string(node) +
                                               " is given as a matrix, which cannot be turned; ignored",
                                           "", bone));
            continue;
        }
        // The normalized bone turns by q about world axes at rest: the node's posed world rotation is q * W, W its
        // rest world rotation P * R, so its local rotation under its parent's rest rotation P is P^-1 * q * P * R.
        // Posed ancestors compose in the same way, as three-vrm's normalized rig does.
        const int parent = parents[std::size_t(node)];
        const glm::dquat parentWorld =
            parent >= 0 ? worldRotation(rest, parents, parent) : glm::dquat(1.0, 0.0, 0.0, 0.0);
        poses[std::size_t(node)].rotation = glm::normalize(glm::inverse(parentWorld) * inModelFrame(rotation) *
                                                           parentWorld * rest[std::size_t(node)].rotation);
    }
}

} // namespace inkgraph::detail

namespace inkgraph {

void checkPoseFile(const std::string& pose, std::size_t memoryLimitBytes, std::string_view speaker) {
    if (pose.empty()) return;
    detail::MeshBudget budget(pose, memoryLimitBytes, speaker);
    detail::humanoidPose(pose, budget, speaker);
}

} // namespace inkgraph
