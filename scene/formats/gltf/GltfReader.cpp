/** @file glTF 2.0 (.gltf JSON and .glb) through the packaged tinygltf. tinygltf parses and resolves buffers; this file
 *  walks the node hierarchy, bounds-checks every accessor it reads (tinygltf does not), bakes node transforms into
 *  world space and picks up the first perspective camera, the first directional KHR_lights_punctual light and each
 *  material's inkgraph extras (a per-mesh shade map). */

#include "scene/formats/FormatTable.h"
#include "scene/formats/gltf/GltfAccessors.h"
#include "scene/formats/gltf/GltfDraco.h"
#include "scene/formats/gltf/GltfPose.h"
#include "scene/formats/ShaderValues.h"
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
#include <fstream>
#include <initializer_list>
#include <iomanip>
#include <iterator>
#include <limits>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <string_view>

namespace inkgraph::detail {

namespace {

/** A material's shade map path: relative to the glTF file, like its buffer URIs, so a scene folder can be moved or
 *  rendered from anywhere; lexically normalised. */
std::string shadeMapBesideModel(const std::string& modelPath, const std::string& named) {
    const std::filesystem::path path(named);
    const std::filesystem::path resolved =
        path.is_absolute() ? path : std::filesystem::path(modelPath).parent_path() / path;
    return resolved.lexically_normal().string();
}

/** The one list of what this reader implements (supportedGltfExtensions()): KHR_lights_punctual's directional light,
 *  KHR_mesh_quantization's integer and normalized attributes (GltfAccessors.cpp reads any component type),
 *  KHR_draco_mesh_compression (GltfDraco.cpp), KHR_texture_transform, KHR_materials_unlit,
 *  KHR_materials_emissive_strength, VRM 0.x ("VRM": its front and MToon materialProperties) and 1.0 ("VRMC_vrm": its
 *  front; "VRMC_materials_mtoon"), scene/formats/gltf/VrmMaterials.h. */
const std::vector<std::string> kSupportedExtensions = {"KHR_lights_punctual",
                                                       "KHR_mesh_quantization",
                                                       "KHR_draco_mesh_compression",
                                                       "KHR_texture_transform",
                                                       "KHR_materials_unlit",
                                                       "KHR_materials_emissive_strength",
                                                       "VRM",
                                                       "VRMC_materials_mtoon",
                                                       "VRMC_vrm"};

/** Unsupported required extensions named one by one in the refusal; the rest are counted. */
constexpr std::size_t kMaxNamedExtensions = 10;

static_assert(std::endian::native == std::endian::little, "glTF buffers are little-endian; add byte swapping");

/** The encoded bytes of the images given as data: URIs, by glTF image index, kept by keepEncodedImage(). */
struct DataUriImages {
    MeshBudget& budget;
    std::vector<std::shared_ptr<const std::vector<unsigned char>>> bytes;
};

/** tinygltf's image decoder, replaced: images stay encoded until a pass samples them (scene/Material.h). tinygltf
 *  calls it for data: URIs (bytes it decoded itself, the size exact), for external files (our one-byte placeholder:
 *  readExternalFile()) and for buffer-view images, whose window it does not bounds-check: those are copied later by
 *  sceneImages() after checking, so only data: URIs are kept here. */
bool keepEncodedImage(tinygltf::Image* image, const int imageIndex, std::string* error, std::string*, int, int,
                      const unsigned char* bytes, int size, void* user) {
    auto& images = *static_cast<DataUriImages*>(user);
    if (image->bufferView != -1 || !image->uri.empty() || imageIndex < 0 || size < 0) {
        return true;
    }
    try {
        images.budget.chargeFile(std::size_t(size));
    } catch (const SceneError&) {
        if (error) *error += "image " + std::to_string(imageIndex) + " is above the memory limit\n";
        return false;
    }
    if (images.bytes.size() <= std::size_t(imageIndex)) images.bytes.resize(std::size_t(imageIndex) + 1);
    images.bytes[std::size_t(imageIndex)] = std::make_shared<const std::vector<unsigned char>>(bytes, bytes + size);
    return true;
}

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
          mReached(model.nodes.size(), false), mWorlds(model.nodes.size()), mMaterialShadeMaps(model.materials.size()),
          mMaterials(model.materials.size()) {}

    void walk() {
        checkRequiredExtensions();
        checkMaterialIndices();
        readVrmFront();
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
        if (mOut.meshes.empty() && mSkippedPrimitives > 0) {
            throwLoadError(mPath, "no triangles: all " + std::to_string(mSkippedPrimitives) +
                                      " primitives are non-triangle (points or lines)");
        }
        checkPlacementPrecision();
    }

private:
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
        mPoses = restPose(mModel);
        if (!mOptions.animation.empty()) {
            applyAnimation(mPath, mModel, findAnimation(mPath, mModel, mOptions.animation), mOptions.time, mPoses,
                           mBudget, mOut.warnings);
        }
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
            mOut.warnings.push_back(cameraLabel(node.camera) + " of type '" + excerptForMessage(camera.type) +
                                    "' ignored (only perspective cameras are used)");
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
            mOut.warnings.push_back(label + ": aspectRatio " + formatNumber(aspectRatio) +
                                    " ignored (must be finite and > 0)");
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
            mOut.warnings.push_back("KHR_lights_punctual " + excerptForMessage(light.type) + " light '" +
                                    excerptForMessage(light.name) + "' ignored (only directional lights are used)");
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

    /** "material 2 'Metal'", or "material 2" for an unnamed one. */
    std::string materialLabel(int materialIndex) const {
        const std::string& name = mModel.materials[std::size_t(materialIndex)].name;
        return "material " + std::to_string(materialIndex) + (name.empty() ? "" : " '" + excerptForMessage(name) + "'");
    }

    /** The shade map material `materialIndex` names in `"extras": {"inkgraph": {"shademap": PATH}}`, resolved against
     *  the file's folder; empty when it names none. Read once per material (its warnings too), when a primitive first
     *  uses it. The original JSON is parsed rather than tinygltf's Value, which drops nulls and empty objects and
     *  arrays, so `"shademap": null` would pass for "no map" instead of being reported. */
    const std::string& materialShadeMap(int materialIndex) {
        std::optional<std::string>& cached = mMaterialShadeMaps[std::size_t(materialIndex)];
        if (cached) {
            return *cached;
        }
        cached.emplace();
        const std::string& extrasJson = mModel.materials[std::size_t(materialIndex)].extras_json_string;
        if (extrasJson.empty()) {
            return *cached;
        }
        const nlohmann::json extras = nlohmann::json::parse(extrasJson, nullptr, false);
        // Other tools may keep anything in extras; only the "inkgraph" member is ours.
        if (!extras.is_object() || !extras.contains("inkgraph")) {
            return *cached;
        }
        const std::string label = materialLabel(materialIndex);
        const nlohmann::json& ours = extras["inkgraph"];
        if (!ours.is_object()) {
            fail(label + ": extras.inkgraph must be an object, got " + std::string(ours.type_name()));
        }
        for (const auto& [key, value] : ours.items()) {
            if (key == "shademap") {
                continue;
            }
            // A newer file or a typo ("shadeMap"): the render still works, so say so instead of refusing it.
            mOut.warnings.push_back(label + ": extras.inkgraph key '" + excerptForMessage(key) +
                                    "' ignored (known: 'shademap')");
        }
        const auto shadeMap = ours.find("shademap");
        if (shadeMap == ours.end()) {
            return *cached;
        }
        if (!shadeMap->is_string() || shadeMap->get_ref<const std::string&>().empty()) {
            fail(label + ": extras.inkgraph.shademap must be a non-empty string (a PNG path), got " +
                 (shadeMap->is_string() ? std::string("an empty string") : std::string(shadeMap->type_name())));
        }
        *cached = shadeMapBesideModel(mPath, shadeMap->get_ref<const std::string&>());
        return *cached;
    }

    /** "texture 2 'skin'", or "texture 2" for an unnamed one. */
    std::string textureLabel(int textureIndex) const {
        const std::string& name = mModel.textures[std::size_t(textureIndex)].name;
        return "texture " + std::to_string(textureIndex) + (name.empty() ? "" : " '" + excerptForMessage(name) + "'");
    }

    /** A sampler enum as the file writes it, or `fallback` (with a warning) for a value glTF does not define;
     *  tinygltf leaves an absent one at -1. */
    template <typename Enum>
    Enum samplerValue(int value, std::initializer_list<Enum> allowed, Enum fallback, const std::string& what) {
        if (value == -1) return fallback;
        for (Enum candidate : allowed)
            if (std::uint32_t(candidate) == std::uint32_t(value)) return candidate;
        mOut.warnings.push_back(what + " " + std::to_string(value) + " is not a glTF value; the default is used");
        return fallback;
    }

    TextureSampler readSampler(int samplerIndex) {
        TextureSampler result;
        if (samplerIndex == -1) return result; // glTF: repeat, filters up to the renderer
        if (samplerIndex < 0 || std::size_t(samplerIndex) >= mModel.samplers.size()) {
            fail("sampler index " + std::to_string(samplerIndex) + " out of range (file has " +
                 std::to_string(mModel.samplers.size()) + " samplers)");
        }
        const tinygltf::Sampler& sampler = mModel.samplers[std::size_t(samplerIndex)];
        const std::string label = "sampler " + std::to_string(samplerIndex);
        using F = TextureFilter;
        using W = TextureWrap;
        result.magFilter =
            samplerValue(sampler.magFilter, {F::Nearest, F::Linear}, result.magFilter, label + " magFilter");
        result.minFilter = samplerValue(sampler.minFilter,
                                        {F::Nearest, F::Linear, F::NearestMipmapNearest, F::LinearMipmapNearest,
                                         F::NearestMipmapLinear, F::LinearMipmapLinear},
                                        result.minFilter, label + " minFilter");
        const std::initializer_list<W> wraps = {W::Repeat, W::ClampToEdge, W::MirroredRepeat};
        result.wrapS = samplerValue(sampler.wrapS, wraps, result.wrapS, label + " wrapS");
        result.wrapT = samplerValue(sampler.wrapT, wraps, result.wrapT, label + " wrapT");
        return result;
    }

    /** A number of an extension object, or `fallback` when absent; a present non-number or non-finite one fails. */
    double extensionNumber(const tinygltf::Value& object, const char* key, double fallback,
                           const std::string& label) const {
        if (!object.Has(key)) return fallback;
        const tinygltf::Value& value = object.Get(key);
        const double number = value.IsNumber() ? value.GetNumberAsDouble() : std::nan("");
        if (!std::isfinite(number)) fail(label + ": '" + key + "' must be a finite number");
        return number;
    }

    /** An [x, y] array of an extension object, or `fallback` when absent. */
    glm::dvec2 extensionPair(const tinygltf::Value& object, const char* key, glm::dvec2 fallback,
                             const std::string& label) const {
        if (!object.Has(key)) return fallback;
        const tinygltf::Value& value = object.Get(key);
        if (!value.IsArray() || value.ArrayLen() != 2) fail(label + ": '" + key + "' must be an array of 2 numbers");
        glm::dvec2 pair;
        for (int i = 0; i < 2; ++i) {
            const tinygltf::Value& item = value.Get(i);
            pair[i] = item.IsNumber() ? item.GetNumberAsDouble() : std::nan("");
            if (!std::isfinite(pair[i])) fail(label + ": '" + key + "' must be an array of 2 finite numbers");
        }
        return pair;
    }

    /** "[x, y]", for messages. */
    static std::string formatPair(const glm::dvec2& pair) {
        return "[" + formatNumber(pair.x) + ", " + formatNumber(pair.y) + "]";
    }

    /** A material's textureInfo as a TextureRef: the image its texture shows, the coordinate set and sampler, and the
     *  KHR_texture_transform matrix. A texture without a core image (only an extension's, e.g. KHR_texture_basisu or
     *  EXT_texture_webp, which the renderer cannot decode) or on a third coordinate set leaves the material
     *  untextured, with a warning. */
    TextureRef readTextureRef(const tinygltf::TextureInfo& info, const std::string& label) {
        TextureRef ref;
        if (info.index == -1) return ref;
        if (info.index < 0 || std::size_t(info.index) >= mModel.textures.size()) {
            fail(label + ": texture index " + std::to_string(info.index) + " out of range (file has " +
                 std::to_string(mModel.textures.size()) + " textures)");
        }
        const tinygltf::Texture& texture = mModel.textures[std::size_t(info.index)];
        const std::string textureName = textureLabel(info.index);
        if (texture.source == -1) {
            std::string extensions;
            std::size_t named = 0;
            for (const auto& [name, value] : texture.extensions)
                if (++named <= kMaxNamedExtensions)
                    extensions += (extensions.empty() ? " (it has only '" : "', '") + excerptForMessage(name);
            mOut.warnings.push_back(label + ": " + textureName + " has no PNG or JPEG source" +
                                    (extensions.empty() ? "" : extensions + "')") + "; drawn untextured");
            return ref;
        }
        if (texture.source < 0 || std::size_t(texture.source) >= mModel.images.size()) {
            fail(label + ": " + textureName + ": image index " + std::to_string(texture.source) +
                 " out of range (file has " + std::to_string(mModel.images.size()) + " images)");
        }
        double texCoord = info.texCoord;
        std::optional<glm::dmat3> transform;
        std::string transformText;
        const auto extension = info.extensions.find("KHR_texture_transform");
        if (extension != info.extensions.end() && extension->second.IsObject()) {
            const tinygltf::Value& object = extension->second;
            const std::string where = label + " KHR_texture_transform";
            const glm::dvec2 offset = extensionPair(object, "offset", glm::dvec2(0.0), where);
            const double rotation = extensionNumber(object, "rotation", 0.0, where);
            const glm::dvec2 scale = extensionPair(object, "scale", glm::dvec2(1.0), where);
            texCoord = extensionNumber(object, "texCoord", texCoord, where);
            // The extension's matrices, column by column as its GLSL writes them: uv' = T * R * S * (u, v, 1).
            const glm::dmat3 translation(1.0, 0.0, 0.0, 0.0, 1.0, 0.0, offset.x, offset.y, 1.0);
            const double c = std::cos(rotation);
            const double s = std::sin(rotation);
            const glm::dmat3 rotationMatrix(c, s, 0.0, -s, c, 0.0, 0.0, 0.0, 1.0);
            const glm::dmat3 scaleMatrix(scale.x, 0.0, 0.0, 0.0, scale.y, 0.0, 0.0, 0.0, 1.0);
            transform = translation * rotationMatrix * scaleMatrix;
            transformText = where + " (offset " + formatPair(offset) + ", rotation " + formatNumber(rotation) +
                            ", scale " + formatPair(scale) + ")";
        }
        if (texCoord != 0.0 && texCoord != 1.0) {
            mOut.warnings.push_back(label + ": texture coordinate set " + formatNumber(texCoord) +
                                    " is not read (only TEXCOORD_0 and TEXCOORD_1); drawn untextured");
            return ref;
        }
        ref.image = texture.source;
        ref.texCoord = int(texCoord);
        ref.sampler = readSampler(texture.sampler);
        if (transform) {
            // The transform says where the image lies: one the shaders' float cannot follow is refused, not guessed.
            std::string problem;
            const std::optional<glm::mat3> forShaders = shaderTextureTransform(*transform, ref.sampler, problem);
            if (!forShaders) fail(transformText + ": " + problem);
            ref.transform = *forShaders;
        }
        return ref;
    }

    /** A VRM character's MToon (scene/formats/gltf/VrmMaterials.h), which may also adjust `material`. Its textures go
     * through readTextureRef(), so their samplers and KHR_texture_transform are read as the glTF material's are. Called
     * once per material, by material(), so its warnings are reported once. */
    std::optional<MToonMaterial> vrmMaterial(int materialIndex, Material& material) {
        const std::string label = materialLabel(materialIndex) + " MToon texture";
        const VrmTextureResolver resolveTexture = [&](int texture, int texCoord,
                                                      const tinygltf::Value* textureInfoExtensions) {
            tinygltf::TextureInfo info;
            info.index = texture;
            info.texCoord = texCoord;
            if (textureInfoExtensions && textureInfoExtensions->IsObject()) {
                for (const std::string& key : textureInfoExtensions->Keys())
                    info.extensions[key] = textureInfoExtensions->Get(key);
            }
            return readTextureRef(info, label);
        };
        std::vector<std::string> warnings;
        std::optional<MToonMaterial> mtoon = readVrmMaterial(mModel, materialIndex, material, resolveTexture, warnings);
        mOut.warnings.insert(mOut.warnings.end(), warnings.begin(), warnings.end());
        return mtoon;
    }

    /** Material `materialIndex` as the renderer sees it, read once (its warnings too) when a primitive first uses
     *  it: the glTF material, then a VRM character's MToon (vrmMaterial()). */
    const Material& material(int materialIndex) {
        std::optional<Material>& cached = mMaterials[std::size_t(materialIndex)];
        if (cached) return *cached;
        const tinygltf::Material& source = mModel.materials[std::size_t(materialIndex)];
        const std::string label = materialLabel(materialIndex);
        Material result;
        result.name = source.name;
        // Factors beyond glTF's ranges are clamped with a warning, as viewers draw them (ShaderValues.h).
        const std::vector<double>& factor = source.pbrMetallicRoughness.baseColorFactor;
        for (std::size_t i = 0; i < 4 && factor.size() == 4; ++i) {
            result.baseColorFactor[int(i)] = shaderValue(
                factor[i], kUnitRange, label + " baseColorFactor[" + std::to_string(i) + "]", mOut.warnings);
        }
        result.baseColorTexture =
            readTextureRef(source.pbrMetallicRoughness.baseColorTexture, label + " baseColorTexture");
        for (std::size_t i = 0; i < 3 && source.emissiveFactor.size() == 3; ++i) {
            result.emissiveFactor[int(i)] =
                shaderValue(source.emissiveFactor[i], kUnitRange, label + " emissiveFactor[" + std::to_string(i) + "]",
                            mOut.warnings);
        }
        const auto strength = source.extensions.find("KHR_materials_emissive_strength");
        if (strength != source.extensions.end() && strength->second.IsObject()) {
            const std::string where = label + " KHR_materials_emissive_strength";
            const double multiplier = extensionNumber(strength->second, "emissiveStrength", 1.0, where);
            if (multiplier < 0.0) fail(label + ": emissiveStrength " + formatNumber(multiplier) + " is negative");
            result.emissiveFactor *=
                shaderValue(multiplier, kNonNegativeRange, where + " emissiveStrength", mOut.warnings);
        }
        result.emissiveTexture = readTextureRef(source.emissiveTexture, label + " emissiveTexture");
        result.unlit = source.extensions.count("KHR_materials_unlit") > 0;
        if (source.alphaMode == "MASK") {
            result.alphaMode = AlphaMode::Mask;
        } else if (source.alphaMode == "BLEND") {
            result.alphaMode = AlphaMode::Blend;
        } else if (source.alphaMode != "OPAQUE") {
            mOut.warnings.push_back(label + ": alphaMode '" + excerptForMessage(source.alphaMode) +
                                    "' is not OPAQUE, MASK or BLEND; drawn opaque");
        }
        if (std::isfinite(source.alphaCutoff) && source.alphaCutoff >= 0.0) {
            // Above 1 every fragment would be cut out: blank paper.
            result.alphaCutoff = shaderValue(source.alphaCutoff, kUnitRange, label + " alphaCutoff", mOut.warnings);
        } else {
            mOut.warnings.push_back(label + ": alphaCutoff " + formatNumber(source.alphaCutoff) +
                                    " is not a number >= 0; 0.5 is used");
        }
        result.doubleSided = source.doubleSided;
        result.shadeMapPath = materialShadeMap(materialIndex);
        result.mtoon = vrmMaterial(materialIndex, result);
        cached = std::move(result);
        return *cached;
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
        mesh.colors.resize(vertexCount);
        for (std::size_t i = 0; i < vertexCount; ++i) {
            const float* rgba = values.data() + i * std::size_t(components);
            mesh.colors[i] = glm::vec4(rgba[0], rgba[1], rgba[2], rgb ? 1.0f : rgba[3]);
        }
        // The colours multiply the surface's in the shaders, with the lighting: 1e38 is a float, its products may not
        // be. Far beyond white, 1e6 draws the same. Reported once, with the first value clamped.
        std::vector<std::string> clamped;
        std::size_t clampedCount = 0;
        // Appended, not "'" + name: GCC 12 warns falsely (-Wrestrict, bug 105329) on that inlined.
        std::string what = "'";
        what.append(excerptForMessage(name)).append("' COLOR_0 value");
        for (glm::vec4& colour : mesh.colors) {
            for (int c = 0; c < 4; ++c) {
                if (colour[c] >= kNonNegativeRange.min && colour[c] <= kNonNegativeRange.max) continue;
                // Accessor values are finite: the one message is made for the first only.
                colour[c] = clampedCount++ == 0 ? shaderValue(colour[c], kNonNegativeRange, what, clamped)
                            : colour[c] < 0.0f  ? float(kNonNegativeRange.min)
                                                : float(kNonNegativeRange.max);
            }
        }
        if (clampedCount > 1)
            clamped.front() += " (and " + std::to_string(clampedCount - 1) + " more values outside it)";
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
        const PrimitivePose pose{mPoses[std::size_t(nodeIndex)].weights, skinJoints ? &*skinJoints : nullptr};
        const std::vector<std::string> path = nodePath(nodeIndex);
        for (std::size_t i = 0; i < mesh.primitives.size(); ++i) {
            const std::string name =
                mesh.primitives.size() == 1 ? baseName : baseName + " primitive " + std::to_string(i);
            chargeNodePath(path); // before the primitive's copy, as its vertices are
            const std::size_t meshesBefore = mOut.meshes.size();
            addPrimitive(mesh.primitives[i], name, nodeLabel(nodeIndex), world, pose);
            if (mOut.meshes.size() > meshesBefore) {
                mOut.meshes.back().nodePath = path;
            }
        }
    }

    /** What moves a primitive's vertices besides its node's transform. */
    struct PrimitivePose {
        const std::vector<double>& morphWeights;
        const std::vector<glm::dmat4>* skinJoints = nullptr; ///< null: not skinned
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
        std::memcpy(vectors.data(), values.data(), vectors.size() * sizeof(glm::vec3));
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
        for (std::size_t i = 0; i < indices.size(); ++i) {
            if (indices[i] >= vertexCount) {
                fail("index accessor " + std::to_string(accessorIndex) + " element " + std::to_string(i) + ": index " +
                     std::to_string(indices[i]) + " out of range (primitive has " + std::to_string(vertexCount) +
                     " vertices)");
            }
        }
        return indices;
    }

    /** Triangles of a TRIANGLES, TRIANGLE_STRIP or TRIANGLE_FAN index sequence, all wound like the first. */
    std::vector<glm::uvec3> triangulate(int mode, const std::vector<std::uint32_t>& v, const std::string& name) {
        std::vector<glm::uvec3> triangles;
        const std::size_t n = v.size();
        if (mode == TINYGLTF_MODE_TRIANGLES) {
            if (n % 3 != 0) {
                mOut.warnings.push_back("'" + excerptForMessage(name) + "': " + std::to_string(n % 3) +
                                        " trailing indices of an incomplete triangle ignored");
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
            mOut.warnings.push_back("'" + excerptForMessage(name) + "': non-triangle primitive (mode " +
                                    std::to_string(mode) + ", " + modeName(mode) + ") skipped");
            return;
        }
        const auto positionAttribute = primitive.attributes.find("POSITION");
        if (positionAttribute == primitive.attributes.end()) {
            mOut.warnings.push_back("'" + excerptForMessage(name) + "': primitive without POSITION skipped");
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

        if (draco) {
            // Draco reorders and merges vertices, so a target's uncompressed accessor no longer lines up with them.
            for (std::size_t t = 0; t < primitive.targets.size() && t < pose.morphWeights.size(); ++t) {
                if (pose.morphWeights[t] != 0.0 && std::isfinite(pose.morphWeights[t])) { // as applyMorphTargets()
                    fail("'" + excerptForMessage(name) +
                         "': morph targets of a Draco-compressed primitive are not supported (target " +
                         std::to_string(t) + " has weight " + formatNumber(pose.morphWeights[t]) + ")");
                }
            }
        }
        applyMorphTargets(mPath, mModel, primitive, pose.morphWeights, mesh.positions, mesh.normals, name,
                          mOut.warnings);
        std::optional<SkinBlend> skin;
        if (pose.skinJoints) {
            // SkinBlend holds every JOINTS_n/WEIGHTS_n set for the primitive's vertices while it is baked.
            const auto sets = std::ranges::count_if(
                primitive.attributes, [](const auto& entry) { return entry.first.starts_with("JOINTS_"); });
            mBudget.check(vertexCount * std::size_t(sets) * kSkinBytesPerVertexPerSet / MeshBudget::kBytesPerVertex + 1,
                          0);
            skin.emplace(mPath, mModel, primitive, vertexCount, *pose.skinJoints, world, name,
                         draco ? &draco->attributes : nullptr);
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
        }
        // A mirroring transform turns counter-clockwise into clockwise; swap two corners to keep fronts outward.
        for (glm::uvec3& triangle : mesh.triangles) {
            if (skin ? bool(mirrored[triangle.x]) : glm::determinant(linear) < 0.0) {
                std::swap(triangle.y, triangle.z);
            }
        }

        if (primitive.material >= 0) { // in range: checkMaterialIndices()
            mesh.material = material(primitive.material);
        }
        mOut.meshes.push_back(std::move(mesh));
    }

    const std::string& mPath;
    const tinygltf::Model& mModel;
    RawScene& mOut;
    MeshBudget& mBudget;
    const LoadOptions& mOptions;
    std::vector<NodePose> mPoses; ///< per node: its local transform and morph weights, animated or not (posed())
    std::vector<bool> mReached;   ///< nodes already reached by the walk; reaching one again is an error
    /** Per node reached by the walk: its world transform, composed precisely, and relative to mOut.origin. */
    std::vector<std::optional<PreciseTransform>> mPreciseWorlds =
        std::vector<std::optional<PreciseTransform>>(mModel.nodes.size());
    std::vector<std::optional<glm::dmat4>> mWorlds;
    std::vector<int> mParent = std::vector<int>(mModel.nodes.size(), -1); ///< each node's parent, -1 for a root
    std::vector<std::optional<std::string>> mMaterialShadeMaps; ///< per material, once read: its shade map or ""
    std::vector<std::optional<Material>> mMaterials;            ///< per material, once read
    std::size_t mSkippedPrimitives = 0;
    double mPlacementError = 0.0;     ///< the largest error bound notePlacement() saw
    double mPlacementMagnitude = 0.0; ///< the largest term of that placement
    std::string mPlacementLabel;      ///< the node it placed
};

/** Deepest nesting of arrays and objects in JSON text, outside strings. */
std::size_t jsonNestingDepth(std::string_view text) {
    std::size_t depth = 0;
    std::size_t deepest = 0;
    bool inString = false;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (inString) {
            if (c == '\\')
                ++i;
            else if (c == '"')
                inString = false;
        } else if (c == '"') {
            inString = true;
        } else if (c == '[' || c == '{') {
            deepest = std::max(deepest, ++depth);
        } else if ((c == ']' || c == '}') && depth > 0) {
            --depth;
        }
    }
    return deepest;
}

/** The JSON text of a .gltf file or of a GLB's JSON chunk (empty when the GLB is too short to have one). */
std::string_view jsonOf(std::string_view content, bool binary) {
    if (!binary) return content;
    if (content.size() < 20) return {};
    std::uint32_t chunkLength = 0;
    std::memcpy(&chunkLength, content.data() + 12, sizeof chunkLength);
    return content.substr(20, chunkLength);
}

/** The file with "indices" removed from every KHR_draco_mesh_compression primitive, or nothing when no primitive has
 *  the extension (or the JSON does not parse: tinygltf then says why). tinygltf built without Draco refuses an indices
 *  accessor without a buffer view, which is how Draco files write it; the decoded Draco faces replace those indices
 *  (decodeDracoPrimitive()). A GLB is rebuilt around the new JSON chunk with its other chunks as they were. */
std::optional<std::string> withoutDracoIndices(std::string_view content, bool binary) {
    const std::string_view json = jsonOf(content, binary);
    if (json.find(kDracoExtension) == std::string_view::npos) return std::nullopt;
    nlohmann::json document = nlohmann::json::parse(json, nullptr, false);
    if (!document.is_object() || !document.contains("meshes") || !document["meshes"].is_array()) return std::nullopt;
    bool changed = false;
    for (nlohmann::json& mesh : document["meshes"]) {
        if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
        for (nlohmann::json& primitive : mesh["primitives"]) {
            if (primitive.is_object() && primitive.contains("indices") && primitive.contains("extensions") &&
                primitive["extensions"].is_object() && primitive["extensions"].contains(kDracoExtension)) {
                primitive.erase("indices");
                changed = true;
            }
        }
    }
    if (!changed) return std::nullopt;
    std::string text = document.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    if (!binary) return text;
    const std::size_t restOffset = 20 + json.size();
    if (content.size() < restOffset) return std::nullopt;
    while (text.size() % 4 != 0) text += ' '; // GLB chunks are 4-byte aligned; JSON pads with spaces
    const auto u32 = [](std::size_t value) {
        const std::uint32_t little = std::uint32_t(value);
        return std::string(reinterpret_cast<const char*>(&little), 4);
    };
    const std::string_view rest = content.substr(restOffset);
    return std::string(content.substr(0, 8)) + u32(12 + 8 + text.size() + rest.size()) + u32(text.size()) + "JSON" +
           text + std::string(rest);
}

/** tinygltf parses JSON recursively, so absurd nesting would overflow the stack: glTF itself nests a few levels, and
 *  extras rarely more than a dozen. Checked before tinygltf sees the file. */
void rejectDeepJson(const std::string& path, std::string_view content, bool binary) {
    constexpr std::size_t kMaxJsonDepth = 256;
    // GLB: 12-byte header, then the JSON chunk's length, type, and text.
    const std::string_view json = binary && content.size() < 20 ? content : jsonOf(content, binary);
    if (jsonNestingDepth(json) > kMaxJsonDepth)
        throwLoadError(path, "JSON nested deeper than " + std::to_string(kMaxJsonDepth) + " levels");
}

/** The external (non-data:) URIs of the top-level "buffers" and "images" arrays, collected by a SAX pass over the
 *  JSON before tinygltf reads it, so the file callbacks can tell an image (not read at load time) from a buffer (read).
 */
class ExternalUriCollector : public nlohmann::json_sax<nlohmann::json> {
public:
    std::vector<std::string> bufferUris;
    std::vector<std::string> imageUris;

    bool null() override { return leaveValue(); }
    bool boolean(bool) override { return leaveValue(); }
    bool number_integer(number_integer_t) override { return leaveValue(); }
    bool number_unsigned(number_unsigned_t) override { return leaveValue(); }
    bool number_float(number_float_t, const string_t&) override { return leaveValue(); }
    bool binary(binary_t&) override { return leaveValue(); }
    bool string(string_t& value) override {
        // Depth 3: the root object, the "buffers"/"images" array, one element object; the member is "uri".
        if (mKeys.size() == 3 && mKeys[2] == "uri" && value.rfind("data:", 0) != 0) {
            if (mKeys[0] == "buffers") bufferUris.push_back(value);
            if (mKeys[0] == "images") imageUris.push_back(value);
        }
        return leaveValue();
    }
    bool start_object(std::size_t) override {
        mKeys.emplace_back();
        return true;
    }
    bool key(string_t& name) override {
        mKeys.back() = name.size() <= 8 ? name : std::string(); // only "buffers", "images" and "uri" matter
        return true;
    }
    bool end_object() override {
        mKeys.pop_back();
        return leaveValue();
    }
    bool start_array(std::size_t) override {
        mKeys.emplace_back(); // arrays have no keys; the placeholder keeps depths aligned with objects
        return true;
    }
    bool end_array() override {
        mKeys.pop_back();
        return leaveValue();
    }
    bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override {
        return false; // tinygltf reports the error in its own words
    }

private:
    bool leaveValue() { return true; }

    std::vector<std::string> mKeys; ///< per open container: the member being read ("" in arrays)
};

/** A URI as tinygltf turns it into a file name: '+' becomes a space and %XX the byte XX (a non-hex digit counts as 0,
 *  as tinygltf does), so the names match the ones its file callbacks receive. */
std::string decodeUri(std::string_view uri) {
    const auto hexValue = [](char c) -> unsigned {
        if (c >= '0' && c <= '9') return unsigned(c - '0');
        if (c >= 'a' && c <= 'f') return unsigned(c - 'a' + 10);
        if (c >= 'A' && c <= 'F') return unsigned(c - 'A' + 10);
        return 0;
    };
    std::string decoded;
    for (std::size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '+') {
            decoded += ' ';
        } else if (uri[i] == '%' && i + 2 < uri.size()) {
            decoded += char((hexValue(uri[i + 1]) << 4) | hexValue(uri[i + 2]));
            i += 2;
        } else {
            decoded += uri[i];
        }
    }
    return decoded;
}

/** The path tinygltf asks its callbacks for first: the model's folder joined with the decoded URI. */
std::string pathBesideModel(const std::string& baseDirectory, std::string_view uri) {
    const std::string decoded = decodeUri(uri);
    if (baseDirectory.empty()) return decoded;
    return baseDirectory + (baseDirectory.back() == '/' ? "" : "/") + decoded;
}

/** What tinygltf's file callbacks work with: the load's budget, the external files the JSON names, and the record of
 *  what was opened (LoadReport::inputFiles). */
struct ExternalFiles {
    MeshBudget& budget;
    std::set<std::string> bufferPaths;
    std::set<std::string> imagePaths;
    std::vector<std::string> opened;
};

/** Only the files the JSON names, beside the model: tinygltf would otherwise fall back to the current folder and read a
 *  file of the same name there. Asks the file system rather than opening (tinygltf's own test blocks on a FIFO). An
 *  image counts as present even when missing: it is not read at load time (only when a pass decodes it, which reports a
 *  missing one then), so loading must not fail or warn for it. */
bool externalFileExists(const std::string& path, void* user) {
    const auto& files = *static_cast<const ExternalFiles*>(user);
    if (files.imagePaths.count(path) > 0) {
        return true;
    }
    std::error_code error;
    return files.bufferPaths.count(path) > 0 && std::filesystem::exists(path, error);
}

/** tinygltf's file reading. An image gets a one-byte placeholder without being opened (SceneImage keeps its path, read
 *  when decoded, so a 1 GiB texture is not held by every load); a buffer must be a regular file, and its size is
 * charged to the load's memory budget before it is read. A refusal comes back to tinygltf as a read error with the
 * reason. */
bool readExternalFile(std::vector<unsigned char>* out, std::string* error, const std::string& path, void* user) {
    auto& files = *static_cast<ExternalFiles*>(user);
    if (files.bufferPaths.count(path) == 0 && files.imagePaths.count(path) > 0) {
        out->assign(1, 0); // tinygltf refuses an empty image; keepEncodedImage() ignores the byte
        return true;
    }
    // A FIFO or device ("/dev/stdin", "/dev/zero") as a buffer URI would block or never end: files only.
    std::error_code typeError;
    if (!std::filesystem::is_regular_file(path, typeError)) {
        if (error) *error += "external file '" + excerptForMessage(path) + "' is not a regular file\n";
        return false;
    }
    std::error_code sizeError;
    const std::uintmax_t size = std::filesystem::file_size(path, sizeError);
    if (sizeError) {
        if (error) *error += "cannot read '" + excerptForMessage(path) + "': " + sizeError.message() + "\n";
        return false;
    }
    try {
        files.budget.chargeFile(std::size_t(size));
    } catch (const SceneError&) {
        if (error)
            *error += "external file '" + excerptForMessage(path) + "' is " + std::to_string(size >> 20) +
                      " MiB, above the memory limit of " + std::to_string(files.budget.limitBytes() >> 20) + " MiB\n";
        return false;
    }
    files.opened.push_back(path);
    return tinygltf::ReadWholeFile(out, error, path, nullptr);
}

/** The file's images in its order (a texture's `source` indexes them): embedded ones with their encoded bytes, external
 *  ones with their path beside the model, not read here. */
std::vector<SceneImage> sceneImages(const std::string& path, const tinygltf::Model& model,
                                    const std::string& baseDirectory, const DataUriImages& dataUriImages,
                                    MeshBudget& budget) {
    std::vector<SceneImage> images;
    images.reserve(model.images.size());
    for (std::size_t i = 0; i < model.images.size(); ++i) {
        const tinygltf::Image& image = model.images[i];
        SceneImage result;
        result.name = image.name.empty() ? excerptForMessage(image.uri) : image.name;
        result.mimeType = image.mimeType;
        if (image.bufferView >= 0) {
            // tinygltf checked only that the view and its buffer exist.
            const tinygltf::BufferView& view = model.bufferViews[std::size_t(image.bufferView)];
            const std::vector<unsigned char>& buffer = model.buffers[std::size_t(view.buffer)].data;
            if (view.byteOffset > buffer.size() || view.byteLength > buffer.size() - view.byteOffset) {
                throwLoadError(path, "image " + std::to_string(i) + ": buffer view " +
                                         std::to_string(image.bufferView) + " (offset " +
                                         std::to_string(view.byteOffset) + ", length " +
                                         std::to_string(view.byteLength) + ") exceeds its buffer of " +
                                         std::to_string(buffer.size()) + " bytes");
            }
            budget.chargeFile(view.byteLength);
            const auto first = buffer.begin() + std::ptrdiff_t(view.byteOffset);
            result.encoded =
                std::make_shared<const std::vector<unsigned char>>(first, first + std::ptrdiff_t(view.byteLength));
        } else if (!image.uri.empty()) {
            result.path = pathBesideModel(baseDirectory, image.uri);
        } else if (i < dataUriImages.bytes.size()) {
            result.encoded = dataUriImages.bytes[i];
        }
        images.push_back(std::move(result));
    }
    return images;
}

RawScene readGltf(const std::string& path, std::string_view content, MeshBudget& budget, const LoadOptions& options) {
    // A byte-order mark before the JSON needs nothing here: tinygltf's JSON parser (nlohmann) skips it.
    const bool binary = content.size() >= 4 && content.substr(0, 4) == "glTF";
    rejectDeepJson(path, content, binary);
    // tinygltf takes 32-bit lengths; the GLB container itself cannot describe more.
    if (content.size() > std::numeric_limits<std::uint32_t>::max())
        throwLoadError(path, "glTF files above 4 GiB are not supported");
    // tinygltf keeps its own copy of every buffer it decodes (the GLB's BIN chunk, data URIs): at most the file again.
    budget.chargeFile(content.size());
    const std::optional<std::string> dracoReady = withoutDracoIndices(content, binary);
    if (dracoReady) {
        budget.chargeFile(dracoReady->size());
        content = *dracoReady;
    }
    const std::string baseDirectory = std::filesystem::path(path).parent_path().string();
    ExternalUriCollector uris;
    const std::string_view json = jsonOf(content, binary);
    nlohmann::json::sax_parse(json.begin(), json.end(), &uris, nlohmann::json::input_format_t::json, false);
    ExternalFiles files{budget, {}, {}, {}};
    for (const std::string& uri : uris.bufferUris) files.bufferPaths.insert(pathBesideModel(baseDirectory, uri));
    for (const std::string& uri : uris.imageUris) files.imagePaths.insert(pathBesideModel(baseDirectory, uri));

    tinygltf::TinyGLTF loader;
    DataUriImages dataUriImages{budget, {}};
    loader.SetImageLoader(&keepEncodedImage, &dataUriImages);
    // Keeps each extras object as JSON text, so materialShadeMap() sees the types as written (GltfWalker).
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
        throwLoadError(path, std::string(binary ? "invalid GLB" : "invalid glTF") + ": " +
                                 (error.empty() ? "tinygltf gave no reason" : joinLines(error)));
    }

    RawScene scene;
    scene.format = binary ? "glb" : "gltf";
    // tinygltf also reports recoverable problems (e.g. chunk padding) through `error` while still succeeding.
    for (const std::string* messages : {&warning, &error}) {
        for (const std::string& line : splitLines(*messages)) {
            scene.warnings.push_back("tinygltf: " + shortenWords(line));
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
    scene.images = sceneImages(path, model, baseDirectory, dataUriImages, budget);
    GltfWalker(path, model, scene, budget, options).walk();
    if (scene.meshes.empty()) {
        throwLoadError(path, "no triangles in the file");
    }
    return scene;
}

/** The files a glTF (or GLB: `content` may stop after the JSON chunk) names: external buffers and images, and the
 *  shade maps of its materials, resolved as readGltf() resolves them. Best effort, nothing thrown. */
std::vector<std::string> gltfReferencedFiles(const std::string& path, std::string_view content) {
    const bool binary = content.size() >= 4 && content.substr(0, 4) == "glTF";
    const std::string_view json = jsonOf(content, binary);
    const std::string baseDirectory = std::filesystem::path(path).parent_path().string();
    std::vector<std::string> files;
    ExternalUriCollector uris; // whatever it collected before a syntax error still counts
    nlohmann::json::sax_parse(json.begin(), json.end(), &uris, nlohmann::json::input_format_t::json, false);
    for (const auto* list : {&uris.bufferUris, &uris.imageUris})
        for (const std::string& uri : *list) files.push_back(pathBesideModel(baseDirectory, uri));
    constexpr std::size_t kMaxJsonDepth = 256; // as rejectDeepJson()
    if (jsonNestingDepth(json) > kMaxJsonDepth) return files;
    const nlohmann::json document = nlohmann::json::parse(json, nullptr, false);
    if (!document.is_object() || !document.contains("materials") || !document["materials"].is_array()) return files;
    for (const nlohmann::json& material : document["materials"]) {
        const nlohmann::json::json_pointer where("/extras/inkgraph/shademap");
        if (material.is_object() && material.contains(where) && material[where].is_string() &&
            !material[where].get_ref<const std::string&>().empty())
            files.push_back(shadeMapBesideModel(path, material[where].get_ref<const std::string&>()));
    }
    return files;
}

/** A GLB's (or VRM's) header and JSON chunk, without the binary chunk after it, which can be large and names no file;
 *  empty when they cannot be read. */
std::string glbJsonChunk(const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    std::string content(20, '\0');
    if (!file.read(content.data(), 20)) return {};
    std::uint32_t chunkLength = 0;
    std::memcpy(&chunkLength, content.data() + 12, sizeof chunkLength);
    std::error_code error;
    const std::uintmax_t size = std::filesystem::file_size(path, error);
    if (error || chunkLength > size - 20) return {};
    content.resize(20 + std::size_t(chunkLength));
    if (!file.read(content.data() + 20, chunkLength)) return {};
    return content;
}

std::vector<std::string> glbReferencedFiles(const std::string& path) {
    const std::string content = glbJsonChunk(path);
    return content.empty() ? std::vector<std::string>{} : gltfReferencedFiles(path, content);
}

} // namespace

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
