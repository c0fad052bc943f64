#pragma once
/** @file Random views of a model for data sets (--views N --seed S): each still's azimuth, elevation, distance scale,
 *  light, expressions and pose, drawn reproducibly. No GL; used by the command line (app/Batch.h) and the library
 *  (api/, Python's sample_views()), which therefore draw the same views.
 *
 *  Determinism: each still has its own random stream, keyed by FNV-1a 64 over (seed, model key, view index) and mixed
 *  by splitmix64, so a view never depends on which other stills a process renders (shards, resumed runs). The
 *  generator, its uniform doubles and the normal are written here (the standard library's distributions differ
 *  between implementations); every still draws the same number of values in the same order whatever the settings, so
 *  turning on light jitter leaves the azimuths as they were. The results are quantized (angles to 1e-6 degree, the
 *  scale and the light's components to 1e-9), so a last-bit difference of a libm function does not change a recorded
 *  number, and the recorded numbers given back as --orbit and --light reproduce the still. */

#include "scene/Scene.h"

#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace inkgraph {

/** What --views and its companion flags ask for. */
struct ViewSampling {
    std::size_t count = 1;  ///< --views N: views per model, 1 to 100000
    std::uint64_t seed = 0; ///< --seed
    /** --view-elevation MEAN,SD[,LOW,HIGH], degrees: the elevation is normal about the mean, clamped to [low, high]
     *  (within [-89.9, 89.9], --orbit's bounds). */
    double elevationMean = 10.0;
    double elevationDeviation = 10.0;
    double elevationLow = -30.0;
    double elevationHigh = 60.0;
    double distanceJitter = 0.0;     ///< --view-distance-jitter J in [0, 0.9]: the scale is 1 + J u, u in [-1, 1]
    double lightJitterDegrees = 0.0; ///< --light-jitter DEG in [0, 180]: the cap's angular radius about `light`
    /** The light the jitter turns (--light, made unit length); needed when lightJitterDegrees > 0. */
    std::optional<glm::dvec3> light;
    /** --expressions' alternatives, each an --expression set; an empty set is the alternative `none`. Empty: no
     *  expressions are chosen. */
    std::vector<std::vector<ExpressionWeight>> expressionChoices;
    /** --poses' alternatives as given: "rest" (no pose), "a-pose" or a pose file. Empty: no pose is chosen. */
    std::vector<std::string> poseChoices;
};

/** The --poses alternative that poses nothing: the model's rest pose. */
inline constexpr std::string_view kRestPoseChoice = "rest";

/** One still's view. */
struct ViewSample {
    std::size_t index = 0;         ///< the view index, 0 to count - 1
    double azimuthDegrees = 0.0;   ///< uniform in [0, 360), a multiple of 1e-6
    double elevationDegrees = 0.0; ///< normal, clamped, a multiple of 1e-6
    double distanceScale = 1.0;    ///< times the auto-framing distance, a multiple of 1e-9
    /** The light turned within the cap, each component a multiple of 1e-9 (not exactly unit length: --light, and the
     *  renderer, normalise it); unset without light jitter. */
    std::optional<glm::dvec3> towardLight;
    /** The chosen --expressions alternative (empty: `none`); unset without --expressions. */
    std::optional<std::vector<ExpressionWeight>> expressions;
    /** The chosen --poses alternative as given ("rest", "a-pose", a file); unset without --poses. */
    std::optional<std::string> pose;

    bool operator==(const ViewSample&) const = default;
};

/** The view `index` of the model listed as `modelKey` (the model path as the list gives it). Throws
 *  std::invalid_argument, naming the setting, for settings out of the ranges above, a light jitter without a light,
 *  or an index not below `count`. */
ViewSample sampleView(const ViewSampling& sampling, const std::string& modelKey, std::size_t index);

/** Every view of `modelKey`, 0 to count - 1. */
std::vector<ViewSample> sampleViews(const ViewSampling& sampling, const std::string& modelKey);

/** An --expressions alternative as --expression writes it ("angry=1,blink=0.5"), or "none" for the empty set. */
std::string expressionSetText(const std::vector<ExpressionWeight>& expressions);

/** The random stream of one still (exposed for the tests): splitmix64 seeded by FNV-1a 64 over the seed's 8 bytes
 *  (little-endian), the model key's bytes and the view index's 8 bytes (little-endian). */
class ViewRandom {
public:
    ViewRandom(std::uint64_t seed, const std::string& modelKey, std::uint64_t index);
    std::uint64_t next();
    /** Uniform in [0, 1): the top 53 bits of next(). */
    double uniform();

private:
    std::uint64_t mState = 0;
};

} // namespace inkgraph
