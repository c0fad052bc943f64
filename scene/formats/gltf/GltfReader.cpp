/** @file glTF 2.0 (.gltf JSON and .glb, and VRM, a GLB) through the packaged tinygltf, and the format table's rows
 *  for them. tinygltf parses and resolves buffers (through GltfFiles.h's callbacks); this file walks the node
 *  hierarchy, bakes node transforms (posed by GltfPose.h) into world space, reads each triangle primitive's attributes
 *  and indices (GltfAccessors.h, or GltfDraco.h when compressed) and picks up the first perspective camera and the
 *  first directional KHR_lights_punctual light; each primitive's material comes from GltfMaterials.h. */

#include "scene/formats/FormatTable.h"
#include "scene/formats/gltf/GltfAccessors.h"
#include "scene/formats/gltf/GltfDraco.h"
#include "scene/formats/gltf/GltfFiles.h"
#include "scene/formats/gltf/GltfMaterials.h"
#include "scene/formats/gltf/GltfMeshopt.h"
#include "scene/formats/gltf/GltfPose.h"
#include "scene/formats/ShaderValues.h"
#include "scene/formats/gltf/VrmAnimation.h"
#include "scene/formats/gltf/VrmHumanoid.h"
#include "scene/formats/gltf/VrmExpressions.h"
#include "scene/formats/gltf/VrmLookAt.h"
#include "scene/formats/gltf/VrmMaterials.h"

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <string_view>

namespace inkgraph::detail {

namespace {

/** The one list of what this reader implements (supportedGltfExtensions()): KHR_lights_punctual's directional light,
 *  KHR_mesh_quantization's integer and normalized attributes (GltfAccessors.cpp reads any component type),
 *  KHR_draco_mesh_compression (GltfDraco.cpp), EXT_meshopt_compression (GltfMeshopt.cpp), KHR_texture_transform,
 *  KHR_materials_unlit, KHR_materials_emissive_strength, VRM 0.x ("VRM": its front and MToon materialProperties) and
 *  1.0 ("VRMC_vrm": its front; "VRMC_materials_mtoon"), scene/formats/gltf/VrmMaterials.h;
 * KHR_materials_pbrSpecularGlossiness's diffuse colour and EXT_texture_webp's images (GltfMaterials.cpp, decoded by
 * scene/TextureImage.cpp). */
const std::vector<std::string> kSupportedExtensions = {"KHR_lights_punctual",
                                                       "KHR_mesh_quantization",
                                                       "KHR_draco_mesh_compression",
                                                       "EXT_meshopt_compression",
                                                       "KHR_texture_transform",
                                                       "KHR_materials_unlit",
                                                       "KHR_materials_emissive_strength",
                                                       "KHR_materials_pbrSpecularGlossiness",
                                                       "EXT_texture_webp",
                                                       "VRM",
                                                       "VRMC_materials_mtoon",
                                                       "VRMC_vrm"};

static_assert(std::endian::native == std::endian::little, "glTF buffers are little-endian; add byte swapping");

std::vector<std::string> splitLines(const std::string& text) {
    std::vector<std::string> lines;
    std::size_t start = 0;
    while (start < text.size()) {
        std::size_t end = text.find('\n', start);
        if (end == std::string::npos) {
            end = text.size();
        }
        std::string line = text.substr(start, end - start);
        while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) {
            line.pop_back();
        }
        if (!line.empty()) {
            lines.push_back(std::move(line));
        }
        start = end + 1;
    }
    return lines;
}

/** A tinygltf message with every long word (a data: URI, a file name, a name from the file) cut by
 *  excerptForMessage(): tinygltf quotes what the file gives it whole, a 64 MB data: URI included. */
std::string shortenWords(const std::string& line) {
    std::string shortened;
    std::size_t start = 0;
    while (start < line.size()) {
        std::size_t end = line.find(' ', start);
        if (end == std::string::npos) {
            end = line.size();
        }
        shortened += excerptForMessage(std::string_view(line).substr(start, end - start));
        if (end < line.size()) {
            shortened += ' ';
        }
        start = end + 1;
    }
    // Many short words (a long name with spaces) must not make a long line either.
    constexpr std::size_t kMaxLineChars = 5 * kMessageExcerptChars;
    if (shortened.size() > kMaxLineChars) {
        shortened = shortened.substr(0, kMaxLineChars) + "... (" + std::to_string(shortened.size()) + " bytes)";
    }
    return shortened;
}

std::string joinLines(const std::string& text) {
    std::string joined;
    for (const std::string& line : splitLines(text)) {
        joined += (joined.empty() ? "" : "; ") + shortenWords(line);
    }
    return joined;
}

const char* modeName(int mode) {
    switch (mode) {
    case TINYGLTF_MODE_POINTS: return "POINTS";
    case TINYGLTF_MODE_LINE: return "LINES";
    case TINYGLTF_MODE_LINE_LOOP: return "LINE_LOOP";
    case TINYGLTF_MODE_LINE_STRIP: return "LINE_STRIP";
    default: return "unknown";
    }
}

/** A normal through a normal matrix, unit length again (zero when the matrix collapses it). */
glm::vec3 transformNormal(const glm::dmat3& normalMatrix, const glm::vec3& normal) {
    const glm::dvec3 transformed = normalMatrix * glm::dvec3(normal);
    const double length = glm::length(transformed);
    return length > 0.0 && std::isfinite(length) ? glm::vec3(transformed / length) : glm::vec3(0.0f);
}

class GltfWalker {
public:
    GltfWalker(const std::string& path, const tinygltf::Model& model, RawScene& out, MeshBudget& budget,
               const LoadOptions& options)
        : mPath(path), mModel(model), mOut(out), mBudget(budget), mOptions(options),
          mReached(model.nodes.size(), false), mWorlds(model.nodes.size()), mMaterials(path, model, out.warnings) {}

    void walk() {
        checkRequiredExtensions();
        checkMaterialIndices();
        readVrmFront();
        checkVrmVersion();
        posed();
        // Depth-first with an explicit stack (a deep hierarchy must not overflow the call stack), in the order the
        // recursive walk would take: roots and children are pushed in reverse so the first is handled first.
        std::vector<int> pending;
        const std::vector<int> roots = rootNodes();
        for (auto root = roots.rbegin(); root != roots.rend(); ++root) {
            claimRoot(*root);
            pending.push_back(*root);
        }
        // Every world transform first, then the visits: a skinned mesh needs its joints' transforms, wherever they
        // are in the hierarchy.
        std::vector<int> visitOrder;
        while (!pending.empty()) {
            const int index = pending.back();
            pending.pop_back();
            const tinygltf::Node& node = mModel.nodes[std::size_t(index)];
            const int parent = mParent[std::size_t(index)];
            mPreciseWorlds[std::size_t(index)] =
                (parent >= 0 ? *mPreciseWorlds[std::size_t(parent)] : PreciseTransform()) *
                mPoses[std::size_t(index)].local();
            visitOrder.push_back(index);
            for (auto child = node.children.rbegin(); child != node.children.rend(); ++child) {
                claimChild(index, *child);
                pending.push_back(*child);
            }
        }
        // Everything is baked relative to the scene's origin, taken before rounding to double (PreciseTransform), so a
        // model placed 1e17 units out keeps the shape it has at the world origin.
        mOut.origin = placementOrigin(visitOrder);
        for (const int index : visitOrder) {
            mWorlds[std::size_t(index)] = mPreciseWorlds[std::size_t(index)]->relativeTo(mOut.origin);
        }
        for (const int index : visitOrder) {
            visit(index, mModel.nodes[std::size_t(index)], *mWorlds[std::size_t(index)]);
        }
        // Said with the warnings of every primitive left out (points, lines, no POSITION), which say why.
        if (mOut.meshes.empty() && mSkippedPrimitives > 0) throwLoadError(mPath, noTrianglesInTheFile(mOut.warnings));
        checkPlacementPrecision();
        collectJoints(visitOrder);
    }

private:
    /** Says the vertices of a skinned primitive whose weights vertexMatrix() normalises or cannot use: a program
     *  skinning the file's weights itself would place them elsewhere than the picture does. */
    void warnWeightSums(const SkinBlend& skin, const std::string& meshName) {
        const SkinBlend::WeightSums sums = skin.weightSums();
        if (sums.unnormalised + sums.zero == 0) return;
        const auto vertices = [](std::size_t count) {
            return std::to_string(count) + (count == 1 ? " vertex's" : " vertices'");
        };
        std::string what;
        if (sums.unnormalised > 0)
            what = vertices(sums.unnormalised) +
                   " joint weights do not sum to 1 (glTF asks that they do); each vertex's are scaled to sum 1";
        if (sums.zero > 0)
            what += (what.empty() ? "" : "; ") + vertices(sums.zero) +
                    " weights are all 0: " + (sums.zero == 1 ? "it follows" : "they follow") +
                    " the mesh's node, unskinned";
        mOut.warnings.push_back(makeWarning(WarningKind::SkinWeightsUnnormalised,
                                            quotedExcerpt(meshName) + ": " + what + " (first: vertex " +
                                                std::to_string(sums.firstVertex) + ", weights summing to " +
                                                formatNumber(sums.firstSum) + ")",
                                            "", meshName));
    }

    /** Grows the box of each joint node that weights a posed vertex by it (SceneJoint::lower, upper). */
    void addToJointBoxes(const SkinBlend& blend, int skinIndex, const std::vector<glm::vec3>& positions) {
        const std::vector<int>& jointNodes = mModel.skins[std::size_t(skinIndex)].joints; // checked: jointMatrices()
        for (std::size_t v = 0; v < positions.size(); ++v) {
            blend.forEachJoint(v, [&](std::size_t joint) {
                mJointBoxes[std::size_t(jointNodes[joint])].add(glm::dvec3(positions[v]));
            });
        }
    }

    /** RawScene::joints: every skin joint and humanoid bone node reached by the walk, each box grown by its
     *  descendants' (a parent comes before its children in `visitOrder`, so the reverse order sees children first). */
    void collectJoints(const std::vector<int>& visitOrder) {
        for (auto node = visitOrder.rbegin(); node != visitOrder.rend(); ++node) {
            const int parent = mParent[std::size_t(*node)];
            const BoundingBox& box = mJointBoxes[std::size_t(*node)];
            if (parent >= 0 && !box.empty()) {
                mJointBoxes[std::size_t(parent)].add(box.min);
                mJointBoxes[std::size_t(parent)].add(box.max);
            }
        }
        std::vector<std::string> boneOf(mModel.nodes.size());
        if (mHumanoid) {
            for (const auto& [bone, node] : mHumanoid->nodeOfBone) boneOf[std::size_t(node)] = bone;
        }
        std::vector<bool> isJoint(mModel.nodes.size(), false);
        for (const tinygltf::Skin& skin : mModel.skins) {
            for (const int joint : skin.joints) {
                if (joint >= 0 && std::size_t(joint) < isJoint.size()) isJoint[std::size_t(joint)] = true;
            }
        }
        for (std::size_t node = 0; node < mModel.nodes.size(); ++node) {
            if (!mReached[node] || (!isJoint[node] && boneOf[node].empty())) continue;
            SceneJoint joint;
            joint.node = mModel.nodes[node].name;
            joint.bone = boneOf[node];
            joint.lower = mJointBoxes[node].min;
            joint.upper = mJointBoxes[node].max;
            mBudget.chargeBytes(sizeof(SceneJoint) + joint.node.size());
            mOut.joints.push_back(std::move(joint));
        }
    }

    [[noreturn]] void fail(const std::string& problem) const { throwLoadError(mPath, problem); }

    /** The scene's origin (RawScene::origin): the world translation of the node that places the first mesh (its skin's
     *  first joint for a skinned one), so that the model's own coordinates stay small whatever its placement. */
    glm::dvec3 placementOrigin(const std::vector<int>& visitOrder) const {
        for (const int index : visitOrder) {
            const tinygltf::Node& node = mModel.nodes[std::size_t(index)];
            if (node.mesh < 0) continue;
            if (node.skin >= 0 && std::size_t(node.skin) < mModel.skins.size()) {
                const std::vector<int>& joints = mModel.skins[std::size_t(node.skin)].joints;
                if (!joints.empty() && joints[0] >= 0 && std::size_t(joints[0]) < mPreciseWorlds.size() &&
                    mPreciseWorlds[std::size_t(joints[0])])
                    return mPreciseWorlds[std::size_t(joints[0])]->translation();
            }
            return mPreciseWorlds[std::size_t(index)]->translation();
        }
        return glm::dvec3(0.0);
    }

    /** Records how precisely `placement` (a mesh node's world transform, or a joint's matrix) was composed, for
     *  checkPlacementPrecision(). */
    void notePlacement(const PreciseTransform& placement, const std::string& label) {
        // Each composition step rounds below about 2^-102 of its largest term (a compensated dot product of four).
        const double error = placement.magnitude() * double(placement.steps() + 1) * std::ldexp(1.0, -100);
        if (error > mPlacementError) {
            mPlacementError = error;
            mPlacementLabel = label;
            mPlacementMagnitude = placement.magnitude();
        }
    }

    /** Refuses a model whose placement the double-double composition could not resolve: translations so much larger
     *  than the model (about 1e22 times) that even 32 digits leave its positions off by more than float's
     *  resolution of them, which would draw a distorted model without a word. */
    void checkPlacementPrecision() const {
        BoundingBox box;
        for (const RawMesh& mesh : mOut.meshes)
            for (const glm::vec3& p : mesh.positions) box.add(glm::dvec3(p));
        const double resolution = box.diagonal() * std::ldexp(1.0, -24); // float's, for the stored positions
        if (mPlacementError > resolution) {
            fail(mPlacementLabel + ": its transforms place it " + formatExtent(mPlacementMagnitude) +
                 " units from the world origin, too far to resolve a model " + formatExtent(box.diagonal()) +
                 " units across (positions could be off by " + formatExtent(mPlacementError) +
                 "); move the model nearer the origin in the file");
        }
    }

    /** The nodes' local transforms and morph weights: their own, or the animation LoadOptions names at its time. */
    void posed() {
        mPoses = restPose(mPath, mModel);
        mHumanoid = readHumanoid(mModel, mOut.warnings);
        const bool vrma = !mOptions.animation.empty() && isVrmAnimationFile(mOptions.animation);
        if ((vrma || !mOptions.pose.empty()) && !mHumanoid) {
            fail(std::string("cannot take a humanoid ") + (vrma ? "animation" : "pose") +
                 ": not a VRM model (no VRMC_vrm or VRM extension)");
        }
        if (vrma) {
            applyVrmAnimation(mOptions.animation, mOptions.time, mModel, *mHumanoid, restPose(mPath, mModel), mPoses,
                              mBudget, mOut.warnings);
            mOut.inputFiles.push_back(mOptions.animation);
        } else if (!mOptions.animation.empty()) {
            applyAnimation(mPath, mModel, findAnimation(mPath, mModel, mOptions.animation), mOptions.time, mPoses,
                           mBudget, mOut.warnings);
        }
        if (!mOptions.pose.empty()) {
            const HumanoidPose pose = humanoidPose(mOptions.pose, mBudget);
            if (mOptions.pose != kAPoseName) mOut.inputFiles.push_back(mOptions.pose);
            applyHumanoidPose(mModel, *mHumanoid, pose, restPose(mPath, mModel), mPoses, mOut.warnings);
        }
        applyVrmFace();
    }

    /** --expression and --look-at, after the animation: the VRM expressions' morph weights and the eye bones onto the
     *  poses; the expressions' material binds are applied as each material is taken (addPrimitive()). */
    void applyVrmFace() {
        if (mOptions.expressions.empty() && !mOptions.lookAt) return;
        VrmExpressions& expressions = mExpressions.emplace(mPath, mModel, mOut.warnings);
        if (!mOptions.expressions.empty() && expressions.empty())
            fail("--expression: the file has no VRM expressions (VRM 1.0 VRMC_vrm.expressions or VRM 0.x "
                 "blendShapeMaster)");
        for (const ExpressionWeight& expression : mOptions.expressions)
            expressions.setWeight(expression.name, expression.weight, "--expression");
        if (mOptions.lookAt) {
            const VrmGaze gaze = applyVrmLookAt(mPath, mModel, mHumanoid ? &*mHumanoid : nullptr, *mOptions.lookAt,
                                                restPose(mPath, mModel), mPoses, expressions, mOut.warnings);
            for (const ExpressionWeight& expression : mOptions.expressions) {
                const std::string name = expressions.canonicalName(expression.name);
                if (gaze.setExpressions && name.starts_with("look"))
                    fail("--expression '" + excerptForMessage(expression.name) +
                         "' and --look-at both set it (the file's look-at moves the eyes by expressions)");
            }
        }
        expressions.applyToPoses(mPoses);
    }

    /** The glTF 2.0 specification: a loader must refuse a file that requires an extension it does not implement,
     *  since the file may not make sense without it (compressed geometry reads as garbage, for one). */
    void checkRequiredExtensions() {
        std::string unsupported;
        std::size_t unsupportedCount = 0;
        for (const std::string& extension : mModel.extensionsRequired) {
            if (std::ranges::find(supportedGltfExtensions(), extension) == supportedGltfExtensions().end()) {
                if (++unsupportedCount <= kMaxNamedExtensions) {
                    unsupported += (unsupported.empty() ? "'" : ", '") + excerptForMessage(extension) + "'";
                }
            }
        }
        if (unsupportedCount > kMaxNamedExtensions) {
            unsupported += " and " + std::to_string(unsupportedCount - kMaxNamedExtensions) + " more";
        }
        if (unsupportedCount > 0) {
            std::string supported;
            for (const std::string& extension : supportedGltfExtensions()) {
                supported += (supported.empty() ? "'" : ", '") + extension + "'";
            }
            fail("requires the unsupported extension" + std::string(unsupportedCount > 1 ? "s " : " ") + unsupported +
                 " (extensionsRequired; supported: " + supported + ")");
        }
    }

    /** A VRM character faces its specification's front: -Z in VRM 0.x (extension "VRM"), +Z in VRM 1.0
     *  ("VRMC_vrm"), so auto-framing shows its face, not its back. */
    void readVrmFront() {
        const auto uses = [&](const char* name) {
            return std::ranges::find(mModel.extensionsUsed, std::string(name)) != mModel.extensionsUsed.end();
        };
        if (uses("VRMC_vrm"))
            mOut.front = glm::dvec3(0.0, 0.0, 1.0);
        else if (uses("VRM"))
            mOut.front = glm::dvec3(0.0, 0.0, -1.0);
    }

    /** VRM 1.0 requires `specVersion` "1.0" (or a pre-release of it, "1.0-beta"). A file that names another version
     *  (a later one whose meaning may differ) or none is read as 1.0, and said. */
    void checkVrmVersion() {
        const auto vrm1 = mModel.extensions.find("VRMC_vrm");
        if (vrm1 == mModel.extensions.end()) return;
        const tinygltf::Value* version = jsonMember(&vrm1->second, "specVersion");
        const bool isString = version != nullptr && version->IsString();
        const std::string text = isString ? version->Get<std::string>() : std::string();
        if (text == "1.0" || text.starts_with("1.0-")) return;
        const std::string problem = version == nullptr ? "missing"
                                    : isString         ? quotedExcerpt(text) + " is not a version this reader knows"
                                                       : "not a string";
        mOut.warnings.push_back(makeWarning(WarningKind::VrmPropertyInvalid,
                                            "VRMC_vrm.specVersion: " + problem + "; read as VRM 1.0", mPath,
                                            "specVersion"));
    }

    /** A primitive naming a material that does not exist would silently take the default colour and shade map. */
    void checkMaterialIndices() const {
        for (std::size_t meshIndex = 0; meshIndex < mModel.meshes.size(); ++meshIndex) {
            const tinygltf::Mesh& mesh = mModel.meshes[meshIndex];
            for (std::size_t i = 0; i < mesh.primitives.size(); ++i) {
                const int material = mesh.primitives[i].material;
                // tinygltf leaves an absent "material" at -1; any other negative value was written in the file.
                if (material < -1 || (material >= 0 && std::size_t(material) >= mModel.materials.size())) {
                    fail("mesh " + std::to_string(meshIndex) +
                         (mesh.name.empty() ? "" : " '" + excerptForMessage(mesh.name) + "'") + " primitive " +
                         std::to_string(i) + ": material index " + std::to_string(material) +
                         " out of range (file has " + std::to_string(mModel.materials.size()) + " materials)");
                }
            }
        }
    }

    std::vector<int> rootNodes() const {
        // tinygltf leaves an absent "scene" at -1; drawing another scene than the one asked for would be wrong.
        if (mModel.defaultScene < -1 ||
            (mModel.defaultScene >= 0 && std::size_t(mModel.defaultScene) >= mModel.scenes.size())) {
            fail("\"scene\": " + std::to_string(mModel.defaultScene) + " is out of range (file has " +
                 std::to_string(mModel.scenes.size()) + " scenes)");
        }
        if (!mModel.scenes.empty()) {
            return mModel.scenes[mModel.defaultScene >= 0 ? std::size_t(mModel.defaultScene) : 0].nodes;
        }
        // No scenes: every node that is nobody's child is a root.
        std::vector<bool> isChild(mModel.nodes.size(), false);
        for (const tinygltf::Node& node : mModel.nodes) {
            for (int child : node.children) {
                if (child >= 0 && std::size_t(child) < isChild.size()) {
                    isChild[std::size_t(child)] = true;
                }
            }
        }
        std::vector<int> roots;
        for (std::size_t i = 0; i < mModel.nodes.size(); ++i) {
            if (!isChild[i]) {
                roots.push_back(int(i));
            }
        }
        return roots;
    }

    void checkNodeIndex(int nodeIndex, const std::string& referrer) const {
        if (nodeIndex < 0 || std::size_t(nodeIndex) >= mModel.nodes.size()) {
            fail(referrer + ": node index " + std::to_string(nodeIndex) + " out of range (file has " +
                 std::to_string(mModel.nodes.size()) + " nodes)");
        }
    }

    void claimRoot(int nodeIndex) {
        checkNodeIndex(nodeIndex, "scene");
        if (mReached[std::size_t(nodeIndex)]) {
            fail("scene: node " + std::to_string(nodeIndex) + " is listed more than once as a root");
        }
        mReached[std::size_t(nodeIndex)] = true;
    }

    /** glTF 2.0 requires a strict forest: every node has at most one parent and no node is its own ancestor. Marking
     *  each node the first time it is reached, and rejecting a second time, enforces both and keeps the walk linear
     *  (shared children would otherwise be expanded once per path, exponentially often). */
    void claimChild(int parentIndex, int nodeIndex) {
        checkNodeIndex(nodeIndex, "node " + std::to_string(parentIndex) + " children");
        if (mReached[std::size_t(nodeIndex)]) {
            fail("node " + std::to_string(nodeIndex) + " has more than one parent (or is in a cycle)");
        }
        mReached[std::size_t(nodeIndex)] = true;
        mParent[std::size_t(nodeIndex)] = parentIndex;
    }

    void visit(int nodeIndex, const tinygltf::Node& node, const glm::dmat4& world) {
        if (node.mesh >= 0) {
            addMesh(nodeIndex, node, world);
        }
        if (node.camera >= 0) {
            addCamera(node, world);
        }
        addLight(node, world);
    }

    /** "camera 2 'main'", or "camera 2" for an unnamed one. */
    std::string cameraLabel(int cameraIndex) const {
        const std::string& name = mModel.cameras[std::size_t(cameraIndex)].name;
        return "camera " + std::to_string(cameraIndex) + (name.empty() ? "" : " '" + excerptForMessage(name) + "'");
    }

    void addCamera(const tinygltf::Node& node, const glm::dmat4& world) {
        if (std::size_t(node.camera) >= mModel.cameras.size()) {
            fail("camera index " + std::to_string(node.camera) + " out of range");
        }
        const tinygltf::Camera& camera = mModel.cameras[std::size_t(node.camera)];
        if (camera.type != "perspective") {
            mOut.warnings.push_back(makeWarning(WarningKind::CameraIgnored,
                                                cameraLabel(node.camera) + " of type '" +
                                                    excerptForMessage(camera.type) +
                                                    "' ignored (only perspective cameras are used)",
                                                "", cameraLabel(node.camera)));
            return;
        }
        if (mOut.camera) {
            return; // the first one wins
        }
        const std::string label = cameraLabel(node.camera);
        SceneCamera result;
        result.name = label;
        result.eye = glm::dvec3(world[3]);
        result.forward = glm::normalize(glm::dvec3(world * glm::dvec4(0.0, 0.0, -1.0, 0.0)));
        result.up = glm::normalize(glm::dvec3(world * glm::dvec4(0.0, 1.0, 0.0, 0.0)));
        // Checked here, not left to resolveCamera(): a bad lens is a problem of the file, not of the flags.
        const double yfov = camera.perspective.yfov;
        if (!std::isfinite(yfov) || yfov <= 0.0 || yfov >= glm::pi<double>()) {
            fail(label + ": perspective yfov " + formatNumber(yfov) + " radians is outside (0, pi)");
        }
        result.fovYDegrees = glm::degrees(yfov);
        // tinygltf leaves a missing aspectRatio at 0, so 0 reads as "not given"; any other invalid value is noted.
        const double aspectRatio = camera.perspective.aspectRatio;
        if (std::isfinite(aspectRatio) && aspectRatio > 0.0) {
            result.aspectRatio = aspectRatio;
        } else if (aspectRatio != 0.0) {
            mOut.warnings.push_back(makeWarning(
                WarningKind::CameraAspectIgnored,
                label + ": aspectRatio " + formatNumber(aspectRatio) + " ignored (must be finite and > 0)", "", label));
        }
        if (!std::isfinite(result.eye.x + result.eye.y + result.eye.z) ||
            !std::isfinite(result.forward.x + result.forward.y + result.forward.z) ||
            !std::isfinite(result.up.x + result.up.y + result.up.z)) {
            fail(label + " has a degenerate or non-finite node transform");
        }
        mOut.camera = result;
    }

    void addLight(const tinygltf::Node& node, const glm::dmat4& world) {
        const auto extension = node.extensions.find("KHR_lights_punctual");
        if (extension == node.extensions.end() || !extension->second.IsObject() || !extension->second.Has("light") ||
            !extension->second.Get("light").IsNumber()) {
            return;
        }
        const int lightIndex = extension->second.Get("light").GetNumberAsInt();
        if (lightIndex < 0 || std::size_t(lightIndex) >= mModel.lights.size()) {
            fail("KHR_lights_punctual light index " + std::to_string(lightIndex) + " out of range");
        }
        const tinygltf::Light& light = mModel.lights[std::size_t(lightIndex)];
        if (light.type != "directional") {
            mOut.warnings.push_back(makeWarning(WarningKind::LightIgnored,
                                                "KHR_lights_punctual " + excerptForMessage(light.type) + " light '" +
                                                    excerptForMessage(light.name) +
                                                    "' ignored (only directional lights are used)",
                                                "", "light '" + excerptForMessage(light.name) + "'"));
            return;
        }
        if (mOut.light) {
            return;
        }
        DirectionalLight result;
        // The light shines down its local -Z, so the direction from the surface toward it is the node's +Z.
        result.towardLight = glm::normalize(glm::dvec3(world * glm::dvec4(0.0, 0.0, 1.0, 0.0)));
        if (light.color.size() >= 3) {
            result.color = glm::dvec3(light.color[0], light.color[1], light.color[2]);
        }
        result.intensity = light.intensity;
        if (!std::isfinite(result.towardLight.x + result.towardLight.y + result.towardLight.z)) {
            fail("light '" + excerptForMessage(light.name) + "' has a degenerate or non-finite node transform");
        }
        mOut.light = result;
    }

    /** TEXCOORD_0 and TEXCOORD_1, and COLOR_0 (RGB gets alpha 1), as the file gives them. */
    void readSurfaceAttributes(const tinygltf::Primitive& primitive, std::optional<DracoPrimitive>& draco,
                               std::size_t vertexCount, const std::string& name, RawMesh& mesh) const {
        for (int set = 0; set < 2; ++set) {
            const std::string attribute = "TEXCOORD_" + std::to_string(set);
            if (primitive.attributes.count(attribute) == 0) continue;
            const std::vector<float> values =
                attributeFloats(primitive, draco, attribute, TINYGLTF_TYPE_VEC2, vertexCount, name);
            mesh.texcoords[set].resize(vertexCount);
            if (vertexCount > 0)
                std::memcpy(mesh.texcoords[set].data(), values.data(), vertexCount * sizeof(glm::vec2));
        }
        const auto color = primitive.attributes.find("COLOR_0");
        if (color == primitive.attributes.end()) return;
        // RGB or RGBA; anything else is refused by the read as "expected VEC4".
        const bool rgb = color->second >= 0 && std::size_t(color->second) < mModel.accessors.size() &&
                         mModel.accessors[std::size_t(color->second)].type == TINYGLTF_TYPE_VEC3;
        const int components = rgb ? 3 : 4;
        const std::vector<float> values = attributeFloats(
            primitive, draco, "COLOR_0", rgb ? TINYGLTF_TYPE_VEC3 : TINYGLTF_TYPE_VEC4, vertexCount, name);
        // glTF allows integer colours only normalized; unmarked, 255 would be a colour 255 times white. Read as the
        // exporter meant, and said.
        float integerWhite = 1.0f;
        if (color->second >= 0 && std::size_t(color->second) < mModel.accessors.size()) {
            const tinygltf::Accessor& accessor = mModel.accessors[std::size_t(color->second)];
            const int type = accessor.componentType;
            if (!accessor.normalized &&
                (type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE || type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT)) {
                const bool bytes = type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
                integerWhite = bytes ? 255.0f : 65535.0f; // divided by, as normalized values are
                mOut.warnings.push_back(makeWarning(
                    WarningKind::ValueOutOfRange,
                    "'" + excerptForMessage(name) + "' COLOR_0: unsigned " + (bytes ? "bytes" : "shorts") +
                        " not marked normalized, as glTF requires of integer colours; read as normalized (" +
                        (bytes ? "255" : "65535") + " is white)",
                    "", name));
            }
        }
        mesh.colors.resize(vertexCount);
        for (std::size_t i = 0; i < vertexCount; ++i) {
            const float* rgba = values.data() + i * std::size_t(components);
            mesh.colors[i] = glm::vec4(rgba[0] / integerWhite, rgba[1] / integerWhite, rgba[2] / integerWhite,
                                       rgb ? 1.0f : rgba[3] / integerWhite);
        }
        // The colours multiply the surface's in the shaders, with the lighting: 1e38 is a float, its products may not
        // be. Far beyond white, 1e6 draws the same. Reported once, with the first value clamped.
        std::vector<Warning> clamped;
        std::size_t clampedCount = 0;
        // Appended, not "'" + name: GCC 12 warns falsely (-Wrestrict, bug 105329) on that inlined.
        std::string what = "'";
        what.append(excerptForMessage(name)).append("' COLOR_0 value");
        for (glm::vec4& colour : mesh.colors) {
            for (int c = 0; c < 4; ++c) {
                if (colour[c] >= kNonNegativeRange.min && colour[c] <= kNonNegativeRange.max) continue;
                // Accessor values are finite: the one message is made for the first only.
                colour[c] = clampedCount++ == 0 ? shaderValue(colour[c], kNonNegativeRange, what, clamped, name)
                            : colour[c] < 0.0f  ? float(kNonNegativeRange.min)
                                                : float(kNonNegativeRange.max);
            }
        }
        if (clampedCount > 1)
            clamped.front().message += " (and " + std::to_string(clampedCount - 1) + " more values outside it)";
        mOut.warnings.insert(mOut.warnings.end(), clamped.begin(), clamped.end());
    }

    /** "node 3 'wheel'", or "node 3" for an unnamed one. */
    std::string nodeLabel(int nodeIndex) const {
        const std::string& name = mModel.nodes[std::size_t(nodeIndex)].name;
        return "node " + std::to_string(nodeIndex) + (name.empty() ? "" : " '" + excerptForMessage(name) + "'");
    }

    void addMesh(int nodeIndex, const tinygltf::Node& node, const glm::dmat4& world) {
        if (std::size_t(node.mesh) >= mModel.meshes.size()) {
            fail("mesh index " + std::to_string(node.mesh) + " out of range");
        }
        const tinygltf::Mesh& mesh = mModel.meshes[std::size_t(node.mesh)];
        const std::string baseName = !node.name.empty()   ? node.name
                                     : !mesh.name.empty() ? mesh.name
                                                          : "mesh " + std::to_string(node.mesh);
        // glTF: a skinned mesh is placed by its joints alone; its node's own transform does not apply.
        std::optional<std::vector<glm::dmat4>> skinJoints;
        if (node.skin >= 0) {
            skinJoints = jointMatrices(
                mPath, mModel, node.skin,
                [&](int joint, const glm::dmat4& inverseBind) {
                    const std::optional<PreciseTransform>& jointWorld = mPreciseWorlds[std::size_t(joint)];
                    if (!jointWorld) {
                        fail(nodeLabel(nodeIndex) + ": skin " + std::to_string(node.skin) + " joint node " +
                             std::to_string(joint) + " is not in the scene");
                    }
                    const PreciseTransform jointMatrix = *jointWorld * inverseBind;
                    notePlacement(jointMatrix,
                                  nodeLabel(joint) + " (a joint of skin " + std::to_string(node.skin) + ")");
                    return jointMatrix.relativeTo(mOut.origin);
                },
                mBudget);
        } else {
            notePlacement(*mPreciseWorlds[std::size_t(nodeIndex)], nodeLabel(nodeIndex));
        }
        const PrimitivePose pose{mPoses[std::size_t(nodeIndex)].weights, skinJoints ? &*skinJoints : nullptr,
                                 skinJoints ? node.skin : -1};
        const std::vector<std::string> path = nodePath(nodeIndex);
        for (std::size_t i = 0; i < mesh.primitives.size(); ++i) {
            const std::string name =
                mesh.primitives.size() == 1 ? baseName : baseName + " primitive " + std::to_string(i);
            chargeNodePath(path); // before the primitive's copy, as its vertices are
            const std::size_t meshesBefore = mOut.meshes.size();
            addPrimitive(mesh.primitives[i], name, nodeLabel(nodeIndex), world, pose);
            if (mOut.meshes.size() > meshesBefore) {
                mOut.meshes.back().nodePath = path;
                mOut.meshes.back().nodeInstance = std::size_t(nodeIndex); // one object per node (ObjectIds.h)
            }
        }
    }

    /** What moves a primitive's vertices besides its node's transform. */
    struct PrimitivePose {
        const std::vector<double>& morphWeights;
        const std::vector<glm::dmat4>* skinJoints = nullptr; ///< null: not skinned
        int skin = -1;                                       ///< the skin's index, when skinned
    };

    /** The node names from the root down to `nodeIndex` (Mesh::nodePath). This one copy lives only while its node
     *  is visited and is no larger than the names the parsed file holds; each mesh's copy is charged. */
    std::vector<std::string> nodePath(int nodeIndex) const {
        std::vector<std::string> path;
        for (int node = nodeIndex; node >= 0; node = mParent[std::size_t(node)]) {
            path.push_back(mModel.nodes[std::size_t(node)].name);
        }
        std::reverse(path.begin(), path.end());
        return path;
    }

    /** Every mesh holds its own copy of its path, as deep as the hierarchy: a deep chain of mesh nodes would hold
     *  depth^2 names, so each copy is charged to the budget first (a skipped primitive's too: a slight over-count). */
    void chargeNodePath(const std::vector<std::string>& path) {
        std::size_t bytes = sizeof(path);
        for (const std::string& name : path) bytes += sizeof(std::string) + name.size();
        mBudget.chargeBytes(bytes);
    }

    /** VEC3 floats (POSITION, NORMAL) as vectors, in the file's frame. */
    static std::vector<glm::vec3> toVec3(const std::vector<float>& values) {
        std::vector<glm::vec3> vectors(values.size() / 3);
        // Not with no values (an accessor of count 0): memcpy of a null pointer is undefined even for 0 bytes.
        if (!vectors.empty()) std::memcpy(vectors.data(), values.data(), vectors.size() * sizeof(glm::vec3));
        return vectors;
    }

    /** Vertex attribute `attribute` of `primitive` as floats: from the decoded Draco data when the primitive
     *  compresses it, else from its accessor, whose count is checked against POSITION before it is read. */
    std::vector<float> attributeFloats(const tinygltf::Primitive& primitive, std::optional<DracoPrimitive>& draco,
                                       const std::string& attribute, int type, std::size_t vertexCount,
                                       const std::string& name) const {
        const int accessorIndex = primitive.attributes.at(attribute);
        if (draco) {
            const auto decoded = draco->attributes.find(attribute);
            if (decoded != draco->attributes.end()) {
                accessorCount(mPath, mModel, accessorIndex, type, attribute); // its type checked, as uncompressed
                return std::move(decoded->second);
            }
        }
        requireVertexCount(accessorIndex, type, attribute, vertexCount, name);
        return readAccessorFloats(mPath, mModel, accessorIndex, type, attribute);
    }

    /** A vertex attribute has one element per vertex; checked before it is read, so a mismatched count allocates
     *  nothing. */
    void requireVertexCount(int accessorIndex, int type, const std::string& attribute, std::size_t vertexCount,
                            const std::string& name) const {
        const std::size_t count = accessorCount(mPath, mModel, accessorIndex, type, attribute);
        if (count != vertexCount) {
            fail("'" + excerptForMessage(name) + "': " + attribute + " has " + std::to_string(count) +
                 " elements but POSITION has " + std::to_string(vertexCount));
        }
    }

    std::vector<std::uint32_t> readIndices(int accessorIndex, std::size_t vertexCount) const {
        std::vector<std::uint32_t> indices =
            readAccessorIntegers(mPath, mModel, accessorIndex, TINYGLTF_TYPE_SCALAR, "index");
        requirePackedIndices(accessorIndex);
        for (std::size_t i = 0; i < indices.size(); ++i) {
            if (indices[i] >= vertexCount) {
                fail("index accessor " + std::to_string(accessorIndex) + " element " + std::to_string(i) + ": index " +
                     std::to_string(indices[i]) + " out of range (primitive has " + std::to_string(vertexCount) +
                     " vertices)");
            }
        }
        return indices;
    }

    /** glTF forbids a byteStride on a buffer view of indices: they lie packed. A stride of the index's own size reads
     *  the same and is taken (exporters write it); another would read every so many bytes, triangles no other reader
     *  draws, so it is refused. Checked after the read, which has checked the accessor and its view. */
    void requirePackedIndices(int accessorIndex) const {
        const tinygltf::Accessor& accessor = mModel.accessors[std::size_t(accessorIndex)];
        if (accessor.bufferView < 0) return; // sparse over zeros: no view
        const tinygltf::BufferView& view = mModel.bufferViews[std::size_t(accessor.bufferView)];
        const int indexBytes = tinygltf::GetComponentSizeInBytes(std::uint32_t(accessor.componentType));
        if (view.byteStride == 0 || int(view.byteStride) == indexBytes) return;
        fail("index accessor " + std::to_string(accessorIndex) + ": buffer view " +
             std::to_string(accessor.bufferView) + " has byteStride " + std::to_string(view.byteStride) +
             ", but glTF forbids a stride on indices (they lie packed, " + std::to_string(indexBytes) + " bytes each)");
    }

    /** Triangles of a TRIANGLES, TRIANGLE_STRIP or TRIANGLE_FAN index sequence, all wound like the first. */
    std::vector<glm::uvec3> triangulate(int mode, const std::vector<std::uint32_t>& v, const std::string& name) {
        std::vector<glm::uvec3> triangles;
        const std::size_t n = v.size();
        if (mode == TINYGLTF_MODE_TRIANGLES) {
            if (n % 3 != 0) {
                mOut.warnings.push_back(makeWarning(WarningKind::IndicesIncomplete,
                                                    "'" + excerptForMessage(name) + "': " + std::to_string(n % 3) +
                                                        " trailing indices of an incomplete triangle ignored",
                                                    "", name));
            }
            triangles.reserve(n / 3);
            for (std::size_t i = 0; i + 2 < n; i += 3) {
                triangles.emplace_back(v[i], v[i + 1], v[i + 2]);
            }
        } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
            // Every other strip triangle swaps its last two corners to keep the strip's winding.
            for (std::size_t i = 0; i + 2 < n; ++i) {
                if (i % 2 == 0) {
                    triangles.emplace_back(v[i], v[i + 1], v[i + 2]);
                } else {
                    triangles.emplace_back(v[i], v[i + 2], v[i + 1]);
                }
            }
        } else { // TRIANGLE_FAN
            for (std::size_t i = 1; i + 1 < n; ++i) {
                triangles.emplace_back(v[0], v[i], v[i + 1]);
            }
        }
        return triangles;
    }

    void addPrimitive(const tinygltf::Primitive& primitive, const std::string& name, const std::string& node,
                      const glm::dmat4& world, const PrimitivePose& pose) {
        const int mode = primitive.mode;
        if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
            mode != TINYGLTF_MODE_TRIANGLE_FAN) {
            ++mSkippedPrimitives;
            mOut.warnings.push_back(makeWarning(WarningKind::PrimitiveSkipped,
                                                "'" + excerptForMessage(name) + "': non-triangle primitive (mode " +
                                                    std::to_string(mode) + ", " + modeName(mode) + ") skipped",
                                                "", name));
            return;
        }
        const auto positionAttribute = primitive.attributes.find("POSITION");
        if (positionAttribute == primitive.attributes.end()) {
            mOut.warnings.push_back(makeWarning(WarningKind::PrimitiveSkipped,
                                                "'" + excerptForMessage(name) + "': primitive without POSITION skipped",
                                                "", name));
            return;
        }

        // Charged before anything is copied: one mesh instanced by many nodes is copied once per node. Draco data is
        // charged by its decoded counts (decodeDracoPrimitive()); its accessors hold no data of their own.
        std::optional<DracoPrimitive> draco;
        std::size_t vertexCount = 0;
        if (hasDracoCompression(primitive)) {
            draco = decodeDracoPrimitive(mPath, mModel, primitive, "'" + excerptForMessage(name) + "'", mBudget);
            vertexCount = draco->vertexCount;
        } else {
            vertexCount = accessorCount(mPath, mModel, positionAttribute->second, TINYGLTF_TYPE_VEC3, "POSITION");
            const std::size_t cornerCount =
                primitive.indices >= 0 ? accessorCount(mPath, mModel, primitive.indices, TINYGLTF_TYPE_SCALAR, "index")
                                       : vertexCount;
            mBudget.charge(vertexCount, mode == TINYGLTF_MODE_TRIANGLES ? cornerCount / 3 : cornerCount);
        }

        RawMesh mesh;
        mesh.name = name;
        mesh.positions = toVec3(attributeFloats(primitive, draco, "POSITION", TINYGLTF_TYPE_VEC3, vertexCount, name));
        if (primitive.attributes.count("NORMAL") > 0) {
            mesh.normals = toVec3(attributeFloats(primitive, draco, "NORMAL", TINYGLTF_TYPE_VEC3, vertexCount, name));
        }

        // A Draco primitive's morph targets are plain accessors, one element per decoded point in Draco's order: the
        // extension compresses no target, and its implementation note has generators write the uncompressed data
        // from the decoded mesh (Khronos' MorphPrimitivesTest glTF-Draco sample carries its targets so; Blender's
        // encoder keeps the point order for primitives with targets).
        // applyMorphTargets() refuses a target whose count is not the decoded points'.
        applyMorphTargets(mPath, mModel, primitive, pose.morphWeights, mesh.positions, mesh.normals, name,
                          mOut.warnings);
        std::optional<SkinBlend> skin;
        if (pose.skinJoints) {
            // SkinBlend holds every JOINTS_n/WEIGHTS_n set for the primitive's vertices while it is baked.
            const auto sets = std::ranges::count_if(
                primitive.attributes, [](const auto& entry) { return entry.first.starts_with("JOINTS_"); });
            mBudget.checkBytes(vertexCount * std::size_t(sets) * kSkinBytesPerVertexPerSet,
                               quotedExcerpt(name) + "'s joints and weights");
            skin.emplace(mPath, mModel, primitive, vertexCount, *pose.skinJoints, world, name,
                         draco ? &draco->attributes : nullptr);
            warnWeightSums(*skin, name);
        }
        readSurfaceAttributes(primitive, draco, vertexCount, name, mesh);

        std::vector<std::uint32_t> indices;
        if (draco) {
            indices = std::move(draco->indices); // a triangle list whatever the mode says: Draco stores faces
        } else if (primitive.indices >= 0) {
            indices = readIndices(primitive.indices, vertexCount);
        } else {
            indices.resize(vertexCount);
            for (std::size_t i = 0; i < vertexCount; ++i) {
                indices[i] = std::uint32_t(i);
            }
        }
        mesh.triangles = triangulate(draco ? TINYGLTF_MODE_TRIANGLES : mode, indices, name);

        // Bake the node transform (a skinned vertex's: its blend of joint matrices); normals use the inverse
        // transpose so non-uniform scale keeps them perpendicular.
        const glm::dmat3 linear(world);
        const glm::dmat3 normalMatrix = glm::transpose(glm::inverse(linear));
        std::vector<bool> mirrored; // per vertex of a skinned mesh: its skin matrix turns the winding over
        // The transforms are relative to the scene's origin (the first mesh's node), so these positions are small
        // wherever the model lies: rounding world coordinates of a model 1e7 units out to float would leave it a
        // blocky polyhedron.
        for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
            const glm::dmat4 vertexMatrix = skin ? skin->vertexMatrix(v) : world;
            const glm::dvec3 relative(vertexMatrix * glm::dvec4(glm::dvec3(mesh.positions[v]), 1.0));
            if (!std::isfinite(relative.x) || !std::isfinite(relative.y) || !std::isfinite(relative.z)) {
                fail(node + (skin ? ": the skin's joint transforms produce non-finite positions"
                                  : ": the node transform produces non-finite positions"));
            }
            if (!(std::max({std::abs(relative.x), std::abs(relative.y), std::abs(relative.z)}) <= kMaxModelExtent)) {
                fail(node + ": after the node transforms a position lies " + formatExtent(glm::length(relative)) +
                     " units from the first mesh's node, more than the " + formatExtent(kMaxModelExtent) +
                     " the renderer can hold (a node scale or translation too large?)");
            }
            mesh.positions[v] = glm::vec3(relative);
            if (skin) {
                const glm::dmat3 vertexLinear(vertexMatrix);
                mirrored.push_back(glm::determinant(vertexLinear) < 0.0);
                if (!mesh.normals.empty()) {
                    mesh.normals[v] = transformNormal(glm::transpose(glm::inverse(vertexLinear)), mesh.normals[v]);
                }
            }
        }
        if (!skin) {
            for (glm::vec3& normal : mesh.normals) normal = transformNormal(normalMatrix, normal);
        } else {
            addToJointBoxes(*skin, pose.skin, mesh.positions);
        }
        // A mirroring transform turns counter-clockwise into clockwise; swap two corners to keep fronts outward.
        for (std::size_t index = 0; index < mesh.triangles.size(); ++index) {
            glm::uvec3& triangle = mesh.triangles[index];
            if (skin ? bool(mirrored[triangle.x]) : glm::determinant(linear) < 0.0) {
                std::swap(triangle.y, triangle.z);
                if (mesh.cornersSwapped.empty()) mesh.cornersSwapped.resize(mesh.triangles.size(), 0);
                mesh.cornersSwapped[index] = 1;
            }
        }

        if (primitive.material >= 0) { // in range: checkMaterialIndices()
            mesh.material = mMaterials.material(primitive.material);
            if (mExpressions) mExpressions->applyToMaterial(primitive.material, mesh.material, mOut.warnings);
        }
        mOut.meshes.push_back(std::move(mesh));
    }

    const std::string& mPath;
    const tinygltf::Model& mModel;
    RawScene& mOut;
    MeshBudget& mBudget;
    const LoadOptions& mOptions;
    std::vector<NodePose> mPoses;      ///< per node: its local transform and morph weights, animated or not (posed())
    std::optional<Humanoid> mHumanoid; ///< a VRM model's humanoid bones (posed())
    /** Per node: the posed vertices it weights as a skin joint, then (collectJoints()) its descendants' too. */
    std::vector<BoundingBox> mJointBoxes = std::vector<BoundingBox>(mModel.nodes.size());
    std::optional<VrmExpressions> mExpressions; ///< the VRM expressions, when --expression or --look-at asks
    std::vector<bool> mReached;                 ///< nodes already reached by the walk; reaching one again is an error
    /** Per node reached by the walk: its world transform, composed precisely, and relative to mOut.origin. */
    std::vector<std::optional<PreciseTransform>> mPreciseWorlds =
        std::vector<std::optional<PreciseTransform>>(mModel.nodes.size());
    std::vector<std::optional<glm::dmat4>> mWorlds;
    std::vector<int> mParent = std::vector<int>(mModel.nodes.size(), -1); ///< each node's parent, -1 for a root
    GltfMaterials mMaterials; ///< each material read once, when a primitive first uses it
    std::size_t mSkippedPrimitives = 0;
    double mPlacementError = 0.0;     ///< the largest error bound notePlacement() saw
    double mPlacementMagnitude = 0.0; ///< the largest term of that placement
    std::string mPlacementLabel;      ///< the node it placed
};

} // namespace

RawScene readGltf(const std::string& path, std::string_view content, MeshBudget& budget, const LoadOptions& options) {
    // A byte-order mark before the JSON needs nothing here: tinygltf's JSON parser (nlohmann) skips it.
    const bool binary = content.size() >= 4 && content.substr(0, 4) == "glTF";
    rejectDeepJson(path, content, binary);
    // tinygltf takes 32-bit lengths; the GLB container itself cannot describe more.
    if (content.size() > std::numeric_limits<std::uint32_t>::max())
        throwLoadError(path, "glTF files above 4 GiB are not supported");
    // tinygltf keeps its own copy of every buffer it decodes (the GLB's BIN chunk, data URIs): at most the file again.
    budget.chargeFile(content.size());
    const TinygltfInput prepared = forTinygltf(path, content, binary);
    if (prepared.rewritten) {
        budget.chargeFile(prepared.rewritten->size());
        content = *prepared.rewritten;
    }
    const std::string baseDirectory = std::filesystem::path(path).parent_path().string();
    const ExternalUris uris = externalUris(jsonOf(content, binary));
    ExternalFiles files{budget, {}, {}, {}};
    for (const std::string& uri : uris.bufferUris) {
        if (const std::optional<std::string> other = files.name(baseDirectory, uri, false)) {
            throwLoadError(path, "buffers '" + excerptForMessage(*other) + "' and '" + excerptForMessage(uri) +
                                     "' name different files that tinygltf reads by one name ('" +
                                     excerptForMessage(tinygltfPathBesideModel({}, uri)) +
                                     "'), so it cannot read both; rename one of the files and its URI");
        }
    }
    for (const std::string& uri : uris.bufferUris) {
        // Said here, in the file's words: tinygltf's own "File not found" names its decoding of the URI
        // ("model lod0.bin" for "model+lod0.bin"), and no folder.
        if (uri.empty() || uri.rfind("data:", 0) == 0) continue; // a GLB's BIN chunk may be written "uri": ""
        const std::string file = files.fileAskedAs(tinygltfPathBesideModel(baseDirectory, uri));
        std::error_code error;
        if (!std::filesystem::exists(file, error)) {
            if (const std::optional<std::string> why = whyFileIsMissing(file))
                throwLoadError(path,
                               "buffer '" + excerptForMessage(uri) + "': '" + excerptForMessage(file) + "' " + *why);
            throwLoadError(path, "buffer '" + excerptForMessage(uri) + "': file not found: '" +
                                     excerptForMessage(file) + "' (a glTF's buffers are files beside it)");
        }
    }
    for (const std::string& uri : uris.imageUris) files.name(baseDirectory, uri, true);
    for (const std::string& uri : uris.imageDataUris) files.name(baseDirectory, uri, true);

    tinygltf::TinyGLTF loader;
    DataUriImages dataUriImages{budget, {}};
    loader.SetImageLoader(&keepEncodedImage, &dataUriImages);
    // Keeps each extras object as JSON text, so GltfMaterials sees the shade-map extra's types as written.
    loader.SetStoreOriginalJSONForExtrasAndExtensions(true);
    loader.SetFsCallbacks(
        {&externalFileExists, &tinygltf::ExpandFilePath, &readExternalFile, &tinygltf::WriteWholeFile, &files});
    tinygltf::Model model;
    std::string error;
    std::string warning;
    const auto length = static_cast<unsigned int>(content.size());
    bool loaded = false;
    try {
        loaded = binary ? loader.LoadBinaryFromMemory(&model, &error, &warning,
                                                      reinterpret_cast<const unsigned char*>(content.data()), length,
                                                      baseDirectory)
                        : loader.LoadASCIIFromString(&model, &error, &warning, content.data(), length, baseDirectory);
    } catch (const std::exception& thrown) {
        // tinygltf 2.7 indexes with .at() on what the file declares: fuzz_gltf found a GLB whose empty buffer made
        // it throw std::out_of_range ("vector::_M_range_check"), which ended the CLI as an internal error.
        throwLoadError(path, std::string(binary ? "invalid GLB" : "invalid glTF") + ": tinygltf failed (" +
                                 shortenWords(thrown.what()) + ")");
    }
    if (!loaded) {
        // tinygltf says the same of a data: URI that is not base64 and of one whose byteLength is not its size, and
        // takes one of another form for a file name ("File not found", quoting its decoded bytes).
        if (error.find("Failed to decode 'uri'") != std::string::npos ||
            error.find("File not found : data:") != std::string::npos)
            if (const std::optional<std::string> why = dataUriBufferProblem(jsonOf(content, binary)))
                throwLoadError(path, std::string(binary ? "invalid GLB" : "invalid glTF") + ": " + *why);
        throwLoadError(path, std::string(binary ? "invalid GLB" : "invalid glTF") + ": " +
                                 (error.empty() ? "tinygltf gave no reason" : joinLines(error)));
    }

    RawScene scene;
    scene.format = binary ? "glb" : "gltf";
    scene.warnings = prepared.warnings;
    // tinygltf also reports recoverable problems (e.g. chunk padding) through `error` while still succeeding.
    // A channel whose target names no node (KHR_animation_pointer's) is said by judgeValueShapes(); tinygltf says
    // only that 'node' is missing, twice.
    constexpr std::string_view kChannelWithoutNode = "`node` field is missing in animation.channels.target";
    const bool channelWithoutNode =
        warning.find(kChannelWithoutNode) != std::string::npos || error.find(kChannelWithoutNode) != std::string::npos;
    for (const std::string* messages : {&warning, &error}) {
        for (const std::string& line : splitLines(*messages)) {
            // tinygltf takes a skin's inverseBindMatrices for required; glTF makes it optional (identity matrices).
            if (line.find("'inverseBindMatrices' property is missing") != std::string::npos) continue;
            if (channelWithoutNode &&
                (line.find(kChannelWithoutNode) != std::string::npos || line == "'node' property is missing."))
                continue;
            scene.warnings.push_back(makeWarning(WarningKind::GltfParserMessage, "tinygltf: " + shortenWords(line)));
        }
    }
    scene.inputFiles = std::move(files.opened);
    // Images too, though not read here: the app must not overwrite one with an output.
    for (const std::string& uri : uris.imageUris) {
        const std::string imagePath = pathBesideModel(baseDirectory, uri);
        if (std::ranges::find(scene.inputFiles, imagePath) == scene.inputFiles.end()) {
            scene.inputFiles.push_back(imagePath);
        }
    }
    decodeMeshoptBufferViews(path, model, prepared.meshoptPlaceholders, budget); // before anything reads a view
    scene.images = sceneImages(path, model, baseDirectory, dataUriImages, budget);
    GltfWalker(path, model, scene, budget, options).walk();
    if (scene.meshes.empty()) {
        throwLoadError(path, noTrianglesInTheFile(scene.warnings));
    }
    return scene;
}

// readGltf() reads all three: the content decides JSON or GLB, whatever the extension says.
FormatReader gltfFormat() {
    return {"glTF",
            {".gltf"},
            readGltf,
            [](const std::string& path) { return gltfReferencedFiles(path, wholeFileBestEffort(path)); },
            true};
}

FormatReader glbFormat() { return {"GLB", {".glb"}, readGltf, glbReferencedFiles, true}; }

FormatReader vrmFormat() { return {"VRM", {".vrm"}, readGltf, glbReferencedFiles, true}; } // a VRM file is a GLB

} // namespace inkgraph::detail

namespace inkgraph {

const std::vector<std::string>& supportedGltfExtensions() { return detail::kSupportedExtensions; }

} // namespace inkgraph
