#pragma once
/** @file A VRM character's expressions (VRM 1.0 VRMC_vrm.expressions, VRM 0.x VRM.blendShapeMaster) at the weights
 *  LoadOptions::expressions gives: their morph target binds onto the posed nodes' weights, their material colour and
 *  texture transform binds onto the materials, after isBinary and the 1.0 override rules (overrideBlink,
 *  overrideLookAt, overrideMouth) as specification/VRMC_vrm-1.0/expressions.md defines them. docs/vrm.md describes
 *  what is read and how. Internal to the glTF reader. */

#include "scene/Material.h"
#include "scene/Warning.h"

#include <glm/glm.hpp>

#include <cstddef>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace tinygltf {
class Model;
class Value;
} // namespace tinygltf

namespace inkgraph::detail {

struct NodePose;

/** `object`'s member `key`, or null when `object` is null, not an object, or lacks it (VRM's JSON, read leniently). */
const tinygltf::Value* jsonMember(const tinygltf::Value* object, const char* key);
/** A finite number, or none (absent, not a number, non-finite). */
std::optional<double> jsonNumber(const tinygltf::Value* value);
/** A whole number in [0, 1e9] (an index), or none. */
std::optional<int> jsonIndex(const tinygltf::Value* value);
/** What a JSON value is, for messages: "a number", "a string", "a boolean", "an array", "an object" or "null". */
const char* jsonTypeName(const tinygltf::Value& value);
/** A string, or "" for anything else. */
std::string jsonString(const tinygltf::Value* value);
/** An array of exactly `count` finite numbers, or none. */
std::optional<std::vector<double>> jsonNumbers(const tinygltf::Value* value, std::size_t count);

class VrmExpressions {
public:
    /** The file's expressions, every weight 0 (none for a file without VRM expressions: empty()). A bind that points
     *  at a node, mesh, morph target or material the file lacks is left out with a warning. */
    VrmExpressions(const std::string& path, const tinygltf::Model& model, std::vector<Warning>& warnings);

    bool empty() const { return mExpressions.empty(); }
    /** Whether `name` is an expression of the file: its 1.0 name (a 0.x group's 1.0 preset name when it has one) or
     *  a 0.x group's own name. Case-sensitive. */
    bool has(const std::string& name) const;
    /** Sets expression `name`'s weight (in [0, 1]); a name the file lacks throws SceneError through throwLoadError()
     *  naming `origin` (the flag that asked) and listing the expressions the file has. */
    void setWeight(const std::string& name, double weight, const std::string& origin);
    /** The 1.0 name of expression `name` (a 0.x group's preset), or `name` when the file lacks it. */
    std::string canonicalName(const std::string& name) const;
    /** The weight `name`'s binds take: its weight, snapped to 0 or 1 when isBinary, attenuated by the overrides of
     *  the others when it is a blink, look or mouth preset. */
    double appliedWeight(const std::string& name) const;

    /** Every morph target an expression binds is set to 0, then each bind adds its weight x its expression's applied
     *  weight (the specification's update algorithm); `poses` are the nodes' (NodePose::weights). */
    void applyToPoses(std::vector<NodePose>& poses) const;
    /** The colour and texture transform binds on glTF material `materialIndex`: each bound value moves from the
     *  material's own towards the bind's target by the applied weight, the moves of several expressions added. A
     *  texture transform float cannot resolve after the texture's wrap reduces its offset is left out, with a
     *  texture-transform-dropped warning in `warnings` once for the material. */
    void applyToMaterial(int materialIndex, Material& material, std::vector<Warning>& warnings) const;

    /** "'happy', 'blink' (0.x 'Blink'), ...": the expressions for a message. */
    std::string listForMessage() const;

private:
    enum class Override { None, Block, Blend };
    enum class Procedural { None, Blink, LookAt, Mouth };
    enum class ColorTarget { Color, EmissionColor, ShadeColor, MatcapColor, RimColor, OutlineColor };
    struct MorphBind {
        int node = -1;
        std::size_t target = 0;
        double weight = 1.0;
    };
    struct ColorBind {
        int material = -1;
        ColorTarget target = ColorTarget::Color;
        glm::dvec4 value{1.0};
    };
    struct TextureBind {
        int material = -1;
        glm::dvec2 scale{1.0};
        glm::dvec2 offset{0.0};
    };
    struct Expression {
        std::string name;      ///< the 1.0 name
        std::string groupName; ///< a 0.x group's own name, else empty
        bool isBinary = false;
        Override overrideBlink = Override::None;
        Override overrideLookAt = Override::None;
        Override overrideMouth = Override::None;
        std::vector<MorphBind> morphBinds;
        std::vector<ColorBind> colorBinds;
        std::vector<TextureBind> textureBinds;
        double weight = 0.0;
    };

    void readVrm1(const tinygltf::Model& model, std::vector<Warning>& warnings);
    void readVrm0(const tinygltf::Model& model, std::vector<Warning>& warnings);
    std::optional<std::size_t> indexOf(const std::string& name) const;
    static Procedural proceduralOf(const std::string& name);
    double outputOf(const Expression& expression) const;
    double appliedWeightOf(const Expression& expression) const;

    std::string mPath;
    std::vector<Expression> mExpressions;
    /** The materials warned of by applyToMaterial(), which runs once per primitive. */
    mutable std::set<int> mMaterialsWarnedOf;
};

} // namespace inkgraph::detail
