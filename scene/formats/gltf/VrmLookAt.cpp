/** @file VRM look-at after specification/VRMC_vrm-1.0/lookAt.md; VRM 0.x's firstPerson settings read as three-vrm
 *  reads them (xRange as inputMaxValue, yRange as outputScale, the curve taken as linear, firstPersonBoneOffset with
 *  Unity's z negated, the face toward -Z). */

#include "scene/formats/gltf/VrmLookAt.h"

#include "scene/formats/FormatReaders.h"
#include "scene/formats/gltf/GltfPose.h"
#include "scene/formats/gltf/VrmExpressions.h"
#include "scene/formats/gltf/VrmHumanoid.h"
#include "scene/MessageText.h"

#include <glm/gtc/constants.hpp>
#include <glm/gtc/quaternion.hpp>

#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

namespace inkgraph::detail {

namespace {

/** One of the specification's range maps: |yaw| or |pitch| up to inputMaxValue degrees scaled to outputScale. */
struct RangeMap {
    double inputMaxValue = 90.0;
    double outputScale = 10.0;

    double map(double degrees) const {
        // The specification's recommendation for inputMaxValue 0: 0 for a value of 0, outputScale otherwise.
        if (!(inputMaxValue > 0.0)) return degrees == 0.0 ? 0.0 : outputScale;
        return std::min(std::abs(degrees), inputMaxValue) / inputMaxValue * outputScale;
    }
};

/** The specification's default offsetFromHeadBone: 6 cm above the head bone. */
constexpr glm::dvec3 kDefaultOffsetFromHead{0.0, 0.06, 0.0};

/** The largest eye turn a bone range map may give, in degrees: an eye turned further looks out of the back of the
 *  head, and a turn of 1e300 degrees is no direction at all (its sine is rounding noise). */
constexpr double kMaxEyeTurnDegrees = 180.0;

struct LookAtSettings {
    bool bones = true; ///< type bone ("Bone"); false: expression ("BlendShape")
    glm::dvec3 offsetFromHead = kDefaultOffsetFromHead;
    std::string offsetWhere;    ///< where the file gives the offset, for a warning; empty: the default
    glm::dvec3 offsetAsGiven{}; ///< the offset in the file's words (0.x: Unity's z), for a warning
    bool facesMinusZ = false;   ///< VRM 0.x
    RangeMap horizontalInner, horizontalOuter, verticalDown, verticalUp;
};

/** A range map `where` (its JSON path) of the file; a bone map's output beyond kMaxEyeTurnDegrees is said and the
 *  default taken. */
RangeMap rangeMapOf(const tinygltf::Value* map, const std::string& where, const char* inputKey, const char* outputKey,
                    bool bones, std::vector<Warning>& warnings) {
    // Defaults as three-vrm takes them: 90 degrees to 10 degrees of eye rotation, or to a weight of 1.
    const double defaultOutput = bones ? 10.0 : 1.0;
    RangeMap result;
    result.inputMaxValue = std::max(0.0, jsonNumber(jsonMember(map, inputKey)).value_or(90.0));
    result.outputScale = jsonNumber(jsonMember(map, outputKey)).value_or(defaultOutput);
    // An expression's weight is clamped to [0, 1] where it is set, whatever the map gives.
    if (bones && !(std::abs(result.outputScale) <= kMaxEyeTurnDegrees)) {
        warnings.push_back(makeWarning(WarningKind::VrmPropertyInvalid,
                                       where + "." + outputKey + " is " + formatNumber(result.outputScale) +
                                           " degrees of eye turn, beyond " + formatNumber(kMaxEyeTurnDegrees) +
                                           "; the default " + formatNumber(defaultOutput) + " is used",
                                       "", where));
        result.outputScale = defaultOutput;
    }
    return result;
}

/** The look-at settings of a VRM 1.0 or 0.x file, or none. */
std::optional<LookAtSettings> readSettings(const tinygltf::Model& model, std::vector<Warning>& warnings) {
    LookAtSettings settings;
    if (const auto vrm1 = model.extensions.find("VRMC_vrm"); vrm1 != model.extensions.end()) {
        const tinygltf::Value* lookAt = jsonMember(&vrm1->second, "lookAt");
        if (lookAt == nullptr) return std::nullopt;
        settings.bones = jsonString(jsonMember(lookAt, "type")) != "expression";
        if (const auto offset = jsonNumbers(jsonMember(lookAt, "offsetFromHeadBone"), 3)) {
            settings.offsetFromHead = {(*offset)[0], (*offset)[1], (*offset)[2]};
            settings.offsetWhere = "VRMC_vrm.lookAt.offsetFromHeadBone";
            settings.offsetAsGiven = settings.offsetFromHead;
        }
        const auto map = [&](const char* name) {
            return rangeMapOf(jsonMember(lookAt, name), std::string("VRMC_vrm.lookAt.") + name, "inputMaxValue",
                              "outputScale", settings.bones, warnings);
        };
        settings.horizontalInner = map("rangeMapHorizontalInner");
        settings.horizontalOuter = map("rangeMapHorizontalOuter");
        settings.verticalDown = map("rangeMapVerticalDown");
        settings.verticalUp = map("rangeMapVerticalUp");
        return settings;
    }
    const auto vrm0 = model.extensions.find("VRM");
    if (vrm0 == model.extensions.end()) return std::nullopt;
    const tinygltf::Value* firstPerson = jsonMember(&vrm0->second, "firstPerson");
    const std::string type = jsonString(jsonMember(firstPerson, "lookAtTypeName"));
    if (type != "Bone" && type != "BlendShape") return std::nullopt;
    settings.bones = type == "Bone";
    settings.facesMinusZ = true;
    if (const tinygltf::Value* offset = jsonMember(firstPerson, "firstPersonBoneOffset")) {
        settings.offsetFromHead = {jsonNumber(jsonMember(offset, "x")).value_or(0.0),
                                   jsonNumber(jsonMember(offset, "y")).value_or(0.06),
                                   -jsonNumber(jsonMember(offset, "z")).value_or(0.0)};
        settings.offsetWhere = "VRM.firstPerson.firstPersonBoneOffset";
        settings.offsetAsGiven = settings.offsetFromHead * glm::dvec3(1.0, 1.0, -1.0);
    }
    const auto map = [&](const char* name) {
        return rangeMapOf(jsonMember(firstPerson, name), std::string("VRM.firstPerson.") + name, "xRange", "yRange",
                          settings.bones, warnings);
    };
    settings.horizontalInner = map("lookAtHorizontalInner");
    settings.horizontalOuter = map("lookAtHorizontalOuter");
    settings.verticalDown = map("lookAtVerticalDown");
    settings.verticalUp = map("lookAtVerticalUp");
    return settings;
}

glm::dmat4 worldOf(int node, const std::vector<int>& parents, const std::vector<NodePose>& poses) {
    glm::dmat4 world(1.0);
    // Bounded by the node count, so a cycle (refused by the walk later) cannot loop here.
    for (std::size_t steps = 0; node >= 0 && steps <= poses.size(); ++steps) {
        world = poses[std::size_t(node)].local() * world;
        node = parents[std::size_t(node)];
    }
    return world;
}

/** The rotation of a transform without shear (its columns normalised). */
glm::dquat rotationOf(const glm::dmat4& transform) {
    glm::dmat3 linear(transform);
    for (int column = 0; column < 3; ++column) {
        const double length = glm::length(linear[column]);
        if (length > 0.0) linear[column] /= length;
    }
    return glm::normalize(glm::quat_cast(linear));
}

/** Says an offset from the head that is not a number, or that places the look-at space farther from the head than
 *  the head is from the hips (outside the head: the file's 1e300 turned the eyes to their limit whatever the target),
 *  and takes the default instead. Judged in the world, so a rig in centimetres (a head scaled by 0.01) is judged by
 *  its own size. */
void checkOffsetFromHead(LookAtSettings& settings, const glm::dmat4& headWorld,
                         const std::optional<glm::dmat4>& hipsWorld, std::vector<Warning>& warnings) {
    if (settings.offsetWhere.empty()) return;
    const glm::dvec3 head(headWorld[3]);
    // By hypot, which does not overflow where the sum of squares of an offset of 1e300 would.
    const auto length = [](const glm::dvec3& v) { return std::hypot(v.x, std::hypot(v.y, v.z)); };
    const double fromHead = length(glm::dvec3(headWorld * glm::dvec4(settings.offsetFromHead, 1.0)) - head);
    const double headToHips = hipsWorld ? length(glm::dvec3((*hipsWorld)[3]) - head) : 0.0;
    const bool finite = std::isfinite(fromHead);
    if (finite && !(hipsWorld && headToHips > 0.0 && fromHead > headToHips)) return;
    const glm::dvec3& offset = settings.offsetAsGiven;
    warnings.push_back(
        makeWarning(WarningKind::VrmPropertyInvalid,
                    settings.offsetWhere + " (" + formatNumber(offset.x) + ", " + formatNumber(offset.y) + ", " +
                        formatNumber(offset.z) + ") " +
                        (finite ? "lies " + formatNumber(fromHead) + " from the head, farther than the hips (" +
                                      formatNumber(headToHips) + ")"
                                : std::string("puts the eyes' origin beyond the numbers")) +
                        "; the default (0, 0.06, 0) is used",
                    "", settings.offsetWhere));
    settings.offsetFromHead = kDefaultOffsetFromHead;
}

} // namespace

VrmGaze applyVrmLookAt(const std::string& path, const tinygltf::Model& model, const Humanoid* humanoid,
                       const glm::dvec3& target, const std::vector<NodePose>& restPoses, std::vector<NodePose>& poses,
                       VrmExpressions& expressions, std::vector<Warning>& warnings) {
    std::optional<LookAtSettings> settings = readSettings(model, warnings);
    if (!settings) {
        throwLoadError(path, "--look-at: the file has no VRM look-at settings (VRM 1.0 VRMC_vrm.lookAt, or VRM 0.x "
                             "firstPerson.lookAtTypeName 'Bone' or 'BlendShape')");
    }
    // readHumanoid() keeps only bones whose nodes are in range.
    const auto boneNode = [&](const char* bone) {
        if (humanoid == nullptr) return -1;
        const auto found = humanoid->nodeOfBone.find(bone);
        return found == humanoid->nodeOfBone.end() ? -1 : found->second;
    };
    const int head = boneNode("head");
    const int leftEye = boneNode("leftEye");
    const int rightEye = boneNode("rightEye");
    if (head < 0) throwLoadError(path, "--look-at: the file's humanoid has no head bone");
    const std::vector<int> parents = nodeParents(model);

    // The look-at space: at offsetFromHeadBone in the head's frame, turned as the head turned from its rest pose (so
    // at rest its axes are the model's), and for a 0.x character turned round to face -Z.
    const glm::dmat4 headWorld = worldOf(head, parents, poses);
    checkOffsetFromHead(*settings, headWorld,
                        boneNode("hips") >= 0 ? std::optional(worldOf(boneNode("hips"), parents, poses)) : std::nullopt,
                        warnings);
    const glm::dquat faceFront = settings->facesMinusZ ? glm::angleAxis(glm::pi<double>(), glm::dvec3(0.0, 1.0, 0.0))
                                                       : glm::dquat(1.0, 0.0, 0.0, 0.0);
    const glm::dquat space =
        rotationOf(headWorld) * glm::inverse(rotationOf(worldOf(head, parents, restPoses))) * faceFront;
    const glm::dvec3 origin(headWorld * glm::dvec4(settings->offsetFromHead, 1.0));
    const glm::dvec3 local = glm::inverse(space) * (target - origin);
    VrmGaze gaze;
    gaze.yawDegrees = glm::degrees(std::atan2(local.x, local.z));
    gaze.pitchDegrees = glm::degrees(std::atan2(-local.y, std::hypot(local.x, local.z)));
    const double yaw = gaze.yawDegrees;
    const double pitch = gaze.pitchDegrees;

    if (!settings->bones) {
        if (!expressions.has("lookLeft") && !expressions.has("lookRight") && !expressions.has("lookUp") &&
            !expressions.has("lookDown")) {
            throwLoadError(path, "--look-at: the file's look-at moves the eyes by expressions, but it has none of "
                                 "lookUp, lookDown, lookLeft, lookRight");
        }
        // Only the horizontal outer map drives lookLeft and lookRight: both eyes move in one expression.
        const auto set = [&](const char* name, double weight) {
            if (expressions.has(name)) expressions.setWeight(name, std::clamp(weight, 0.0, 1.0), "--look-at");
        };
        set("lookLeft", yaw > 0.0 ? settings->horizontalOuter.map(yaw) : 0.0);
        set("lookRight", yaw > 0.0 ? 0.0 : settings->horizontalOuter.map(yaw));
        set("lookDown", pitch > 0.0 ? settings->verticalDown.map(pitch) : 0.0);
        set("lookUp", pitch > 0.0 ? 0.0 : settings->verticalUp.map(pitch));
        gaze.setExpressions = true;
        return gaze;
    }

    const double eyePitch = pitch > 0.0 ? settings->verticalDown.map(pitch) : -settings->verticalUp.map(pitch);
    // Yaw to the left turns the left eye outward and the right eye inward.
    const double leftYaw = yaw > 0.0 ? settings->horizontalOuter.map(yaw) : -settings->horizontalInner.map(yaw);
    const double rightYaw = yaw > 0.0 ? settings->horizontalInner.map(yaw) : -settings->horizontalOuter.map(yaw);
    struct Turn {
        int node;
        double yawDegrees;
    };
    std::vector<std::pair<int, glm::dquat>> turned;
    for (const Turn& eye : {Turn{leftEye, leftYaw}, Turn{rightEye, rightYaw}}) {
        if (eye.node < 0) {
            throwLoadError(path, std::string("--look-at: the file's look-at type is bone but its humanoid has no ") +
                                     (eye.node == leftEye ? "leftEye" : "rightEye") + " bone");
        }
        if (poses[std::size_t(eye.node)].matrix) {
            throwLoadError(path, "--look-at: eye bone node " + std::to_string(eye.node) +
                                     " is given as a matrix, which cannot be turned");
        }
        // The specification's local rotation, Euler YXZ (yaw about +Y, then pitch about +X), is taken in the look-at
        // space and applied on top of the eye's present world rotation.
        const glm::dquat gazeTurn = glm::angleAxis(glm::radians(eye.yawDegrees), glm::dvec3(0.0, 1.0, 0.0)) *
                                    glm::angleAxis(glm::radians(eyePitch), glm::dvec3(1.0, 0.0, 0.0));
        const int parent = parents[std::size_t(eye.node)];
        const glm::dquat parentWorld =
            parent >= 0 ? rotationOf(worldOf(parent, parents, poses)) : glm::dquat(1, 0, 0, 0);
        const glm::dquat eyeWorld = parentWorld * poses[std::size_t(eye.node)].rotation;
        const glm::dquat turnedWorld = space * gazeTurn * glm::inverse(space) * eyeWorld;
        turned.emplace_back(eye.node, glm::normalize(glm::inverse(parentWorld) * turnedWorld));
    }
    for (const auto& [node, rotation] : turned) poses[std::size_t(node)].rotation = rotation;
    return gaze;
}

} // namespace inkgraph::detail
