#include "api/Frame.h"

#include "flags/FlagTable.h"

namespace inkgraph::api {
inline namespace INKGRAPH_ABI_NAMESPACE {
namespace {

/** Applies one flag of a frame's field to `options`, its message after the field's name ("Frame::fov: --fov: ..."),
 *  and records it as given. */
void applyField(const std::string& field, const std::string& flag, const std::string& value, RenderOptions& options,
                std::vector<std::string>& given) {
    try {
        if (value.empty()) throw UsageError(flag + ": empty value");
        findFlag(flag)->apply(value, options);
    } catch (const UsageError& error) {
        throw UsageError("Frame::" + field + ": " + error.what());
    }
    given.push_back(flag);
}

} // namespace

void applyFrame(const Frame& frame, RenderOptions& options, std::vector<std::string>& given) {
    applyField("width and height", "--size", std::to_string(frame.width) + "x" + std::to_string(frame.height), options,
               given);
    if (frame.eye) applyField("eye", "--eye", vectorText(*frame.eye), options, given);
    if (frame.orbit) {
        std::string orbit = exactText(frame.orbit->azimuth) + "," + exactText(frame.orbit->elevation);
        // Appended piece by piece: a literal prepended to a temporary string draws GCC 12's -Wrestrict false positive.
        if (frame.orbit->distance && frame.orbit->distanceScale != 1.0)
            throw UsageError("Frame::orbit: a distance and a distanceScale (" + exactText(frame.orbit->distanceScale) +
                             ") are given; the scale is of the auto-framing distance, so give one of them");
        if (frame.orbit->distance) orbit.append(",").append(exactText(*frame.orbit->distance));
        if (!frame.orbit->distance && frame.orbit->distanceScale != 1.0)
            orbit.append(",x").append(exactText(frame.orbit->distanceScale));
        applyField("orbit", "--orbit", orbit, options, given);
    }
    if (frame.target) applyField("target", "--target", vectorText(*frame.target), options, given);
    if (frame.up) applyField("up", "--up", vectorText(*frame.up), options, given);
    if (frame.fov) applyField("fov", "--fov", exactText(*frame.fov), options, given);
    if (frame.clip)
        applyField("clip", "--clip", exactText(frame.clip->near) + "," + exactText(frame.clip->far), options, given);
    if (frame.placement != CameraPlacement::FileOrAuto && frame.placement != CameraPlacement::Auto)
        throw UsageError("Frame::placement: no CameraPlacement has the value " +
                         std::to_string(static_cast<int>(frame.placement)));
    if (frame.placement == CameraPlacement::Auto) applyField("placement", "--camera", "auto", options, given);
    if (!frame.frameNodes.empty()) {
        std::string nodes;
        for (const std::string& node : frame.frameNodes) nodes += (nodes.empty() ? "" : ",") + node;
        applyField("frameNodes", "--frame", nodes, options, given);
    }
    if (!frame.animation.empty()) applyField("animation", "--animation", frame.animation, options, given);
    if (frame.time) applyField("time", "--time", exactText(*frame.time), options, given);
    if (!frame.pose.empty()) applyField("pose", "--pose", frame.pose, options, given);
    applyFace(frame.expressions, frame.lookAt, "Frame::", options.expressions, options.lookAt);
}

Frame Frame::fromArguments(const std::vector<std::string>& arguments) {
    return translated("Frame::fromArguments()", [&] {
        SourcedArguments given{arguments, {}};
        separateAttachedValues(given.arguments, given.origins); // "--lines=contour" is --lines, not the Frame's
        refuseOtherFlags(given, FlagOwner::Frame);
        const RenderOptions options = parseRenderFlags(given.arguments);
        Frame frame;
        frame.width = options.width;
        frame.height = options.height;
        if (options.eye) frame.eye = vec3Of(*options.eye);
        if (options.orbit)
            frame.orbit = Orbit{options.orbit->azimuthDegrees, options.orbit->elevationDegrees, options.orbit->distance,
                                options.orbit->distanceScale};
        if (options.target) frame.target = vec3Of(*options.target);
        if (options.up) frame.up = vec3Of(*options.up);
        frame.fov = options.fovYDegrees;
        if (options.clipRange) frame.clip = Clip{options.clipRange->x, options.clipRange->y};
        frame.placement = options.autoCamera ? CameraPlacement::Auto : CameraPlacement::FileOrAuto;
        frame.frameNodes = options.frameNodes;
        frame.animation = options.animation;
        frame.pose = options.pose;
        for (const ExpressionWeight& expression : options.expressions)
            frame.expressions[expression.name] = expression.weight;
        if (options.lookAt) frame.lookAt = vec3Of(*options.lookAt);
        // --time given (even as 0) stays given: it is checked against --animation as on the command line.
        for (const std::string& argument : arguments)
            if (argument == "--time") frame.time = options.animationTime;
        return frame;
    });
}

} // namespace INKGRAPH_ABI_NAMESPACE
} // namespace inkgraph::api
