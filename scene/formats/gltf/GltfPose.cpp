/** @file Node poses, animation sampling, morph targets and skinning for the glTF reader, after the glTF 2.0
 *  specification's "Animations", "Morph Targets" and "Skins" sections and its Appendix C (interpolation). */

#include "scene/formats/gltf/GltfPose.h"

#include "scene/formats/FormatReaders.h"
#include "scene/formats/gltf/GltfAccessors.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <tiny_gltf.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <optional>
#include <tuple>

namespace inkgraph::detail {

namespace {

/** "animation 1 'walk'", or "animation 1" for an unnamed one. */
std::string animationLabel(const tinygltf::Model& model, std::size_t index) {
    const std::string& name = model.animations[index].name;
    return "animation " + std::to_string(index) + (name.empty() ? "" : " '" + excerptForMessage(name) + "'");
}

/** Animations listed by name in a refusal; the rest are counted. */
constexpr std::size_t kMaxListedAnimations = 10;

/** The element of `curve` at keyframe `key` (for CUBICSPLINE: `part` 0 in-tangent, 1 value, 2 out-tangent). */
const float* keyElement(const AnimationCurve& curve, std::size_t key, std::size_t part) {
    const std::size_t perKey = curve.interpolation == Interpolation::CubicSpline ? 3 : 1;
    return curve.values.data() + (key * perKey + part) * curve.components;
}

std::vector<double> elementAt(const AnimationCurve& curve, std::size_t key) {
    const std::size_t part = curve.interpolation == Interpolation::CubicSpline ? 1 : 0;
    const float* element = keyElement(curve, key, part);
    return std::vector<double>(element, element + curve.components);
}

/** Spherical interpolation of unit quaternions stored x, y, z, w, along the shorter arc. */
std::vector<double> slerpXyzw(const float* a, const float* b, double t) {
    const glm::dquat from(a[3], a[0], a[1], a[2]);
    const glm::dquat to(b[3], b[0], b[1], b[2]);
    // glm::slerp takes the shorter arc (it negates `to` when the dot product is negative), as glTF asks.
    const glm::dquat result = glm::slerp(glm::normalize(from), glm::normalize(to), t);
    return {result.x, result.y, result.z, result.w};
}

/** `xyzw` as a unit quaternion; emptied where it is of zero length (no rotation at all, not the identity). */
void normaliseQuaternion(std::vector<double>& xyzw) {
    const std::optional<glm::dquat> unit = unitQuaternion(xyzw[0], xyzw[1], xyzw[2], xyzw[3]);
    xyzw = unit ? std::vector<double>{unit->x, unit->y, unit->z, unit->w} : std::vector<double>();
}

Interpolation interpolationOf(const std::string& path, const std::string& label, const std::string& name) {
    if (name.empty() || name == "LINEAR") return Interpolation::Linear; // LINEAR is the default
    if (name == "STEP") return Interpolation::Step;
    if (name == "CUBICSPLINE") return Interpolation::CubicSpline;
    throwLoadError(path, label + ": unknown interpolation '" + excerptForMessage(name) +
                             "' (known: 'LINEAR', 'STEP', 'CUBICSPLINE')");
}

/** The number of morph targets of node `nodeIndex`'s mesh (its first primitive's: glTF requires all alike). */
std::size_t morphTargetCount(const tinygltf::Model& model, const tinygltf::Node& node) {
    if (node.mesh < 0 || std::size_t(node.mesh) >= model.meshes.size()) return 0;
    const tinygltf::Mesh& mesh = model.meshes[std::size_t(node.mesh)];
    return mesh.primitives.empty() ? 0 : mesh.primitives[0].targets.size();
}

/** Reads one sampler's keyframes: `components` floats per element (0: as many as the output holds per keyframe,
 *  for weights). */
AnimationCurve readCurve(const std::string& path, const tinygltf::Model& model,
                         const tinygltf::AnimationSampler& sampler, const std::string& label, int outputType,
                         std::size_t components, bool rotation, MeshBudget& budget) {
    AnimationCurve curve;
    curve.interpolation = interpolationOf(path, label, sampler.interpolation);
    curve.rotation = rotation;
    const std::size_t keys = accessorCount(path, model, sampler.input, TINYGLTF_TYPE_SCALAR, label + " input");
    const std::size_t outputs = accessorCount(path, model, sampler.output, outputType, label + " output");
    const std::size_t perKey = curve.interpolation == Interpolation::CubicSpline ? 3 : 1;
    if (keys == 0) {
        throwLoadError(path, label + ": no keyframes (input accessor " + std::to_string(sampler.input) + " is empty)");
    }
    // Weights: a SCALAR output of keyframes x targets values; every other path one element per keyframe.
    const std::size_t elementComponents = outputType == TINYGLTF_TYPE_SCALAR ? 1 : components;
    const std::size_t elementsPerKey = outputType == TINYGLTF_TYPE_SCALAR ? components : 1;
    if (outputs / perKey / keys != elementsPerKey || outputs % (perKey * keys) != 0) {
        throwLoadError(
            path, label + ": output accessor " + std::to_string(sampler.output) + " has " + std::to_string(outputs) +
                      " elements, expected " + std::to_string(keys * perKey * elementsPerKey) + " (" +
                      std::to_string(keys) + " keyframes" + (perKey == 3 ? " x 3 for CUBICSPLINE" : "") +
                      (outputType == TINYGLTF_TYPE_SCALAR ? " x " + std::to_string(components) + " morph targets"
                                                          : std::string()) +
                      ")");
    }
    // Keyframes are held as floats, input and output together; charged as the vertices they would equal.
    const std::size_t bytes = (keys + outputs * elementComponents) * sizeof(float);
    budget.checkBytes(bytes, label + "'s keyframes");
    curve.times = readAccessorFloats(path, model, sampler.input, TINYGLTF_TYPE_SCALAR, label + " input");
    for (std::size_t i = 1; i < curve.times.size(); ++i) {
        if (curve.times[i] < curve.times[i - 1]) {
            throwLoadError(path, label + ": keyframe times decrease at element " + std::to_string(i) + " (" +
                                     formatNumber(curve.times[i - 1]) + " then " + formatNumber(curve.times[i]) + ")");
        }
    }
    curve.values = readAccessorFloats(path, model, sampler.output, outputType, label + " output");
    curve.components = elementComponents * elementsPerKey;
    // A keyframe's rotation of zero length is none: it was drawn as the identity, without a word, where a node's
    // rotation of zero length is refused.
    for (std::size_t key = 0; rotation && key < keys; ++key) {
        const float* q = keyElement(curve, key, perKey == 3 ? 1 : 0);
        if (!unitQuaternion(q[0], q[1], q[2], q[3])) {
            throwLoadError(path, label + ": keyframe " + std::to_string(key) + " rotation [" + formatNumber(q[0]) +
                                     ", " + formatNumber(q[1]) + ", " + formatNumber(q[2]) + ", " + formatNumber(q[3]) +
                                     "] must be finite and of non-zero length");
        }
    }
    return curve;
}

/** a + b exactly, as the rounded sum and its rounding error (Knuth's TwoSum). */
void addExactly(double a, double b, double& sum, double& error) {
    sum = a + b;
    const double bPart = sum - a;
    error = (a - (sum - bPart)) + (b - bPart);
}

} // namespace

PreciseTransform::PreciseTransform(const glm::dmat4& matrix) {
    for (int column = 0; column < 4; ++column) {
        for (int row = 0; row < 4; ++row) mEntries[column][row].hi = matrix[column][row];
    }
    for (int row = 0; row < 3; ++row) mMagnitude = std::max(mMagnitude, std::abs(matrix[3][row]));
}

PreciseTransform PreciseTransform::operator*(const glm::dmat4& local) const {
    PreciseTransform result;
    result.mMagnitude = mMagnitude;
    result.mSteps = mSteps + 1;
    for (int column = 0; column < 4; ++column) {
        for (int row = 0; row < 4; ++row) {
            double hi = 0.0;
            double lo = 0.0;
            for (int k = 0; k < 4; ++k) {
                // (a.hi + a.lo) x b: the product's rounding error comes exactly from fma, a.lo x b is far below it.
                const Sum& a = mEntries[k][row];
                const double b = local[column][k];
                const double product = a.hi * b;
                const double productError = std::fma(a.hi, b, -product) + a.lo * b;
                if (column == 3 && row < 3) result.mMagnitude = std::max(result.mMagnitude, std::abs(product));
                double sum = 0.0;
                double sumError = 0.0;
                addExactly(hi, product, sum, sumError);
                lo += sumError + productError;
                hi = sum;
            }
            // Renormalised, so hi is the entry rounded to double and lo what is left.
            addExactly(hi, lo, result.mEntries[column][row].hi, result.mEntries[column][row].lo);
        }
    }
    return result;
}

glm::dvec3 PreciseTransform::translation() const { return {mEntries[3][0].hi, mEntries[3][1].hi, mEntries[3][2].hi}; }

glm::dmat4 PreciseTransform::relativeTo(const glm::dvec3& origin) const {
    glm::dmat4 matrix;
    for (int column = 0; column < 4; ++column) {
        for (int row = 0; row < 4; ++row) matrix[column][row] = mEntries[column][row].hi;
    }
    // translate(-origin) x M adds -origin x M's bottom row (0, 0, 0, 1 for every glTF node) to each column.
    for (int column = 0; column < 4; ++column) {
        const double w = mEntries[column][3].hi;
        for (int row = 0; row < 3; ++row) {
            double sum = 0.0;
            double error = 0.0;
            addExactly(mEntries[column][row].hi, -origin[row] * w, sum, error);
            matrix[column][row] = sum + (error + mEntries[column][row].lo);
        }
    }
    return matrix;
}

glm::dmat4 NodePose::local() const {
    if (matrix) return *matrix;
    return glm::translate(glm::dmat4(1.0), translation) * glm::mat4_cast(rotation) * glm::scale(glm::dmat4(1.0), scale);
}

std::optional<glm::dquat> unitQuaternion(double x, double y, double z, double w) {
    if (!(std::isfinite(x) && std::isfinite(y) && std::isfinite(z) && std::isfinite(w))) return std::nullopt;
    const double largest = std::max({std::abs(x), std::abs(y), std::abs(z), std::abs(w)});
    if (largest == 0.0) return std::nullopt;
    const glm::dquat scaled(w / largest, x / largest, y / largest, z / largest);
    return scaled / glm::length(scaled);
}

std::vector<NodePose> restPose(const std::string& path, const tinygltf::Model& model) {
    std::vector<NodePose> poses(model.nodes.size());
    for (std::size_t i = 0; i < model.nodes.size(); ++i) {
        const tinygltf::Node& node = model.nodes[i];
        NodePose& pose = poses[i];
        if (node.matrix.size() == 16) {
            pose.matrix = glm::make_mat4(node.matrix.data()); // both column-major
        }
        if (node.translation.size() == 3) pose.translation = glm::make_vec3(node.translation.data());
        if (node.rotation.size() == 4) {
            const std::vector<double>& xyzw = node.rotation; // stored x, y, z, w
            const std::optional<glm::dquat> unit = unitQuaternion(xyzw[0], xyzw[1], xyzw[2], xyzw[3]);
            if (!unit) {
                throwLoadError(path, "node " + std::to_string(i) +
                                         (node.name.empty() ? "" : " '" + excerptForMessage(node.name) + "'") +
                                         ": rotation [" + formatNumber(xyzw[0]) + ", " + formatNumber(xyzw[1]) + ", " +
                                         formatNumber(xyzw[2]) + ", " + formatNumber(xyzw[3]) +
                                         "] must be finite and of non-zero length");
            }
            pose.rotation = *unit;
        }
        if (node.scale.size() == 3) pose.scale = glm::make_vec3(node.scale.data());
        if (!node.weights.empty()) {
            pose.weights = node.weights;
        } else if (node.mesh >= 0 && std::size_t(node.mesh) < model.meshes.size()) {
            pose.weights = model.meshes[std::size_t(node.mesh)].weights;
        }
    }
    return poses;
}

std::size_t findAnimation(const std::string& path, const tinygltf::Model& model, const std::string& name) {
    for (std::size_t i = 0; i < model.animations.size(); ++i) {
        if (model.animations[i].name == name) return i;
    }
    // An index as text, for unnamed animations ("0"): digits only, so " 1" or "1.0" is not taken for one.
    if (!name.empty() && name.size() <= 9 && std::ranges::all_of(name, [](char c) { return c >= '0' && c <= '9'; })) {
        const std::size_t index = std::stoul(name);
        if (index < model.animations.size()) return index;
    }
    std::string known;
    for (std::size_t i = 0; i < model.animations.size() && i < kMaxListedAnimations; ++i) {
        const std::string& animationName = model.animations[i].name;
        known += (known.empty() ? "" : ", ") + std::to_string(i) +
                 (animationName.empty() ? "" : " '" + excerptForMessage(animationName) + "'");
    }
    if (model.animations.size() > kMaxListedAnimations) {
        known += " and " + std::to_string(model.animations.size() - kMaxListedAnimations) + " more";
    }
    // A name written as a VRM Animation file is a file that is not there (or not a file): say so, not only that the
    // model has no animation of that name.
    std::string extension = std::filesystem::path(name).extension().string();
    std::ranges::transform(extension, extension.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    std::error_code error;
    const std::string vrmaNote = extension != ".vrma" ? std::string()
                                 : std::filesystem::exists(name, error)
                                     ? "; as a VRM Animation file it is not a regular file"
                                     : "; no VRM Animation file is there either";
    throwLoadError(
        path, "no animation '" + excerptForMessage(name) + "' (" +
                  (model.animations.empty() ? std::string("the file has no animations") : "the file has " + known) +
                  ")" + vrmaNote);
}

std::vector<double> sampleCurve(const AnimationCurve& curve, double time) {
    const std::vector<float>& times = curve.times;
    if (!(time > times.front())) return elementAt(curve, 0); // before the first keyframe, or NaN
    if (time >= times.back()) return elementAt(curve, times.size() - 1);
    // The keyframe interval [times[key], times[key + 1]) holding `time`; its length is > 0 by construction.
    const std::size_t key = std::size_t(std::upper_bound(times.begin(), times.end(), time) - times.begin()) - 1;
    const double start = times[key];
    const double length = double(times[key + 1]) - start;
    const double t = (time - start) / length;
    std::vector<double> result(curve.components);
    switch (curve.interpolation) {
    case Interpolation::Step: return elementAt(curve, key);
    case Interpolation::Linear: {
        const float* a = keyElement(curve, key, 0);
        const float* b = keyElement(curve, key + 1, 0);
        if (curve.rotation) return slerpXyzw(a, b, t);
        for (std::size_t c = 0; c < curve.components; ++c) result[c] = (1.0 - t) * a[c] + t * b[c];
        return result;
    }
    case Interpolation::CubicSpline: {
        // Hermite spline (glTF Appendix C): value v, out-tangent b of this key; in-tangent a, value of the next,
        // tangents scaled by the interval's length.
        const float* value = keyElement(curve, key, 1);
        const float* outTangent = keyElement(curve, key, 2);
        const float* inTangent = keyElement(curve, key + 1, 0);
        const float* nextValue = keyElement(curve, key + 1, 1);
        const double t2 = t * t;
        const double t3 = t2 * t;
        for (std::size_t c = 0; c < curve.components; ++c) {
            result[c] = (2 * t3 - 3 * t2 + 1) * value[c] + length * (t3 - 2 * t2 + t) * outTangent[c] +
                        (-2 * t3 + 3 * t2) * nextValue[c] + length * (t3 - t2) * inTangent[c];
        }
        if (curve.rotation) normaliseQuaternion(result);
        return result;
    }
    }
    return result;
}

void applyAnimation(const std::string& path, const tinygltf::Model& model, std::size_t animationIndex, double time,
                    std::vector<NodePose>& poses, MeshBudget& budget, std::vector<Warning>& warnings) {
    const tinygltf::Animation& animation = model.animations[animationIndex];
    const std::string label = animationLabel(model, animationIndex);
    for (std::size_t c = 0; c < animation.channels.size(); ++c) {
        const tinygltf::AnimationChannel& channel = animation.channels[c];
        const std::string channelLabel = label + " channel " + std::to_string(c);
        if (channel.sampler < 0 || std::size_t(channel.sampler) >= animation.samplers.size()) {
            throwLoadError(path, channelLabel + ": sampler " + std::to_string(channel.sampler) +
                                     " out of range (the animation has " + std::to_string(animation.samplers.size()) +
                                     " samplers)");
        }
        const std::string& target = channel.target_path;
        if (target != "translation" && target != "rotation" && target != "scale" && target != "weights") {
            warnings.push_back(makeWarning(WarningKind::AnimationChannelIgnored,
                                           channelLabel + ": target path '" + excerptForMessage(target) + "' ignored",
                                           "", channelLabel));
            continue;
        }
        if (channel.target_node < 0) {
            continue; // glTF: a channel without a node is for an extension to interpret
        }
        if (std::size_t(channel.target_node) >= model.nodes.size()) {
            throwLoadError(path, channelLabel + ": node " + std::to_string(channel.target_node) +
                                     " out of range (file has " + std::to_string(model.nodes.size()) + " nodes)");
        }
        const tinygltf::Node& node = model.nodes[std::size_t(channel.target_node)];
        NodePose& pose = poses[std::size_t(channel.target_node)];
        if (pose.matrix && target != "weights") {
            warnings.push_back(makeWarning(WarningKind::AnimationChannelIgnored,
                                           channelLabel + ": node " + std::to_string(channel.target_node) +
                                               " has a matrix, which glTF does not let an animation target; channel "
                                               "ignored",
                                           "", channelLabel));
            continue;
        }
        const tinygltf::AnimationSampler& sampler = animation.samplers[std::size_t(channel.sampler)];
        const std::string samplerLabel = label + " sampler " + std::to_string(channel.sampler);
        if (target == "weights") {
            const std::size_t targets = morphTargetCount(model, node);
            if (targets == 0) {
                warnings.push_back(makeWarning(WarningKind::AnimationChannelIgnored,
                                               channelLabel + ": node " + std::to_string(channel.target_node) +
                                                   " has no morph targets; weights channel ignored",
                                               "", channelLabel));
                continue;
            }
            pose.weights = sampleCurve(
                readCurve(path, model, sampler, samplerLabel, TINYGLTF_TYPE_SCALAR, targets, false, budget), time);
            continue;
        }
        const bool rotation = target == "rotation";
        const std::vector<double> value = sampleCurve(readCurve(path, model, sampler, samplerLabel,
                                                                rotation ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3,
                                                                rotation ? 4 : 3, rotation, budget),
                                                      time);
        if (value.empty()) {
            throwLoadError(path, samplerLabel + ": its CUBICSPLINE rotation passes through zero at --time " +
                                     formatNumber(time) + ", which is no rotation (its tangents cancel its values)");
        }
        if (target == "translation") pose.translation = glm::dvec3(value[0], value[1], value[2]);
        if (target == "scale") pose.scale = glm::dvec3(value[0], value[1], value[2]);
        if (rotation) pose.rotation = glm::normalize(glm::dquat(value[3], value[0], value[1], value[2]));
    }
}

void applyMorphTargets(const std::string& path, const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                       const std::vector<double>& weights, std::vector<glm::vec3>& positions,
                       std::vector<glm::vec3>& normals, const std::string& meshLabel, std::vector<Warning>& warnings) {
    bool warnedOtherAttributes = false;
    bool movedNormals = false;
    for (std::size_t t = 0; t < primitive.targets.size() && t < weights.size(); ++t) {
        const double weight = weights[t];
        if (weight == 0.0 || !std::isfinite(weight)) continue;
        for (const auto& [attribute, accessor] : primitive.targets[t]) {
            const bool isPosition = attribute == "POSITION";
            const bool isNormal = attribute == "NORMAL";
            if (!isPosition && !isNormal) {
                // Tangents are not used; texture coordinate and colour targets would be, but are not applied yet.
                if (attribute != "TANGENT" && !warnedOtherAttributes) {
                    warnings.push_back(makeWarning(WarningKind::MorphAttributeIgnored,
                                                   quotedExcerpt(meshLabel) + ": morph target " + std::to_string(t) +
                                                       " moves " + excerptForMessage(attribute) +
                                                       ", which is not applied (only POSITION and NORMAL are)",
                                                   "", meshLabel));
                    warnedOtherAttributes = true;
                }
                continue;
            }
            std::vector<glm::vec3>& values = isPosition ? positions : normals;
            if (values.empty()) continue; // a NORMAL target on a primitive without normals: they are computed later
            const std::string role = quotedExcerpt(meshLabel) + " morph target " + std::to_string(t) + " " + attribute;
            const std::size_t count = accessorCount(path, model, accessor, TINYGLTF_TYPE_VEC3, role);
            if (count != values.size()) {
                throwLoadError(path, role + " has " + std::to_string(count) + " elements but POSITION has " +
                                         std::to_string(values.size()));
            }
            const std::vector<float> offsets = readAccessorFloats(path, model, accessor, TINYGLTF_TYPE_VEC3, role);
            for (std::size_t v = 0; v < values.size(); ++v) {
                const glm::dvec3 moved =
                    glm::dvec3(values[v]) + weight * glm::dvec3(offsets[3 * v], offsets[3 * v + 1], offsets[3 * v + 2]);
                if (!std::isfinite(moved.x) || !std::isfinite(moved.y) || !std::isfinite(moved.z)) {
                    throwLoadError(path, role + " at weight " + formatNumber(weight) + ": non-finite result");
                }
                values[v] = glm::vec3(moved);
            }
            movedNormals = movedNormals || isNormal;
        }
    }
    if (movedNormals) {
        for (glm::vec3& normal : normals) {
            const float length = glm::length(normal);
            normal = length > 0.0f ? normal / length : glm::vec3(0.0f);
        }
    }
}

std::vector<glm::dmat4>
jointMatrices(const std::string& path, const tinygltf::Model& model, int skinIndex,
              const std::function<glm::dmat4(int node, const glm::dmat4& inverseBind)>& jointMatrix,
              MeshBudget& budget) {
    if (skinIndex < 0 || std::size_t(skinIndex) >= model.skins.size()) {
        throwLoadError(path, "skin index " + std::to_string(skinIndex) + " out of range (file has " +
                                 std::to_string(model.skins.size()) + " skins)");
    }
    const tinygltf::Skin& skin = model.skins[std::size_t(skinIndex)];
    const std::string label =
        "skin " + std::to_string(skinIndex) + (skin.name.empty() ? "" : " '" + excerptForMessage(skin.name) + "'");
    std::vector<float> inverseBind;
    if (skin.inverseBindMatrices >= 0) {
        const std::string role = label + " inverseBindMatrices";
        const std::size_t count = accessorCount(path, model, skin.inverseBindMatrices, TINYGLTF_TYPE_MAT4, role);
        if (count < skin.joints.size()) {
            throwLoadError(path, role + ": " + std::to_string(count) + " matrices for " +
                                     std::to_string(skin.joints.size()) + " joints");
        }
        // glTF allows more matrices than joints; all are read, so all are checked (a sparse accessor without a buffer
        // view can declare any count).
        budget.checkBytes(count > SIZE_MAX / sizeof(glm::dmat4) - skin.joints.size()
                              ? SIZE_MAX
                              : (count + skin.joints.size()) * sizeof(glm::dmat4),
                          role);
        inverseBind = readAccessorFloats(path, model, skin.inverseBindMatrices, TINYGLTF_TYPE_MAT4, role);
    }
    std::vector<glm::dmat4> matrices;
    matrices.reserve(skin.joints.size());
    for (std::size_t j = 0; j < skin.joints.size(); ++j) {
        const int joint = skin.joints[j];
        if (joint < 0 || std::size_t(joint) >= model.nodes.size()) {
            throwLoadError(path, label + " joint " + std::to_string(j) + ": node index " + std::to_string(joint) +
                                     " out of range (file has " + std::to_string(model.nodes.size()) + " nodes)");
        }
        const glm::dmat4 bind =
            inverseBind.empty() ? glm::dmat4(1.0) : glm::dmat4(glm::make_mat4(inverseBind.data() + 16 * j));
        matrices.push_back(jointMatrix(joint, bind));
    }
    return matrices;
}

SkinBlend::SkinBlend(const std::string& path, const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                     std::size_t vertexCount, std::vector<glm::dmat4> joints, const glm::dmat4& fallback,
                     const std::string& meshLabel, const std::map<std::string, std::vector<float>>* decoded)
    : mJoints(std::move(joints)), mFallback(fallback) {
    const std::string label = quotedExcerpt(meshLabel);
    for (int set = 0;; ++set) {
        const auto jointsAttribute = primitive.attributes.find("JOINTS_" + std::to_string(set));
        const auto weightsAttribute = primitive.attributes.find("WEIGHTS_" + std::to_string(set));
        if (jointsAttribute == primitive.attributes.end() || weightsAttribute == primitive.attributes.end()) {
            if (set == 0) {
                throwLoadError(path, label + ": skinned, but the primitive has no JOINTS_0 and WEIGHTS_0");
            }
            break;
        }
        const std::string jointsRole = label + " " + jointsAttribute->first;
        const std::string weightsRole = label + " " + weightsAttribute->first;
        // A Draco primitive's decoded set (the decoder checked its count and component count); else the accessors.
        const auto decodedOf = [&](const std::string& attribute) -> const std::vector<float>* {
            if (!decoded) return nullptr;
            const auto found = decoded->find(attribute);
            return found != decoded->end() ? &found->second : nullptr;
        };
        const std::vector<float>* decodedJoints = decodedOf(jointsAttribute->first);
        const std::vector<float>* decodedWeights = decodedOf(weightsAttribute->first);
        for (const auto& [role, accessor, fromDraco] :
             {std::tuple{jointsRole, jointsAttribute->second, decodedJoints != nullptr},
              std::tuple{weightsRole, weightsAttribute->second, decodedWeights != nullptr}}) {
            const std::size_t count = accessorCount(path, model, accessor, TINYGLTF_TYPE_VEC4, role);
            if (count != vertexCount && !fromDraco) {
                throwLoadError(path, role + " has " + std::to_string(count) + " elements but POSITION has " +
                                         std::to_string(vertexCount));
            }
        }
        std::vector<std::uint32_t> jointOf;
        if (decodedJoints) {
            jointOf.reserve(decodedJoints->size());
            for (const float joint : *decodedJoints) {
                // JOINTS_n are unsigned integers; the decoder gives them as floats, exact below 2^24.
                jointOf.push_back(std::isfinite(joint) && joint >= 0.0f && joint < 16777216.0f
                                      ? std::uint32_t(joint)
                                      : std::numeric_limits<std::uint32_t>::max());
            }
        } else {
            jointOf = readAccessorIntegers(path, model, jointsAttribute->second, TINYGLTF_TYPE_VEC4, jointsRole);
        }
        const std::vector<float> weightOf =
            decodedWeights ? *decodedWeights
                           : readAccessorFloats(path, model, weightsAttribute->second, TINYGLTF_TYPE_VEC4, weightsRole);
        // Interleaved per vertex: the earlier sets' influences, then this one's four.
        std::vector<std::uint32_t> joined(vertexCount * (mInfluences + 4));
        std::vector<float> joinedWeights(joined.size());
        for (std::size_t v = 0; v < vertexCount; ++v) {
            for (std::size_t i = 0; i < mInfluences; ++i) {
                joined[v * (mInfluences + 4) + i] = mJointOf[v * mInfluences + i];
                joinedWeights[v * (mInfluences + 4) + i] = mWeightOf[v * mInfluences + i];
            }
            for (std::size_t i = 0; i < 4; ++i) {
                const std::uint32_t joint = jointOf[4 * v + i];
                const float weight = weightOf[4 * v + i];
                // A joint index with weight 0 has no effect; exporters leave 0 or junk there.
                if (weight != 0.0f && joint >= mJoints.size()) {
                    throwLoadError(path, jointsRole + " element " + std::to_string(v) + ": joint " +
                                             std::to_string(joint) + " out of range (the skin has " +
                                             std::to_string(mJoints.size()) + " joints)");
                }
                if (weight < 0.0f) {
                    throwLoadError(path, weightsRole + " element " + std::to_string(v) + ": negative weight " +
                                             formatNumber(weight));
                }
                joined[v * (mInfluences + 4) + mInfluences + i] = weight != 0.0f ? joint : 0;
                joinedWeights[v * (mInfluences + 4) + mInfluences + i] = weight;
            }
        }
        mJointOf = std::move(joined);
        mWeightOf = std::move(joinedWeights);
        mInfluences += 4;
    }
}

SkinBlend::WeightSums SkinBlend::weightSums() const {
    WeightSums sums;
    const std::size_t vertices = mInfluences == 0 ? 0 : mWeightOf.size() / mInfluences;
    for (std::size_t v = 0; v < vertices; ++v) {
        double total = 0.0;
        for (std::size_t i = 0; i < mInfluences; ++i) total += mWeightOf[v * mInfluences + i];
        if (std::abs(total - 1.0) <= kWeightSumTolerance) continue;
        if (sums.unnormalised + sums.zero == 0) {
            sums.firstVertex = v;
            sums.firstSum = total;
        }
        ++(total > 0.0 ? sums.unnormalised : sums.zero);
    }
    return sums;
}

glm::dmat4 SkinBlend::vertexMatrix(std::size_t vertex) const {
    double total = 0.0;
    for (std::size_t i = 0; i < mInfluences; ++i) total += mWeightOf[vertex * mInfluences + i];
    if (!(total > 0.0)) return mFallback;
    glm::dmat4 blended(0.0);
    for (std::size_t i = 0; i < mInfluences; ++i) {
        const double weight = mWeightOf[vertex * mInfluences + i];
        if (weight != 0.0) blended += (weight / total) * mJoints[mJointOf[vertex * mInfluences + i]];
    }
    return blended;
}

} // namespace inkgraph::detail
