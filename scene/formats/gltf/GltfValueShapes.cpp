/** @file The shapes of glTF's core values (GltfValueShapes.h). */

#include "scene/formats/gltf/GltfValueShapes.h"

#include "scene/MessageText.h"
#include "scene/formats/FormatReaders.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <optional>

namespace inkgraph::detail {

namespace {

/** How a value that is not what glTF wants there reads in a message: a string quoted, anything else as JSON. */
std::string valueForMessage(const nlohmann::json& value) {
    if (value.is_string()) return "the string " + quotedExcerpt(value.get<std::string>());
    return excerptForMessage(value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
}

/** Why `value` is not `count` finite numbers, or nothing when it is. */
std::optional<std::string> notNumbers(const nlohmann::json& value, std::size_t count) {
    const std::string wanted = std::to_string(count) + " numbers";
    if (!value.is_array()) return "is " + valueForMessage(value) + ", not " + wanted;
    if (value.size() != count)
        return "has " + std::to_string(value.size()) + (value.size() == 1 ? " value" : " values") + ", not " + wanted;
    for (std::size_t i = 0; i < count; ++i) {
        if (!value[i].is_number())
            return "[" + std::to_string(i) + "] is " + valueForMessage(value[i]) + ", not a number";
        if (!std::isfinite(value[i].get<double>()))
            return "[" + std::to_string(i) + "] is " + valueForMessage(value[i]) + ", not a finite number";
    }
    return std::nullopt;
}

/** The major and minor numbers of a version string ("2.0"), or nothing when it does not start with digits. */
std::optional<std::pair<long, long>> versionNumbers(const std::string& text) {
    const std::size_t dot = text.find('.');
    const std::string major = text.substr(0, dot);
    const std::string minor = dot == std::string::npos ? "0" : text.substr(dot + 1);
    const auto digits = [](const std::string& part) {
        return !part.empty() && part.size() <= 9 &&
               std::ranges::all_of(part, [](char c) { return c >= '0' && c <= '9'; });
    };
    if (!digits(major) || !digits(minor)) return std::nullopt;
    return std::pair{std::stol(major), std::stol(minor)};
}

void judgeVersions(const std::string& path, const nlohmann::json& document) {
    const auto asset = document.find("asset");
    if (asset == document.end() || !asset->is_object()) return; // tinygltf refuses a file without one
    for (const char* member : {"version", "minVersion"}) {
        const auto value = asset->find(member);
        if (value == asset->end()) continue;
        const std::string at = std::string("asset.") + member;
        // tinygltf refuses a number (2.0) as if the file had no asset.
        if (!value->is_string())
            throwLoadError(path, at + " is " + valueForMessage(*value) + ", not a string such as '2.0'");
        const std::string text = value->get<std::string>();
        const std::optional<std::pair<long, long>> numbers = versionNumbers(text);
        if (!numbers) throwLoadError(path, at + " is " + quotedExcerpt(text) + ", not a version such as '2.0'");
        // A reader of 2.0 reads every 2.x file (glTF keeps minor versions compatible) unless minVersion says more.
        const bool readable =
            member == std::string_view("version") ? numbers->first == 2 : *numbers <= std::pair<long, long>{2, 0};
        if (!readable) {
            throwLoadError(path, at + " is " + quotedExcerpt(text) +
                                     ": this reader reads glTF 2.0 (and later 2.x files that do not ask for more)");
        }
    }
}

/** tinygltf takes a top-level member that is not an array for an empty one: "materials": {...} was told as "material
 *  index 0 out of range (file has 0 materials)". */
void judgeTopLevelArrays(const std::string& path, const nlohmann::json& document) {
    for (const char* member : {"accessors", "animations", "buffers", "bufferViews", "cameras", "images", "materials",
                               "meshes", "nodes", "samplers", "scenes", "skins", "textures"}) {
        const auto value = document.find(member);
        if (value != document.end() && !value->is_array() && !value->is_null())
            throwLoadError(path, std::string(member) + " is " + valueForMessage(*value) + ", not an array");
    }
}

void judgeExtensionLists(const std::string& path, const nlohmann::json& document) {
    for (const char* member : {"extensionsRequired", "extensionsUsed"}) {
        const auto list = document.find(member);
        if (list == document.end()) continue;
        const bool names = list->is_array() && std::ranges::all_of(*list, [](const auto& e) { return e.is_string(); });
        if (!names) {
            throwLoadError(path, std::string(member) + " is " + valueForMessage(*list) +
                                     ", not an array of extension names (such as [\"KHR_texture_transform\"])");
        }
    }
}

/** tinygltf refuses a stride outside glTF's range as "must be the multiple of 4", even 512. */
void judgeBufferViews(const std::string& path, const nlohmann::json& document) {
    const auto views = document.find("bufferViews");
    if (views == document.end() || !views->is_array()) return;
    for (std::size_t i = 0; i < views->size(); ++i) {
        const nlohmann::json& view = (*views)[i];
        if (!view.is_object()) continue;
        const auto stride = view.find("byteStride");
        if (stride == view.end() || !stride->is_number_unsigned()) continue; // not an integer: refused already
        const std::uint64_t bytes = stride->get<std::uint64_t>();
        if (bytes < 4 || bytes > 252 || bytes % 4 != 0) {
            throwLoadError(path, "bufferViews[" + std::to_string(i) + "].byteStride is " + std::to_string(bytes) +
                                     ", not a multiple of 4 from 4 to 252 (glTF's strides)");
        }
    }
}

/** An object's "name" when it is a string, else "". */
std::string nameOf(const nlohmann::json& object) {
    const auto name = object.find("name");
    return name != object.end() && name->is_string() ? name->get<std::string>() : std::string();
}

/** The most morph targets any primitive of `mesh` has. */
std::size_t morphTargetCount(const nlohmann::json& mesh) {
    std::size_t count = 0;
    const auto primitives = mesh.find("primitives");
    if (primitives == mesh.end() || !primitives->is_array()) return 0;
    for (const nlohmann::json& primitive : *primitives) {
        if (!primitive.is_object()) continue;
        const auto targets = primitive.find("targets");
        if (targets != primitive.end() && targets->is_array()) count = std::max(count, targets->size());
    }
    return count;
}

/** MorphWeightsMismatched when `weights` (at `at`, its JSON pointer `pointer`) is not `targets` numbers; weights that
 *  are not an array of numbers are dropped (tinygltf would read them as none). */
void judgeWeights(const nlohmann::json& weights, std::size_t targets, const std::string& at, const std::string& pointer,
                  const std::string& item, ValueShapes& shapes) {
    const bool numbers =
        weights.is_array() && std::ranges::all_of(weights, [](const nlohmann::json& w) { return w.is_number(); });
    if (!numbers) {
        shapes.warnings.push_back(
            makeWarning(WarningKind::MorphWeightsMismatched,
                        at + " is " + valueForMessage(weights) + ", not an array of numbers; " +
                            (targets > 0 ? "read as no weights (the morph targets are not applied)" : "ignored"),
                        "", item));
        shapes.dropped.push_back(pointer);
        return;
    }
    if (weights.size() == targets) return;
    shapes.warnings.push_back(makeWarning(
        WarningKind::MorphWeightsMismatched,
        at + " has " + std::to_string(weights.size()) + " weights for " + std::to_string(targets) + " morph targets; " +
            (weights.size() < targets ? "the targets without one are not applied" : "the extra weights are ignored"),
        "", item));
}

void judgeNodes(const std::string& path, const nlohmann::json& document, ValueShapes& shapes) {
    const auto nodes = document.find("nodes");
    if (nodes == document.end() || !nodes->is_array()) return;
    const auto meshes = document.find("meshes");
    for (std::size_t i = 0; i < nodes->size(); ++i) {
        const nlohmann::json& node = (*nodes)[i];
        if (!node.is_object()) continue;
        const std::string at = "nodes[" + std::to_string(i) + "]";
        for (const auto& [member, count] :
             {std::pair{"matrix", 16}, {"translation", 3}, {"rotation", 4}, {"scale", 3}}) {
            const auto value = node.find(member);
            if (value == node.end()) continue;
            if (const std::optional<std::string> why = notNumbers(*value, std::size_t(count)))
                throwLoadError(path, at + "." + member + (why->front() == '[' ? "" : " ") + *why);
        }
        const auto matrix = node.find("matrix");
        if (matrix != node.end()) {
            // Column-major: the bottom row is elements 3, 7, 11 and 15. Exporters write it within float rounding.
            constexpr double kTolerance = 1e-5;
            const nlohmann::json& m = *matrix;
            const bool affine =
                std::abs(m[3].get<double>()) <= kTolerance && std::abs(m[7].get<double>()) <= kTolerance &&
                std::abs(m[11].get<double>()) <= kTolerance && std::abs(m[15].get<double>() - 1.0) <= kTolerance;
            if (!affine) {
                throwLoadError(path, at + ".matrix is projective: its bottom row is [" +
                                         formatNumber(m[3].get<double>()) + ", " + formatNumber(m[7].get<double>()) +
                                         ", " + formatNumber(m[11].get<double>()) + ", " +
                                         formatNumber(m[15].get<double>()) +
                                         "] (elements 3, 7, 11, 15), where glTF's affine nodes have [0, 0, 0, 1]");
            }
        }
        const auto weights = node.find("weights");
        const auto mesh = node.find("mesh");
        if (weights == node.end() || mesh == node.end() || !mesh->is_number_unsigned() || meshes == document.end() ||
            !meshes->is_array() || mesh->get<std::uint64_t>() >= meshes->size())
            continue;
        const nlohmann::json& meshObject = (*meshes)[mesh->get<std::size_t>()];
        if (meshObject.is_object())
            judgeWeights(*weights, morphTargetCount(meshObject), at + ".weights",
                         "/nodes/" + std::to_string(i) + "/weights", nameOf(node), shapes);
    }
    if (meshes == document.end() || !meshes->is_array()) return;
    for (std::size_t i = 0; i < meshes->size(); ++i) {
        const nlohmann::json& mesh = (*meshes)[i];
        if (!mesh.is_object()) continue;
        const auto weights = mesh.find("weights");
        if (weights != mesh.end())
            judgeWeights(*weights, morphTargetCount(mesh), "meshes[" + std::to_string(i) + "].weights",
                         "/meshes/" + std::to_string(i) + "/weights", nameOf(mesh), shapes);
    }
}

/** One material value's wanted shape: `count` numbers (0: one number), a string, or a boolean. */
struct MaterialValue {
    const char* object;   ///< the member holding it ("" for the material itself)
    const char* member;   ///< its name
    std::size_t count;    ///< numbers in the array, 0 for a single number
    char kind;            ///< 'n' numbers, 's' string, 'b' boolean
    const char* fallback; ///< tinygltf's default, as the message gives it
};

constexpr MaterialValue kMaterialValues[] = {
    {"pbrMetallicRoughness", "baseColorFactor", 4, 'n', "[1, 1, 1, 1]"},
    {"pbrMetallicRoughness", "metallicFactor", 0, 'n', "1"},
    {"pbrMetallicRoughness", "roughnessFactor", 0, 'n', "1"},
    {"normalTexture", "scale", 0, 'n', "1"},
    {"occlusionTexture", "strength", 0, 'n', "1"},
    {"", "emissiveFactor", 3, 'n', "[0, 0, 0]"},
    {"", "alphaMode", 0, 's', "OPAQUE"},
    {"", "alphaCutoff", 0, 'n', "0.5"},
    {"", "doubleSided", 0, 'b', "false"},
};

void judgeMaterials(const nlohmann::json& document, ValueShapes& shapes) {
    const auto materials = document.find("materials");
    if (materials == document.end() || !materials->is_array()) return;
    for (std::size_t i = 0; i < materials->size(); ++i) {
        const nlohmann::json& material = (*materials)[i];
        if (!material.is_object()) continue;
        const std::string at = "materials[" + std::to_string(i) + "]";
        const std::string name = nameOf(material);
        const std::string pointer = "/materials/" + std::to_string(i) + "/";
        for (const char* container : {"pbrMetallicRoughness", "normalTexture", "occlusionTexture"}) {
            const auto object = material.find(container);
            if (object == material.end() || object->is_object()) continue;
            shapes.warnings.push_back(makeWarning(WarningKind::MaterialValueInvalid,
                                                  at + "." + container + " is " + valueForMessage(*object) +
                                                      ", not an object; its defaults are used",
                                                  "", name));
            shapes.dropped.push_back(pointer + container);
        }
        for (const MaterialValue& wanted : kMaterialValues) {
            const nlohmann::json* holder = &material;
            std::string place = at + ".";
            if (*wanted.object != '\0') {
                const auto object = material.find(wanted.object);
                if (object == material.end() || !object->is_object()) continue; // said above
                holder = &*object;
                place += std::string(wanted.object) + ".";
            }
            const auto value = holder->find(wanted.member);
            if (value == holder->end()) continue;
            place += wanted.member;
            std::optional<std::string> why;
            if (wanted.kind == 'n' && wanted.count > 0) {
                why = notNumbers(*value, wanted.count);
                if (why && why->front() != '[') why = " " + *why;
            } else if (wanted.kind == 'n' && !value->is_number()) {
                why = " is " + valueForMessage(*value) + ", not a number";
            } else if (wanted.kind == 's' && !value->is_string()) {
                why = " is " + valueForMessage(*value) + ", not a string";
            } else if (wanted.kind == 'b' && !value->is_boolean()) {
                why = " is " + valueForMessage(*value) + ", not true or false";
            }
            if (why) {
                shapes.warnings.push_back(makeWarning(WarningKind::MaterialValueInvalid,
                                                      place + *why + "; the default " + wanted.fallback + " is used",
                                                      "", name));
                // tinygltf reads some such values as absent and refuses others (an emissiveFactor of 2 numbers).
                shapes.dropped.push_back(pointer + (*wanted.object != '\0' ? std::string(wanted.object) + "/" : "") +
                                         wanted.member);
            }
        }
    }
}

/** AnimationChannelIgnored for a channel whose target names no node: KHR_animation_pointer's ("path": "pointer"),
 *  which this reader does not read, or another extension's. tinygltf skips it, saying only that 'node' is missing. */
void judgeAnimationChannels(const nlohmann::json& document, ValueShapes& shapes) {
    const auto animations = document.find("animations");
    if (animations == document.end() || !animations->is_array()) return;
    for (std::size_t a = 0; a < animations->size(); ++a) {
        const nlohmann::json& animation = (*animations)[a];
        const auto channels = animation.is_object() ? animation.find("channels") : animation.end();
        if (!animation.is_object() || channels == animation.end() || !channels->is_array()) continue;
        for (std::size_t c = 0; c < channels->size(); ++c) {
            const nlohmann::json& channel = (*channels)[c];
            const auto target = channel.is_object() ? channel.find("target") : channel.end();
            if (!channel.is_object() || target == channel.end() || !target->is_object() || target->contains("node"))
                continue;
            const std::string at = "animations[" + std::to_string(a) + "].channels[" + std::to_string(c) + "]";
            const bool pointer = target->contains("extensions") && (*target)["extensions"].is_object() &&
                                 (*target)["extensions"].contains("KHR_animation_pointer");
            shapes.warnings.push_back(makeWarning(
                WarningKind::AnimationChannelIgnored,
                at + ": its target names no node (" +
                    (pointer ? std::string("a KHR_animation_pointer channel, which this reader does not read")
                             : std::string("another extension's channel")) +
                    "); ignored",
                "", at));
        }
    }
}

} // namespace

void judgeGlbHeader(const std::string& path, std::string_view content) {
    if (content.size() < 8) return; // tinygltf refuses a GLB too short for its header
    std::uint32_t version = 0;
    std::memcpy(&version, content.data() + 4, sizeof version);
    if (version != 2) {
        throwLoadError(path, "GLB header version " + std::to_string(version) +
                                 ", not 2 (glTF 2.0's binary form; version 1 is glTF 1.0's, which this reader does "
                                 "not read)");
    }
}

ValueShapes judgeValueShapes(const std::string& path, const nlohmann::json& document) {
    ValueShapes shapes;
    judgeVersions(path, document);
    judgeTopLevelArrays(path, document);
    judgeExtensionLists(path, document);
    judgeBufferViews(path, document);
    judgeNodes(path, document, shapes);
    judgeMaterials(document, shapes);
    judgeAnimationChannels(document, shapes);
    return shapes;
}

void dropValues(nlohmann::json& document, const std::vector<std::string>& pointers) {
    for (const std::string& text : pointers) {
        const nlohmann::json::json_pointer pointer(text);
        if (!document.contains(pointer)) continue;
        document.at(pointer.parent_pointer()).erase(pointer.back());
    }
}

} // namespace inkgraph::detail
