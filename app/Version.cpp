#include "app/Version.h"

#include "render/BuildInfo.h"
#include "app/Cli.h"
#include "render/ImageFiles.h"
#include "gl/BinaryLocation.h"
#include "gl/HeadlessContext.h"
#include "gl/ShaderLibrary.h"

#include <draco/core/draco_version.h>
#include <epoxy/egl.h>
#include <glm/glm.hpp>
#include <meshoptimizer.h>
#include <nlohmann/json.hpp>
#include <oneapi/tbb/version.h>
#include <opencv2/core/utility.hpp>
#include <png.h>
#include <zlib.h>

#include <filesystem>
#include <ostream>
#include <system_error>
#include <vector>

namespace inkgraph {
namespace {

void writeFact(std::ostream& out, const std::string& name, const std::string& value) {
    constexpr std::size_t kValueColumn = 15;
    const std::string label = name + ":";
    out << label << std::string(label.size() < kValueColumn ? kValueColumn - label.size() : 1, ' ') << value << "\n";
}

std::string eglString(int name) {
    const char* text = eglQueryString(eglGetCurrentDisplay(), name);
    return text != nullptr ? text : "unknown";
}

/** The libraries inkgraph runs with: the shared libraries' own answer at run time where they have one, else the
 *  version of the headers (GLM, nlohmann_json, Draco, meshoptimizer, which are compiled in or say no version at run
 * time) or of the package the build found. */
std::vector<std::pair<std::string, std::string>> libraryVersions() {
    return {
        {"OpenCV", cv::getVersionString()},
        {"libpng", png_get_libpng_ver(nullptr)},
        {"zlib", zlibVersion()},
        {"oneTBB", TBB_runtime_version()},
        {"tinygltf", INKGRAPH_TINYGLTF_VERSION},
        {"Draco", draco::kDracoVersion},
        // MESHOPTIMIZER_VERSION is major * 1000 + minor * 10 + patch (180: 0.18.0).
        {"meshoptimizer", std::to_string(MESHOPTIMIZER_VERSION / 1000) + "." +
                              std::to_string(MESHOPTIMIZER_VERSION % 1000 / 10) + "." +
                              std::to_string(MESHOPTIMIZER_VERSION % 10)},
        {"GLM", std::to_string(GLM_VERSION_MAJOR) + "." + std::to_string(GLM_VERSION_MINOR) + "." +
                    std::to_string(GLM_VERSION_PATCH) + "." + std::to_string(GLM_VERSION_REVISION)},
        {"libepoxy", INKGRAPH_EPOXY_VERSION},
        {"nlohmann_json", std::to_string(NLOHMANN_JSON_VERSION_MAJOR) + "." +
                              std::to_string(NLOHMANN_JSON_VERSION_MINOR) + "." +
                              std::to_string(NLOHMANN_JSON_VERSION_PATCH)},
    };
}

} // namespace

std::string versionLine() {
    return std::string("inkgraph ") + inkgraphVersion() + " (git " + inkgraphGitCommit() + ")";
}

int writeVerboseVersion(std::ostream& out) {
    int exitCode = kExitOk;
    out << versionLine() << "\n";
    writeFact(out, "binary", containingBinary().empty() ? "unknown" : containingBinary().string());

    const ShaderFolder shaders = ShaderLibrary::findShaderFolder();
    std::string searched;
    for (const std::filesystem::path& folder : shaders.searched)
        searched += (searched.empty() ? "'" : ", '") + folder.string() + "'";
    std::error_code notFolder;
    if (shaders.path.empty()) {
        writeFact(out, "shaders", "not found (searched " + (searched.empty() ? "nothing" : searched) + ")");
        exitCode = kExitNoGl;
    } else if (!std::filesystem::is_directory(shaders.path, notFolder)) {
        writeFact(out, "shaders", shaders.path.string() + " (" + shaders.origin + "), which is not a folder");
        exitCode = kExitNoGl;
    } else {
        writeFact(out, "shaders", shaders.path.string() + " (" + shaders.origin + ")");
    }

    try {
        const HeadlessContext context;
        writeFact(out, "EGL",
                  eglString(EGL_VERSION) + ", " + eglString(EGL_VENDOR) + ", " + context.platform() + " platform");
        writeFact(out, "OpenGL", context.version() + ", " + context.renderer() + ", " + context.vendor());
    } catch (const HeadlessContextError& error) {
        writeFact(out, "OpenGL", std::string("no context: ") + error.what());
        exitCode = kExitNoGl;
    }

    try {
        writeFact(out, "OpenImageIO", imageIoLibrary());
    } catch (const FileError& error) {
        writeFact(out, "OpenImageIO", std::string("not loaded: ") + error.what());
    }
    for (const auto& [library, version] : libraryVersions()) writeFact(out, library, version);
    return exitCode;
}

} // namespace inkgraph
