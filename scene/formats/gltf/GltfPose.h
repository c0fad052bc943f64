#pragma once
/** @file The pose of a glTF model: nodes' local transforms (their own TRS, or an animation sampled at a time), world
 *  matrices, morph targets at their weights and skins blended by their joints. Internal to the glTF reader
 *  (scene/formats/gltf/GltfReader.cpp), which bakes the posed positions into world space. */

#include "scene/Warning.h"

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace tinygltf {
class Model;
struct Primitive;
} // namespace tinygltf

namespace inkgraph::detail {

class MeshBudget;

/** One node's local transform and morph weights, as the file gives them or as an animation overrides them. */
struct NodePose {
    glm::dvec3 translation{0.0};
    glm::dquat rotation{1.0, 0.0, 0.0, 0.0}; // glm's (w, x, y, z)
    glm::dvec3 scale{1.0};
    /** A node given as "matrix": glTF forbids animating such a node, so it stays as written. */
    std::optional<glm::dmat4> matrix;
    /** Morph target weights: node.weights, else its mesh's weights, else none (every target at 0). */
    std::vector<double> weights;

    /** T * R * S, or the matrix. */
    glm::dmat4 local() const;
};

/** A world transform composed in double-double arithmetic (Dekker's error-free products and sums: each entry is an
 *  unevaluated sum hi + lo, about 32 significant digits), so that translations far larger than the model do not swallow
 *  it before positions are made relative to the scene's origin: in double 1e17 + 0.5 is 1e17, which collapses a unit
 *  cube placed there; here the sum is held exactly. Positions are baked with relativeTo() the origin, in double. */
class PreciseTransform {
public:
    PreciseTransform() : PreciseTransform(glm::dmat4(1.0)) {}
    explicit PreciseTransform(const glm::dmat4& matrix);

    /** This transform followed by `local` (this x local, as matrices), in double-double. */
    PreciseTransform operator*(const glm::dmat4& local) const;
    /** The translation, rounded to double. */
    glm::dvec3 translation() const;
    /** translate(-origin) x this, rounded to double: the difference is taken before rounding, so a transform near
     *  `origin` comes out as exactly as a transform near the world origin would. */
    glm::dmat4 relativeTo(const glm::dvec3& origin) const;
    /** The largest magnitude among the terms summed into the translation, in this composition and every one it
     *  follows: each step rounds off a few 2^-106 of it at most. */
    double magnitude() const { return mMagnitude; }
    /** How many compositions led here (the steps whose errors add up). */
    std::size_t steps() const { return mSteps; }

private:
    struct Sum {
        double hi = 0.0;
        double lo = 0.0;
    };
    Sum mEntries[4][4]; ///< column-major, as glm
    double mMagnitude = 0.0;
    std::size_t mSteps = 0;
};

/** The unit quaternion along (x, y, z, w), or nullopt when a component is not finite or every one is 0 (no
 *  rotation). The components are divided by the largest first: the sum of squares of 1e300 overflows a double and
 *  that of 1e-200 underflows to 0, and glm::normalize() then gives back a quaternion of zeros or the identity, a
 *  silently lost rotation. */
std::optional<glm::dquat> unitQuaternion(double x, double y, double z, double w);

/** Every node's rest pose: its own TRS (or matrix) and weights. Rotations are normalised, whatever their length;
 *  throws SceneError through throwLoadError() naming `path` and the node for a rotation with a component that is not
 *  finite or of length 0, which is no rotation. */
std::vector<NodePose> restPose(const std::string& path, const tinygltf::Model& model);

/** The index of the animation `name` (its name, or its index as text when no animation has that name); throws
 *  SceneError through throwLoadError() listing the animations the file has. */
std::size_t findAnimation(const std::string& path, const tinygltf::Model& model, const std::string& name);

/** How a sampler interpolates between keyframes (glTF animation.sampler.interpolation). */
enum class Interpolation { Step, Linear, CubicSpline };

/** One sampler's keyframes, read from the file. */
struct AnimationCurve {
    std::vector<float> times; ///< increasing
    /** `components` floats per element; CUBICSPLINE stores three elements per keyframe (in-tangent, value,
     *  out-tangent), the others one. */
    std::vector<float> values;
    std::size_t components = 0;
    Interpolation interpolation = Interpolation::Linear;
    bool rotation = false; ///< LINEAR quaternions slerp, and every result is normalised
};

/** The curve's value at `time` (clamped to its first and last keyframe); for a rotation, empty where a CUBICSPLINE
 *  passes through a quaternion of zero length (readCurve() refuses a keyframe's). */
std::vector<double> sampleCurve(const AnimationCurve& curve, double time);

/** Overrides `poses` with animation `animationIndex` sampled at `time` seconds: its translation, rotation, scale and
 *  weights channels. Each sampler's keyframes are checked against `budget` before they are read. Channels that
 *  cannot apply (a node given as a matrix, a "pointer" path) are skipped with a
 *  warning; bad accessors and indices throw. */
void applyAnimation(const std::string& path, const tinygltf::Model& model, std::size_t animationIndex, double time,
                    std::vector<NodePose>& poses, MeshBudget& budget, std::vector<Warning>& warnings);

/** Adds the morph targets of `primitive` at `weights` to its positions and normals (renormalised), in place. Only
 *  targets of non-zero weight are read, one at a time, each exactly as long as the positions (already charged). Targets
 * moving texture coordinates or colours are not applied; a warning says so once per primitive when such a target has a
 * non-zero weight. */
void applyMorphTargets(const std::string& path, const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                       const std::vector<double>& weights, std::vector<glm::vec3>& positions,
                       std::vector<glm::vec3>& normals, const std::string& meshLabel, std::vector<Warning>& warnings);

/** Skin `skinIndex`'s joint matrices: world(joint) * inverseBindMatrix (identity when the skin has none), as
 *  `jointMatrix(joint node, its inverse bind matrix)` composes them (precisely, relative to the scene's origin: the
 *  reader's PreciseTransform). The inverse bind matrices are checked against `budget` before they are read. Throws for
 *  a bad joint index or inverse bind matrix accessor. */
std::vector<glm::dmat4>
jointMatrices(const std::string& path, const tinygltf::Model& model, int skinIndex,
              const std::function<glm::dmat4(int node, const glm::dmat4& inverseBind)>& jointMatrix,
              MeshBudget& budget);

/** The per-vertex skinning of one primitive: JOINTS_n / WEIGHTS_n (n = 0 and 1 when present) blending the skin's
 *  joint matrices. */
class SkinBlend {
public:
    /** Reads the primitive's joints and weights (`vertexCount` each) and checks every joint index against
     *  `joints.size()`. `fallback` is the matrix of a vertex whose weights sum to zero (the skinned node's world).
     *  `decoded`, for a Draco-compressed primitive, holds its decoded attributes by name (DracoPrimitive::attributes,
     *  four floats per vertex for JOINTS_n and WEIGHTS_n): a set found there is taken from it, not its accessor. */
    SkinBlend(const std::string& path, const tinygltf::Model& model, const tinygltf::Primitive& primitive,
              std::size_t vertexCount, std::vector<glm::dmat4> joints, const glm::dmat4& fallback,
              const std::string& meshLabel, const std::map<std::string, std::vector<float>>* decoded = nullptr);

    /** sum_i weight_i * joint[joint_i] over the vertex's influences, weights normalised to sum 1. */
    glm::dmat4 vertexMatrix(std::size_t vertex) const;

    /** The vertices whose weights do not sum to 1 within kWeightSumTolerance (glTF asks that they do), which
     *  vertexMatrix() normalises, and those whose weights are all 0, which follow the fallback. */
    struct WeightSums {
        std::size_t unnormalised = 0; ///< off 1, but not all 0
        std::size_t zero = 0;         ///< all 0
        std::size_t firstVertex = 0;  ///< the first vertex of either kind
        double firstSum = 1.0;        ///< its sum
    };
    WeightSums weightSums() const;
    /** How far a vertex's weights may sum from 1: four unsigned-byte weights, each rounded by up to half of 1/255,
     *  twice over for JOINTS_1, stay within it. */
    static constexpr double kWeightSumTolerance = 0.02;
    /** Calls `visit(joint)` with the index (into the skin's joints) of each influence of non-zero weight at `vertex`.
     */
    template <class Visit>
    void forEachJoint(std::size_t vertex, Visit&& visit) const {
        for (std::size_t i = 0; i < mInfluences; ++i) {
            if (mWeightOf[vertex * mInfluences + i] > 0.0f) visit(mJointOf[vertex * mInfluences + i]);
        }
    }

private:
    std::vector<glm::dmat4> mJoints;
    glm::dmat4 mFallback;
    std::size_t mInfluences = 0;         ///< 4 per JOINTS_n set
    std::vector<std::uint32_t> mJointOf; ///< mInfluences per vertex
    std::vector<float> mWeightOf;        ///< mInfluences per vertex
};

/** Bytes SkinBlend holds per vertex for `sets` JOINTS/WEIGHTS pairs, for the load's memory budget. */
inline constexpr std::size_t kSkinBytesPerVertexPerSet = 4 * (sizeof(std::uint32_t) + sizeof(float));

} // namespace inkgraph::detail
