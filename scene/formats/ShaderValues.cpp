#include "scene/formats/ShaderValues.h"

#include "scene/formats/FormatReaders.h"

#include <algorithm>
#include <cmath>

namespace inkgraph::detail {

float shaderValue(double value, ShaderRange range, const std::string& what, std::vector<Warning>& warnings,
                  const std::string& item) {
    if (value >= range.min && value <= range.max) return float(value);
    const double used = value > range.max ? range.max : range.min;
    warnings.push_back(makeWarning(WarningKind::ValueOutOfRange,
                                   what + " " + formatNumber(value) + " is outside [" + formatNumber(range.min) + ", " +
                                       formatNumber(range.max) + "]; " + formatNumber(used) + " is used",
                                   "", item));
    return float(used);
}

namespace {

/** How far a wrap mode repeats: sampling at s and at s + period gives the same texel; 0 when it does not repeat. */
double wrapPeriod(TextureWrap wrap) {
    switch (wrap) {
    case TextureWrap::Repeat: return 1.0;
    case TextureWrap::MirroredRepeat: return 2.0;
    case TextureWrap::ClampToEdge: return 0.0;
    }
    return 0.0;
}

} // namespace

std::optional<glm::mat3> shaderTextureTransform(const glm::dmat3& transform, const TextureSampler& sampler,
                                                std::string& problem) {
    glm::dmat3 reduced = transform;
    const double periods[2] = {wrapPeriod(sampler.wrapS), wrapPeriod(sampler.wrapT)};
    for (int row = 0; row < 2; ++row) {
        // fmod is exact, and leaves an offset inside (-period, period) as it is.
        if (periods[row] > 0.0 && std::isfinite(reduced[2][row]))
            reduced[2][row] = std::fmod(reduced[2][row], periods[row]);
    }
    double largestLinear = 0.0;
    double largestOffset = 0.0;
    for (int column = 0; column < 3; ++column) {
        for (int row = 0; row < 3; ++row) {
            const double size = std::isnan(reduced[column][row]) ? INFINITY : std::abs(reduced[column][row]);
            double& largest = column == 2 ? largestOffset : largestLinear;
            largest = std::max(largest, size);
        }
    }
    const std::string limit = ", beyond the " + formatNumber(kMaxTextureTransformEntry) +
                              " at which float still resolves a texel of the image";
    if (largestLinear > kMaxTextureTransformEntry) {
        problem =
            "its scale and rotation stretch texture coordinates " + formatNumber(largestLinear) + " times" + limit;
        return std::nullopt;
    }
    if (!std::isfinite(largestOffset)) {
        problem = "its offset is not finite";
        return std::nullopt;
    }
    if (largestOffset > kMaxTextureTransformEntry) {
        // Only an offset along a clamp-to-edge wrap is left this large: a repeating one was reduced.
        problem = "its offset moves texture coordinates by " + formatNumber(largestOffset) + limit +
                  " (the wrap is clamp-to-edge, which does not repeat)";
        return std::nullopt;
    }
    return glm::mat3(reduced);
}

} // namespace inkgraph::detail
