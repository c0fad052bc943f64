#pragma once
/** @file What the library's sources share, not installed: the data behind the public classes, the one way every
 *  exception leaves the library (as Error, by the core's report: render/ErrorReport.h), the checks of which flags a
 *  Look and a Frame take, the command-line names of the public enums, and the conversions between cv::Mat and Image. */

#include "inkgraph/inkgraph.h"

#include "flags/Options.h"
#include "flags/StyleFile.h"
#include "scene/Scene.h"
#include "scene/SceneDerivedData.h"

#include <opencv2/core.hpp>

#include <charconv>
#include <exception>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace inkgraph::api {
inline namespace INKGRAPH_ABI_NAMESPACE {

struct Scene::Impl {
    std::string path; ///< "" for arrays
    SceneOptions options;
    std::shared_ptr<const inkgraph::Scene> scene;
    /** What its renders derive from `scene` whatever the view (edge adjacency, curvature, ...), shared by all of them,
     *  on any thread. */
    std::shared_ptr<inkgraph::SceneDerivedData> derived;
};

/** The library's way into a Scene's data, which the public header keeps private. */
struct SceneAccess {
    static const Scene::Impl& impl(const Scene& scene) { return *scene.mImpl; }
    static Scene make(std::shared_ptr<const Scene::Impl> impl) { return Scene(std::move(impl)); }
};

/** A look as the flags that give it, in order (each with its origin: a style file's line, or ""), and those flags
 *  parsed (each value checked; the rules between them wait for the render). */
struct Look::Impl {
    std::vector<std::string> arguments;
    std::vector<std::string> origins;
    RenderOptions parsed;

    /** The flags given, by their first name, in order. */
    std::vector<std::string> givenFlags() const;
};

/** The library's way to make an Image over pixels it does not own. */
struct ImageAccess {
    static Image view(int width, int height, int channels, Image::Type type, const std::uint8_t* data,
                      std::size_t rowBytes, std::shared_ptr<const void> owner) {
        return Image(width, height, channels, type, data, rowBytes, std::move(owner));
    }
};

/** The objects and the meshes of `scene` as Scene::objects() and Scene::meshes() give them: what a still drawn from
 *  it names in its id buffers. */
std::vector<SceneObject> objectsOf(const inkgraph::Scene& scene);
std::vector<SceneMesh> meshesOf(const inkgraph::Scene& scene);

/** The library's way into a Look's data. */
/** Error(Usage) for a Look used after it was moved from: its state went with the move. */
inline Error lookMovedFrom() {
    return Error(Error::Kind::Usage, "Look: this Look was moved from; assign it a Look before using it");
}

struct LookAccess {
    static const Look::Impl& impl(const Look& look) {
        if (!look.mImpl) throw lookMovedFrom();
        return *look.mImpl;
    }
};

/** `error` as the command line reports it (render/ErrorReport.h): its message, and the kind of its exit code. */
Error errorOf(const std::exception_ptr& error);

/** A refusal of the library's own of kind Context, said in its caller's name as a UsageError is (a renderer in a child
 *  forked after the driver started cannot make a context: the message is HeadlessContext()'s without its name). */
class ContextRefusal : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/** A refusal of kind Input (the model lacks what the caller asks), said in its caller's name as a UsageError is: the
 *  loader's refusal of a frame's pose or face, whose message would start with loadScene(), which the caller never
 *  called. */
class InputRefusal : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/** Runs `body`; every exception leaves as Error. A UsageError's message, which starts with the flag, gets `function`
 *  in front ("Look::set(): --bands: ..."), as a ContextRefusal's and an InputRefusal's; the other layers' messages
 *  start with their own function already. */
template <class Body>
decltype(auto) translated(const std::string& function, Body&& body) {
    try {
        return body();
    } catch (const Error&) {
        throw;
    } catch (const UsageError& usage) {
        throw Error(Error::Kind::Usage, function + ": " + usage.what());
    } catch (const ContextRefusal& refusal) {
        throw Error(Error::Kind::Context, function + ": " + refusal.what());
    } catch (const InputRefusal& refusal) {
        throw Error(Error::Kind::Input, function + ": " + refusal.what());
    } catch (...) {
        throw errorOf(std::current_exception());
    }
}

/** Whose flags a list holds: a Look's (the Look and Lines sections of the flag table) or a Frame's (the Camera
 *  section and --size). */
enum class FlagOwner { Look, Frame };

/** Throws UsageError at the first flag of `arguments` that `owner` does not take, naming it and where the library
 *  takes it instead. Values are skipped; an unknown flag or a stray value stops the check, for parseRenderFlags() to
 *  refuse in the command line's words. */
void refuseOtherFlags(const SourcedArguments& arguments, FlagOwner owner);

/** The shortest text that reads back as `value`: how a typed number becomes its flag's value. */
inline std::string exactText(double value) {
    char text[64];
    const auto [end, error] = std::to_chars(text, text + sizeof text, value);
    return std::string(text, error == std::errc() ? end : text);
}

/** "X,Y,Z" and "R,G,B,A" as the flags take them. */
std::string vectorText(const Vec3& vector);
std::string colorText(const Color& color);

/** A vector of the renderer core (the scene's and the camera's glm::dvec3) as the API's Vec3. */
inline Vec3 vec3Of(const glm::dvec3& vector) { return {vector.x, vector.y, vector.z}; }

/** A typed face (SceneOptions' or Frame's expressions and lookAt) as the loader takes it, checked by --expression's
 *  and --look-at's rules and messages after `field` ("SceneOptions::"). */
void applyFace(const std::map<std::string, double>& expressions, const std::optional<Vec3>& lookAt,
               const std::string& field, std::vector<ExpressionWeight>& expressionsOut,
               std::optional<glm::dvec3>& lookAtOut);

/** An 8-bit or float image of 1 or 4 channels as an Image that shares its pixels;
 *  std::logic_error for another type. */
Image imageOf(const cv::Mat& mat);
/** The image's pixels as a cv::Mat header (no copy); UsageError for an empty image. */
cv::Mat matOf(const Image& image);

} // namespace INKGRAPH_ABI_NAMESPACE
} // namespace inkgraph::api
