/** @file VRM Animation (.vrma) retargeting: the VRMC_vrm_animation-1.0 specification's humanoid, sampled and turned
 *  into the normalized pose convention as three-vrm-animation does, then posed on the model by VrmHumanoid.h. */

#include "scene/formats/gltf/VrmAnimation.h"

#include "scene/formats/FormatReaders.h"
#include "scene/formats/gltf/GltfFiles.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <limits>

namespace inkgraph::detail {

namespace {

/** The .vrma parsed by tinygltf: its GLB's own binary chunk only (it names no other files to read). */
tinygltf::Model parseVrma(const std::string& path, const std::string& content, MeshBudget& budget) {
    if (content.size() < 4 || content.compare(0, 4, "glTF") != 0) {
        throwLoadError(path, "not a VRM Animation file: a .vrma is a GLB, and this one does not start with 'glTF'");
    }
    if (content.size() > std::numeric_limits<std::uint32_t>::max())
        throwLoadError(path, "VRM Animation files above 4 GiB are not supported");
    rejectDeepJson(path, content, true);
    budget.chargeFile(content.size()); // tinygltf's copy of its buffers
    tinygltf::TinyGLTF loader;
    DataUriImages images{budget, {}};
    loader.SetImageLoader(&keepEncodedImage, &images);
    ExternalFiles files{budget, {}, {}, {}}; // none named: an external buffer is refused
    loader.SetFsCallbacks(
        {&externalFileExists, &tinygltf::ExpandFilePath, &readExternalFile, &tinygltf::WriteWholeFile, &files});
    tinygltf::Model model;
    std::string error;
    std::string warning;
    bool loaded = false;
    try {
        loaded = loader.LoadBinaryFromMemory(
            &model, &error, &warning, reinterpret_cast<const unsigned char*>(content.data()),
            static_cast<unsigned int>(content.size()), std::filesystem::path(path).parent_path().string());
    } catch (const std::exception& thrown) {
        throwLoadError(path, std::string("invalid GLB: tinygltf failed (") + excerptForMessage(thrown.what()) + ")");
    }
    if (!loaded) {
        throwLoadError(path, "invalid GLB: " +
                                 (error.empty() ? std::string("tinygltf gave no reason") : excerptForMessage(error)));
    }
    return model;
}

} // namespace

bool isVrmAnimationFile(const std::string& animation) {
    std::string extension = std::filesystem::path(animation).extension().string();
    std::ranges::transform(extension, extension.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    std::error_code ignored;
    return extension == ".vrma" && std::filesystem::is_regular_file(animation, ignored);
}

void applyVrmAnimation(const std::string& vrmaPath, double time, const tinygltf::Model& model, const Humanoid& humanoid,
                       const std::vector<NodePose>& rest, std::vector<NodePose>& poses, MeshBudget& budget,
                       std::vector<Warning>& warnings) {
    const tinygltf::Model vrma = parseVrma(vrmaPath, readSideFile(vrmaPath, "VRM Animation file", budget), budget);
    std::vector<Warning> vrmaWarnings;
    const std::optional<Humanoid> animated = readHumanBonesObject(vrma, "VRMC_vrm_animation", vrmaWarnings);
    if (!animated) throwLoadError(vrmaPath, "not a VRM Animation file: it has no VRMC_vrm_animation extension");
    const std::vector<NodePose> vrmaRest = restPose(vrmaPath, vrma);
    std::vector<NodePose> vrmaPoses = vrmaRest;
    if (!vrma.animations.empty()) applyAnimation(vrmaPath, vrma, 0, time, vrmaPoses, budget, vrmaWarnings);
    for (Warning& warning : vrmaWarnings) {
        if (warning.file.empty()) warning.file = vrmaPath;
        warnings.push_back(std::move(warning));
    }

    // A sampled local rotation L of a bone whose parent's rest world rotation is P and whose own rest rotation is R
    // turns its world rotation from P R to P L: by q = P L R^-1 P^-1 about world axes, the normalized rotation
    // (applyHumanoidPose() inverts this on the model).
    const std::vector<int> vrmaParents = nodeParents(vrma);
    HumanoidPose pose;
    for (const auto& [bone, node] : animated->nodeOfBone) {
        if (!humanoid.nodeOfBone.contains(bone)) continue; // a bone the model lacks has nowhere to go
        const int parent = vrmaParents[std::size_t(node)];
        const glm::dquat parentRest =
            parent >= 0 ? worldRotation(vrmaRest, vrmaParents, parent) : glm::dquat(1.0, 0.0, 0.0, 0.0);
        pose[bone] = glm::normalize(parentRest * vrmaPoses[std::size_t(node)].rotation *
                                    glm::inverse(vrmaRest[std::size_t(node)].rotation) * glm::inverse(parentRest));
    }
    applyHumanoidPose(model, humanoid, pose, rest, poses, warnings);

    // The hips: where the .vrma puts them in its world, scaled to the model's size by the rest hips heights (as
    // three-vrm-animation scales them), turned half a turn about Y onto a 0.x model.
    const auto vrmaHips = animated->nodeOfBone.find("hips");
    const auto modelHips = humanoid.nodeOfBone.find("hips");
    if (vrmaHips == animated->nodeOfBone.end() || modelHips == humanoid.nodeOfBone.end()) return;
    // Only an animation that moves the hips moves them (three-vrm-animation makes a hips track only from one).
    const bool movesHips = !vrma.animations.empty() &&
                           std::ranges::any_of(vrma.animations[0].channels, [&](const tinygltf::AnimationChannel& c) {
                               return c.target_node == vrmaHips->second && c.target_path == "translation";
                           });
    if (!movesHips) return;
    const std::vector<int> parents = nodeParents(model);
    const double vrmaHeight = worldMatrix(vrmaRest, vrmaParents, vrmaHips->second)[3].y;
    const double modelHeight = worldMatrix(rest, parents, modelHips->second)[3].y;
    if (!(std::abs(vrmaHeight) > 0.0) || !std::isfinite(modelHeight / vrmaHeight) ||
        poses[std::size_t(modelHips->second)].matrix) {
        return; // no scale to take (hips on the ground), or hips that cannot move: rotations only
    }
    glm::dvec3 hips = glm::dvec3(worldMatrix(vrmaPoses, vrmaParents, vrmaHips->second)[3]) * (modelHeight / vrmaHeight);
    if (humanoid.facesMinusZ) hips = glm::dvec3(-hips.x, hips.y, -hips.z);
    const int hipsParent = parents[std::size_t(modelHips->second)];
    const glm::dmat4 parentWorld = hipsParent >= 0 ? worldMatrix(rest, parents, hipsParent) : glm::dmat4(1.0);
    poses[std::size_t(modelHips->second)].translation = glm::dvec3(glm::inverse(parentWorld) * glm::dvec4(hips, 1.0));
}

} // namespace inkgraph::detail
