/** @file VRM expressions after specification/VRMC_vrm-1.0/expressions.md (binds, isBinary, the procedural overrides
 *  and their interaction with isBinary, the update algorithm), and VRM 0.x's blendShapeMaster read as 1.0 expressions
 *  the way UniVRM's migration and three-vrm's importer read it (preset names mapped, bind weights /100, materialValues
 *  by material name, _MainTex_ST as a texture transform). */

#include "scene/formats/gltf/VrmExpressions.h"

#include "scene/formats/FormatReaders.h"
#include "scene/formats/gltf/GltfPose.h"
#include "scene/formats/gltf/VrmMaterials.h"
#include "scene/formats/ShaderValues.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

namespace inkgraph::detail {

namespace {

/** VRM 1.0's preset names (expressions.md "Preset Expressions"). */
constexpr std::array<std::string_view, 18> kPresetNames = {
    "happy", "angry", "sad",       "relaxed",    "surprised", "aa",       "ih",       "ou",        "ee",
    "oh",    "blink", "blinkLeft", "blinkRight", "lookUp",    "lookDown", "lookLeft", "lookRight", "neutral"};

/** VRM 0.x presetName -> the 1.0 preset (UniVRM's migration, three-vrm's v0v1PresetNameMap). "unknown" maps to none:
 *  such a group is a custom expression under its own name. */
constexpr std::array<std::pair<std::string_view, std::string_view>, 17> kV0PresetNames = {{{"a", "aa"},
                                                                                           {"i", "ih"},
                                                                                           {"u", "ou"},
                                                                                           {"e", "ee"},
                                                                                           {"o", "oh"},
                                                                                           {"blink", "blink"},
                                                                                           {"joy", "happy"},
                                                                                           {"angry", "angry"},
                                                                                           {"sorrow", "sad"},
                                                                                           {"fun", "relaxed"},
                                                                                           {"lookup", "lookUp"},
                                                                                           {"lookdown", "lookDown"},
                                                                                           {"lookleft", "lookLeft"},
                                                                                           {"lookright", "lookRight"},
                                                                                           {"blink_l", "blinkLeft"},
                                                                                           {"blink_r", "blinkRight"},
                                                                                           {"neutral", "neutral"}}};

/** Expressions named one by one in a refusal; the rest are counted. */
constexpr std::size_t kMaxListedExpressions = 40;

bool isPreset(const std::string& name) {
    return std::ranges::find(kPresetNames, std::string_view(name)) != kPresetNames.end();
}

std::size_t morphTargetsOfMesh(const tinygltf::Model& model, int mesh) {
    if (mesh < 0 || std::size_t(mesh) >= model.meshes.size()) return 0;
    const tinygltf::Mesh& primitives = model.meshes[std::size_t(mesh)];
    return primitives.primitives.empty() ? 0 : primitives.primitives[0].targets.size();
}

/** The scale and offset of a uv transform T * R * S, and its unit axes (R's columns), so that a new scale and offset
 *  keep its rotation. */
struct UvPlacement {
    glm::dvec2 scale{1.0};
    glm::dvec2 offset{0.0};
    glm::dvec2 axisU{1.0, 0.0};
    glm::dvec2 axisV{0.0, 1.0};
};

UvPlacement placementOf(const glm::mat3& transform) {
    UvPlacement placement;
    const glm::dvec2 columnU(transform[0][0], transform[0][1]);
    const glm::dvec2 columnV(transform[1][0], transform[1][1]);
    placement.scale = {glm::length(columnU), glm::length(columnV)};
    placement.offset = {transform[2][0], transform[2][1]};
    // A zero scale (a meter drawn empty) has no direction of its own: it takes the other axis's, turned.
    if (placement.scale.y > 0.0) placement.axisV = columnV / placement.scale.y;
    placement.axisU =
        placement.scale.x > 0.0 ? columnU / placement.scale.x : glm::dvec2(placement.axisV.y, -placement.axisV.x);
    if (placement.scale.y == 0.0) placement.axisV = glm::dvec2(-placement.axisU.y, placement.axisU.x);
    return placement;
}

/** In double: an offset a whole number of repeats away keeps its fraction until the texture's wrap reduces it
 *  (shaderTextureTransform()). */
glm::dmat3 transformOf(const UvPlacement& placement) {
    glm::dmat3 transform(1.0);
    transform[0] = glm::dvec3(placement.axisU * placement.scale.x, 0.0);
    transform[1] = glm::dvec3(placement.axisV * placement.scale.y, 0.0);
    transform[2] = glm::dvec3(placement.offset, 1.0);
    return transform;
}

/** A bind's target colour with each channel in [0, 1], where the file's own colours are kept (shaderValue()); one
 *  outside it is clamped with a value-out-of-range warning naming `at`. */
glm::dvec4 clampedTarget(const std::vector<double>& value, const std::string& at, const std::string& path,
                         std::vector<Warning>& warnings) {
    glm::dvec4 target;
    std::vector<Warning> problems;
    for (int channel = 0; channel < 4; ++channel)
        target[channel] = shaderValue(value[std::size_t(channel)], ShaderRange{0.0, 1.0},
                                      at + ".targetValue[" + std::to_string(channel) + "]", problems);
    for (Warning& problem : problems) {
        problem.file = path;
        warnings.push_back(std::move(problem));
    }
    return target;
}

/** An expression's `isBinary`: absent is false; a value other than true or false is said through `warn(key, problem)`
 *  and read as false, the specification's default. */
template <typename Warn>
bool isBinaryOf(const tinygltf::Value& expression, const Warn& warn) {
    const tinygltf::Value* value = jsonMember(&expression, "isBinary");
    if (value == nullptr) return false;
    if (value->IsBool()) return value->Get<bool>();
    warn("isBinary", std::string(jsonTypeName(*value)) + ", not true or false; read as false");
    return false;
}

/** A bind's `weight`: absent is `fallback`; a value that is not a finite number is said through `warn(key, problem)`
 *  and read as `fallback` (a string "50" was taken silently as the full weight). */
template <typename Warn>
double bindWeightOf(const tinygltf::Value& bind, double fallback, const Warn& warn) {
    const tinygltf::Value* value = jsonMember(&bind, "weight");
    if (value == nullptr) return fallback;
    if (const std::optional<double> weight = jsonNumber(value)) return *weight;
    warn("weight", (value->IsNumber() ? std::string("not finite") : std::string(jsonTypeName(*value))) +
                       ", not a number; read as " + formatNumber(fallback));
    return fallback;
}

} // namespace

const tinygltf::Value* jsonMember(const tinygltf::Value* object, const char* key) {
    if (object == nullptr || !object->IsObject() || !object->Has(key)) return nullptr;
    return &object->Get(key);
}

std::optional<double> jsonNumber(const tinygltf::Value* value) {
    if (value == nullptr || !value->IsNumber()) return std::nullopt;
    const double number = value->GetNumberAsDouble();
    return std::isfinite(number) ? std::optional<double>(number) : std::nullopt;
}

std::optional<int> jsonIndex(const tinygltf::Value* value) {
    const std::optional<double> number = jsonNumber(value);
    if (!number || *number < 0.0 || *number > 1e9 || *number != std::floor(*number)) return std::nullopt;
    return int(*number);
}

const char* jsonTypeName(const tinygltf::Value& value) {
    if (value.IsNumber()) return "a number";
    if (value.IsString()) return "a string";
    if (value.IsBool()) return "a boolean";
    if (value.IsArray()) return "an array";
    if (value.IsObject()) return "an object";
    return "null";
}

std::string jsonString(const tinygltf::Value* value) {
    return value != nullptr && value->IsString() ? value->Get<std::string>() : std::string();
}

/** `count` finite numbers, or none. */
std::optional<std::vector<double>> jsonNumbers(const tinygltf::Value* value, std::size_t count) {
    if (value == nullptr || !value->IsArray() || value->ArrayLen() != count) return std::nullopt;
    std::vector<double> numbers;
    for (std::size_t i = 0; i < count; ++i) {
        const std::optional<double> number = jsonNumber(&value->Get(int(i)));
        if (!number) return std::nullopt;
        numbers.push_back(*number);
    }
    return numbers;
}

VrmExpressions::VrmExpressions(const std::string& path, const tinygltf::Model& model, std::vector<Warning>& warnings)
    : mPath(path) {
    readVrm1(model, warnings);
    if (mExpressions.empty()) readVrm0(model, warnings);
}

void VrmExpressions::readVrm1(const tinygltf::Model& model, std::vector<Warning>& warnings) {
    const auto extension = model.extensions.find("VRMC_vrm");
    if (extension == model.extensions.end()) return;
    const tinygltf::Value* expressions = jsonMember(&extension->second, "expressions");
    const auto warn = [&](const std::string& where, const std::string& problem) {
        warnings.push_back(makeWarning(WarningKind::VrmPropertyInvalid,
                                       "VRMC_vrm.expressions." + where + ": " + problem + "; left out", mPath, where));
    };
    // A value taken as its default: `problem` says what it was and what it is read as.
    const auto readAs = [&](const std::string& where, const std::string& problem) {
        warnings.push_back(makeWarning(WarningKind::VrmPropertyInvalid,
                                       "VRMC_vrm.expressions." + where + ": " + problem, mPath, where));
    };
    const auto overrideOf = [&](const tinygltf::Value* object, const char* key, const std::string& where) {
        const std::string mode = jsonString(jsonMember(object, key));
        if (mode == "block") return Override::Block;
        if (mode == "blend") return Override::Blend;
        if (!mode.empty() && mode != "none")
            warn(where + "." + key, quotedExcerpt(mode) + " is not 'none', 'block' or 'blend'");
        return Override::None;
    };
    for (const char* section : {"preset", "custom"}) {
        const tinygltf::Value* group = jsonMember(expressions, section);
        if (group == nullptr || !group->IsObject()) continue;
        for (const std::string& name : group->Keys()) {
            const std::string where = std::string(section) + "." + excerptForMessage(name);
            const bool preset = std::string_view(section) == "preset";
            if (preset != isPreset(name)) {
                warn(where, preset ? "not a preset name" : "a custom expression may not take a preset's name");
                continue;
            }
            const tinygltf::Value& object = group->Get(name);
            Expression expression;
            expression.name = name;
            expression.isBinary = isBinaryOf(
                object, [&](const char* key, const std::string& problem) { readAs(where + "." + key, problem); });
            expression.overrideBlink = overrideOf(&object, "overrideBlink", where);
            expression.overrideLookAt = overrideOf(&object, "overrideLookAt", where);
            expression.overrideMouth = overrideOf(&object, "overrideMouth", where);
            if (const tinygltf::Value* binds = jsonMember(&object, "morphTargetBinds"); binds && binds->IsArray()) {
                for (std::size_t i = 0; i < binds->ArrayLen(); ++i) {
                    const tinygltf::Value& bind = binds->Get(int(i));
                    const std::string at = where + ".morphTargetBinds[" + std::to_string(i) + "]";
                    const std::optional<int> node = jsonIndex(jsonMember(&bind, "node"));
                    const std::optional<int> index = jsonIndex(jsonMember(&bind, "index"));
                    if (!node || !index || std::size_t(*node) >= model.nodes.size()) {
                        warn(at, "no node of the file and morph target index");
                        continue;
                    }
                    const std::size_t targets = morphTargetsOfMesh(model, model.nodes[std::size_t(*node)].mesh);
                    if (std::size_t(*index) >= targets) {
                        warn(at, "node " + std::to_string(*node) + "'s mesh has " + std::to_string(targets) +
                                     " morph targets, not " + std::to_string(*index + 1));
                        continue;
                    }
                    const double weight = bindWeightOf(bind, 1.0, [&](const char* key, const std::string& problem) {
                        readAs(at + "." + key, problem);
                    });
                    expression.morphBinds.push_back({*node, std::size_t(*index), weight});
                }
            }
            if (const tinygltf::Value* binds = jsonMember(&object, "materialColorBinds"); binds && binds->IsArray()) {
                static const std::array<std::pair<std::string_view, ColorTarget>, 6> kTypes = {
                    {{"color", ColorTarget::Color},
                     {"emissionColor", ColorTarget::EmissionColor},
                     {"shadeColor", ColorTarget::ShadeColor},
                     {"matcapColor", ColorTarget::MatcapColor},
                     {"rimColor", ColorTarget::RimColor},
                     {"outlineColor", ColorTarget::OutlineColor}}};
                for (std::size_t i = 0; i < binds->ArrayLen(); ++i) {
                    const tinygltf::Value& bind = binds->Get(int(i));
                    const std::string at = where + ".materialColorBinds[" + std::to_string(i) + "]";
                    const std::optional<int> material = jsonIndex(jsonMember(&bind, "material"));
                    const std::string type = jsonString(jsonMember(&bind, "type"));
                    const auto known = std::ranges::find(kTypes, std::string_view(type),
                                                         &std::pair<std::string_view, ColorTarget>::first);
                    const std::optional<std::vector<double>> value = jsonNumbers(jsonMember(&bind, "targetValue"), 4);
                    if (!material || std::size_t(*material) >= model.materials.size() || known == kTypes.end() ||
                        !value) {
                        warn(at, "needs a material of the file, a known type and a targetValue of 4 numbers");
                        continue;
                    }
                    expression.colorBinds.push_back(
                        {*material, known->second,
                         clampedTarget(*value, "VRMC_vrm.expressions." + at, mPath, warnings)});
                }
            }
            if (const tinygltf::Value* binds = jsonMember(&object, "textureTransformBinds");
                binds && binds->IsArray()) {
                for (std::size_t i = 0; i < binds->ArrayLen(); ++i) {
                    const tinygltf::Value& bind = binds->Get(int(i));
                    const std::string at = where + ".textureTransformBinds[" + std::to_string(i) + "]";
                    const std::optional<int> material = jsonIndex(jsonMember(&bind, "material"));
                    const tinygltf::Value* scaleValue = jsonMember(&bind, "scale");
                    const tinygltf::Value* offsetValue = jsonMember(&bind, "offset");
                    const auto scale = scaleValue ? jsonNumbers(scaleValue, 2) : std::vector<double>{1.0, 1.0};
                    const auto offset = offsetValue ? jsonNumbers(offsetValue, 2) : std::vector<double>{0.0, 0.0};
                    if (!material || std::size_t(*material) >= model.materials.size() || !scale || !offset) {
                        warn(at, "needs a material of the file, and a scale and offset of 2 numbers each");
                        continue;
                    }
                    expression.textureBinds.push_back(
                        {*material, {(*scale)[0], (*scale)[1]}, {(*offset)[0], (*offset)[1]}});
                }
            }
            mExpressions.push_back(std::move(expression));
        }
    }
}

void VrmExpressions::readVrm0(const tinygltf::Model& model, std::vector<Warning>& warnings) {
    const auto extension = model.extensions.find("VRM");
    if (extension == model.extensions.end()) return;
    const tinygltf::Value* groups = jsonMember(jsonMember(&extension->second, "blendShapeMaster"), "blendShapeGroups");
    if (groups == nullptr || !groups->IsArray()) return;
    for (std::size_t g = 0; g < groups->ArrayLen(); ++g) {
        const tinygltf::Value& group = groups->Get(int(g));
        const std::string where = "blendShapeGroups[" + std::to_string(g) + "]";
        const auto warn = [&](const std::string& at, const std::string& problem) {
            warnings.push_back(makeWarning(WarningKind::VrmPropertyInvalid,
                                           "VRM.blendShapeMaster." + at + ": " + problem + "; left out", mPath, at));
        };
        const auto readAs = [&](const std::string& at, const std::string& problem) {
            warnings.push_back(
                makeWarning(WarningKind::VrmPropertyInvalid, "VRM.blendShapeMaster." + at + ": " + problem, mPath, at));
        };
        Expression expression;
        expression.groupName = jsonString(jsonMember(&group, "name"));
        const std::string preset = jsonString(jsonMember(&group, "presetName"));
        const auto mapped = std::ranges::find(kV0PresetNames, std::string_view(preset),
                                              &std::pair<std::string_view, std::string_view>::first);
        expression.name = mapped != kV0PresetNames.end() ? std::string(mapped->second) : expression.groupName;
        if (expression.name.empty()) {
            warn(where, "a group without a name or preset");
            continue;
        }
        if (has(expression.name)) {
            warn(where, "a second group for " + quotedExcerpt(expression.name));
            continue;
        }
        if (expression.groupName == expression.name) expression.groupName.clear();
        expression.isBinary =
            isBinaryOf(group, [&](const char* key, const std::string& problem) { readAs(where + "." + key, problem); });
        if (const tinygltf::Value* binds = jsonMember(&group, "binds"); binds && binds->IsArray()) {
            for (std::size_t i = 0; i < binds->ArrayLen(); ++i) {
                const tinygltf::Value& bind = binds->Get(int(i));
                const std::string at = where + ".binds[" + std::to_string(i) + "]";
                const std::optional<int> mesh = jsonIndex(jsonMember(&bind, "mesh"));
                const std::optional<int> index = jsonIndex(jsonMember(&bind, "index"));
                if (!mesh || !index || std::size_t(*index) >= morphTargetsOfMesh(model, *mesh)) {
                    warn(at, "no mesh of the file with that morph target");
                    continue;
                }
                // 0.x weights run to 100 (Unity's blend shape weights).
                const double weight = bindWeightOf(bind, 100.0,
                                                   [&](const char* key, const std::string& problem) {
                                                       readAs(at + "." + key, problem);
                                                   }) /
                                      100.0;
                // A 0.x bind names the mesh: every node that shows it moves.
                for (std::size_t node = 0; node < model.nodes.size(); ++node) {
                    if (model.nodes[node].mesh == *mesh)
                        expression.morphBinds.push_back({int(node), std::size_t(*index), weight});
                }
            }
        }
        if (const tinygltf::Value* values = jsonMember(&group, "materialValues"); values && values->IsArray()) {
            static const std::array<std::pair<std::string_view, ColorTarget>, 5> kProperties = {
                {{"_Color", ColorTarget::Color},
                 {"_EmissionColor", ColorTarget::EmissionColor},
                 {"_ShadeColor", ColorTarget::ShadeColor},
                 {"_RimColor", ColorTarget::RimColor},
                 {"_OutlineColor", ColorTarget::OutlineColor}}};
            for (std::size_t i = 0; i < values->ArrayLen(); ++i) {
                const tinygltf::Value& value = values->Get(int(i));
                const std::string at = where + ".materialValues[" + std::to_string(i) + "]";
                const std::string materialName = jsonString(jsonMember(&value, "materialName"));
                const std::string property = jsonString(jsonMember(&value, "propertyName"));
                const std::optional<std::vector<double>> target = jsonNumbers(jsonMember(&value, "targetValue"), 4);
                const auto color = std::ranges::find(kProperties, std::string_view(property),
                                                     &std::pair<std::string_view, ColorTarget>::first);
                if (!target || (color == kProperties.end() && property != "_MainTex_ST")) {
                    warn(at, "property " + quotedExcerpt(property) +
                                 " is not applied (only _Color, _EmissionColor, _ShadeColor, _RimColor, "
                                 "_OutlineColor and _MainTex_ST, with a targetValue of 4 numbers)");
                    continue;
                }
                bool found = false;
                for (std::size_t material = 0; material < model.materials.size(); ++material) {
                    if (model.materials[material].name != materialName) continue;
                    found = true;
                    const std::vector<double>& v = *target;
                    if (color != kProperties.end()) {
                        // 0.x colours are Unity's gamma-space values, as the 0.x materials read them.
                        const glm::dvec4 gamma = clampedTarget(v, "VRM.blendShapeMaster." + at, mPath, warnings);
                        expression.colorBinds.push_back(
                            {int(material), color->second,
                             glm::dvec4(srgbToLinear(float(gamma[0])), srgbToLinear(float(gamma[1])),
                                        srgbToLinear(float(gamma[2])), gamma[3])});
                    } else {
                        // Unity's _ST is (scale u, scale v, offset u, offset v) with v up the image; glTF's v runs down
                        // it, so the offset becomes 1 - scale v - offset v (three-vrm's conversion).
                        expression.textureBinds.push_back({int(material), {v[0], v[1]}, {v[2], 1.0 - v[3] - v[1]}});
                    }
                }
                if (!found) warn(at, "no material named " + quotedExcerpt(materialName));
            }
        }
        mExpressions.push_back(std::move(expression));
    }
}

std::optional<std::size_t> VrmExpressions::indexOf(const std::string& name) const {
    // A 1.0 name first: a 0.x group may be named like another group's preset ("Blink" is not "blink").
    for (std::size_t i = 0; i < mExpressions.size(); ++i)
        if (mExpressions[i].name == name) return i;
    for (std::size_t i = 0; i < mExpressions.size(); ++i)
        if (!mExpressions[i].groupName.empty() && mExpressions[i].groupName == name) return i;
    return std::nullopt;
}

bool VrmExpressions::has(const std::string& name) const { return indexOf(name).has_value(); }

std::string VrmExpressions::canonicalName(const std::string& name) const {
    const std::optional<std::size_t> found = indexOf(name);
    return found ? mExpressions[*found].name : name;
}

std::string VrmExpressions::listForMessage() const {
    std::string list;
    for (std::size_t i = 0; i < mExpressions.size() && i < kMaxListedExpressions; ++i) {
        const Expression& expression = mExpressions[i];
        list += (i == 0 ? "" : ", ") + quotedExcerpt(expression.name);
        if (!expression.groupName.empty()) list += " (0.x " + quotedExcerpt(expression.groupName) + ")";
    }
    if (mExpressions.size() > kMaxListedExpressions)
        list += " and " + std::to_string(mExpressions.size() - kMaxListedExpressions) + " more";
    return list;
}

void VrmExpressions::setWeight(const std::string& name, double weight, const std::string& origin) {
    const std::optional<std::size_t> found = indexOf(name);
    if (!found) {
        throwLoadError(mPath, origin + ": no expression " + quotedExcerpt(name) +
                                  " (names are case-sensitive; the file has " + listForMessage() + ")");
    }
    mExpressions[*found].weight = std::clamp(weight, 0.0, 1.0);
}

VrmExpressions::Procedural VrmExpressions::proceduralOf(const std::string& name) {
    if (name == "blink" || name == "blinkLeft" || name == "blinkRight") return Procedural::Blink;
    if (name == "lookUp" || name == "lookDown" || name == "lookLeft" || name == "lookRight") return Procedural::LookAt;
    if (name == "aa" || name == "ih" || name == "ou" || name == "ee" || name == "oh") return Procedural::Mouth;
    return Procedural::None;
}

double VrmExpressions::outputOf(const Expression& expression) const {
    if (expression.isBinary) return expression.weight > 0.5 ? 1.0 : 0.0;
    return expression.weight;
}

double VrmExpressions::appliedWeightOf(const Expression& expression) const {
    const double output = outputOf(expression);
    const Procedural kind = proceduralOf(expression.name);
    if (kind == Procedural::None || output == 0.0) return output;
    // The overrides of every expression of another kind add up (block: 1 while it shows at all; blend: its output,
    // the binary output for an isBinary one); what is left of 1 scales this one.
    double amount = 0.0;
    for (const Expression& other : mExpressions) {
        if (proceduralOf(other.name) == kind) continue; // an override of its own kind is invalid
        const Override mode = kind == Procedural::Blink    ? other.overrideBlink
                              : kind == Procedural::LookAt ? other.overrideLookAt
                                                           : other.overrideMouth;
        const double otherOutput = outputOf(other);
        if (mode == Override::Block) amount += otherOutput > 0.0 ? 1.0 : 0.0;
        if (mode == Override::Blend) amount += otherOutput;
    }
    const double factor = 1.0 - std::clamp(amount, 0.0, 1.0);
    // An overridden isBinary expression may show only 0 or 1: any override suppresses it entirely.
    if (expression.isBinary && factor < 1.0) return 0.0;
    return output * factor;
}

double VrmExpressions::appliedWeight(const std::string& name) const {
    const std::optional<std::size_t> found = indexOf(name);
    return found ? appliedWeightOf(mExpressions[*found]) : 0.0;
}

void VrmExpressions::applyToPoses(std::vector<NodePose>& poses) const {
    for (const Expression& expression : mExpressions) {
        for (const MorphBind& bind : expression.morphBinds) {
            std::vector<double>& weights = poses[std::size_t(bind.node)].weights;
            if (weights.size() <= bind.target) weights.resize(bind.target + 1, 0.0);
            weights[bind.target] = 0.0;
        }
    }
    for (const Expression& expression : mExpressions) {
        const double applied = appliedWeightOf(expression);
        if (applied == 0.0) continue;
        for (const MorphBind& bind : expression.morphBinds)
            poses[std::size_t(bind.node)].weights[bind.target] += bind.weight * applied;
    }
}

void VrmExpressions::applyToMaterial(int materialIndex, Material& material, std::vector<Warning>& warnings) const {
    const Material own = material;
    std::vector<TextureRef*> uvTextures = {&material.baseColorTexture, &material.metallicRoughnessTexture,
                                           &material.emissiveTexture, &material.normalTexture};
    if (material.mtoon) {
        // Every texture MToon samples by uv; the matcap is sampled by the normal and keeps its place.
        MToonMaterial& mtoon = *material.mtoon;
        uvTextures.insert(uvTextures.end(),
                          {&mtoon.shadeMultiplyTexture, &mtoon.shadingShiftTexture, &mtoon.rimMultiplyTexture,
                           &mtoon.outlineWidthMultiplyTexture, &mtoon.uvAnimationMaskTexture});
    }
    std::vector<UvPlacement> ownPlacements;
    for (TextureRef* texture : uvTextures) ownPlacements.push_back(placementOf(texture->transform));
    std::vector<UvPlacement> placements = ownPlacements;
    bool moved = false;
    bool coloured = false;

    for (const Expression& expression : mExpressions) {
        const double applied = appliedWeightOf(expression);
        if (applied == 0.0) continue;
        for (const ColorBind& bind : expression.colorBinds) {
            if (bind.material != materialIndex) continue;
            coloured = true;
            const auto toward = [&](glm::vec3& value, const glm::vec3& base) {
                value += glm::vec3((glm::dvec3(bind.value) - glm::dvec3(base)) * applied);
            };
            switch (bind.target) {
            case ColorTarget::Color:
                material.baseColorFactor += glm::vec4((bind.value - glm::dvec4(own.baseColorFactor)) * applied);
                break;
            case ColorTarget::EmissionColor: toward(material.emissiveFactor, own.emissiveFactor); break;
            case ColorTarget::ShadeColor:
                if (material.mtoon) toward(material.mtoon->shadeColorFactor, own.mtoon->shadeColorFactor);
                break;
            case ColorTarget::MatcapColor:
                if (material.mtoon) toward(material.mtoon->matcapFactor, own.mtoon->matcapFactor);
                break;
            case ColorTarget::RimColor:
                if (material.mtoon)
                    toward(material.mtoon->parametricRimColorFactor, own.mtoon->parametricRimColorFactor);
                break;
            case ColorTarget::OutlineColor:
                if (material.mtoon) toward(material.mtoon->outlineColorFactor, own.mtoon->outlineColorFactor);
                break;
            }
        }
        for (const TextureBind& bind : expression.textureBinds) {
            if (bind.material != materialIndex) continue;
            moved = true;
            for (std::size_t i = 0; i < placements.size(); ++i) {
                placements[i].scale += (bind.scale - ownPlacements[i].scale) * applied;
                placements[i].offset += (bind.offset - ownPlacements[i].offset) * applied;
            }
        }
    }
    // Colours stay where the shaders take them (a sum of several expressions may overshoot): the base colour in
    // [0, 1], the others not negative.
    if (coloured) {
        material.baseColorFactor = glm::clamp(material.baseColorFactor, 0.0f, 1.0f);
        material.emissiveFactor = glm::max(material.emissiveFactor, 0.0f);
    }
    if (coloured && material.mtoon) {
        MToonMaterial& mtoon = *material.mtoon;
        for (glm::vec3* factor :
             {&mtoon.shadeColorFactor, &mtoon.matcapFactor, &mtoon.parametricRimColorFactor, &mtoon.outlineColorFactor})
            *factor = glm::max(*factor, 0.0f);
    }
    if (!moved) return;
    // Each texture's offset reduced by its own wrap, as a file's KHR_texture_transform is; a transform float cannot
    // resolve leaves the texture where the material puts it, with a warning once for the material (a huge scale drew
    // the textures black without a word, a repeat offset of 1e7 + 0.875 as one flat colour).
    std::string dropped;
    for (std::size_t i = 0; i < uvTextures.size(); ++i) {
        if (!uvTextures[i]->present()) continue;
        std::string problem;
        if (const std::optional<glm::mat3> transform =
                shaderTextureTransform(transformOf(placements[i]), uvTextures[i]->sampler, problem))
            uvTextures[i]->transform = *transform;
        else if (dropped.empty())
            dropped = problem;
    }
    if (!dropped.empty() && mMaterialsWarnedOf.insert(materialIndex).second) {
        const std::string item = "materials[" + std::to_string(materialIndex) + "]";
        warnings.push_back(makeWarning(WarningKind::TextureTransformDropped,
                                       "the expressions' texture transform on material " +
                                           (material.name.empty() ? item : quotedExcerpt(material.name)) + ": " +
                                           dropped + "; the textures are drawn without it",
                                       mPath, item));
    }
}

} // namespace inkgraph::detail
