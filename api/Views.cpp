#include "api/Internal.h"

#include "flags/Options.h"
#include "scene/ViewSampling.h"

namespace inkgraph::api {
inline namespace INKGRAPH_ABI_NAMESPACE {

std::vector<ViewSample> sampleViews(std::size_t count, std::uint64_t seed, const std::string& modelKey,
                                    const ViewSampling& sampling) {
    return translated("sampleViews()", [&] {
        // Through the command line's flags: the same checks and messages, and the same doubles, as --views.
        std::vector<std::string> arguments = {
            "--views",
            std::to_string(count),
            "--seed",
            std::to_string(seed),
            "--view-elevation",
            exactText(sampling.elevationMean) + "," + exactText(sampling.elevationDeviation) + "," +
                exactText(sampling.elevationLow) + "," + exactText(sampling.elevationHigh),
            "--view-distance-jitter",
            exactText(sampling.distanceJitter),
            "--light-jitter",
            exactText(sampling.lightJitter)};
        if (sampling.light) arguments.insert(arguments.end(), {"--light", vectorText(*sampling.light)});
        const auto joined = [](const std::vector<std::string>& items, char separator) {
            std::string text;
            for (const std::string& item : items) text += (text.empty() ? "" : std::string(1, separator)) + item;
            return text;
        };
        if (!sampling.expressions.empty())
            arguments.insert(arguments.end(), {"--expressions", joined(sampling.expressions, ';')});
        if (!sampling.poses.empty()) arguments.insert(arguments.end(), {"--poses", joined(sampling.poses, ',')});
        const RenderOptions options = parseRenderFlags(arguments);
        std::vector<ViewSample> samples;
        for (const inkgraph::ViewSample& drawn : inkgraph::sampleViews(viewSamplingOf(options), modelKey)) {
            ViewSample sample;
            sample.index = drawn.index;
            sample.azimuth = drawn.azimuthDegrees;
            sample.elevation = drawn.elevationDegrees;
            sample.distanceScale = drawn.distanceScale;
            if (drawn.towardLight)
                sample.light = Vec3{drawn.towardLight->x, drawn.towardLight->y, drawn.towardLight->z};
            if (drawn.expressions) sample.expression = expressionSetText(*drawn.expressions);
            sample.pose = drawn.pose;
            samples.push_back(std::move(sample));
        }
        return samples;
    });
}

} // namespace INKGRAPH_ABI_NAMESPACE
} // namespace inkgraph::api
