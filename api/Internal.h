#pragma once
/** @file What the library's sources share, not installed: the data behind the public classes, the one way every
 *  exception leaves the library (as Error, by the command line's own mapping), the checks of which flags a Look and a
 *  Frame take, and the conversions between cv::Mat and Image. */

#include "inkgraph/inkgraph.h"

#include "flags/Options.h"
#include "flags/StyleFile.h"
#include "scene/Scene.h"

#include <opencv2/core.hpp>

#include <exception>
#include <memory>
#include <string>
#include <vector>

namespace inkgraph::api {

struct Scene::Impl {
    std::string path;
    SceneOptions options;
    std::shared_ptr<const inkgraph::Scene> scene;
};

/** `error` as the command line reports it (render/ErrorReport.h reportOf()): its message, and the kind of its exit
 * code. */
Error errorOf(const std::exception_ptr& error);

/** Runs `body`; every exception leaves as Error. A UsageError's message, which starts with the flag, gets `function`
 *  in front ("Look::set(): --bands: ..."); the other layers' messages start with their own function already. */
template <class Body>
decltype(auto) translated(const std::string& function, Body&& body) {
    try {
        return body();
    } catch (const Error&) {
        throw;
    } catch (const UsageError& usage) {
        throw Error(Error::Kind::Usage, function + ": " + usage.what());
    } catch (...) {
        throw errorOf(std::current_exception());
    }
}

/** Whose flags a list holds: a Look's (the Look and Lines sections of the flag table) or a Frame's camera (the Camera
 *  section but --animation and --time, which are SceneOptions). */
enum class FlagOwner { Look, Camera };

/** Throws UsageError at the first flag of `arguments` that `owner` does not take, naming it and where the library
 *  takes it instead. Values are skipped; an unknown flag or a stray value stops the check, for parseRenderFlags() to
 *  refuse in the command line's words. */
void refuseOtherFlags(const SourcedArguments& arguments, FlagOwner owner);

/** An 8-bit or float image of 1 or 4 channels as Image (a copy); std::logic_error for another type. */
Image imageOf(const cv::Mat& mat);
/** The image's pixels as a cv::Mat header (no copy); UsageError for an image whose fields do not agree. */
cv::Mat matOf(const Image& image);

} // namespace inkgraph::api
