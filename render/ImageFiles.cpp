#include "render/ImageFiles.h"

#include "render/ImageIoModule.h"
#include "render/OutputPlace.h"
#include "render/PngFiles.h"
#include "render/TemporaryFiles.h"
#include "codecs/PngChunks.h"
#include "gl/BinaryLocation.h"
#include "scene/MessageText.h"

#include <dlfcn.h>
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <future>
#include <iterator>
#include <mutex>
#include <system_error>

namespace inkgraph {
namespace {

/** `path` in single quotes, on one line, for messages. */
std::string quotedPath(const std::filesystem::path& path) { return detail::quotedFileName(path.string()); }

constexpr const char* kModuleName = kImageIoModuleName;

void renameIntoPlace(const std::filesystem::path& temporary, const std::filesystem::path& path) {
    std::error_code error;
    std::filesystem::rename(temporary, path, error);
    if (error) {
        removeTemporary(temporary); // from the folder it was made in, should that have moved
        throw FileError("writeFile(): cannot move the finished file into place as " +
                        detail::quotedFileName(path.string()) + ": " + error.message());
    }
    forgetTemporary(temporary);
}

/** Where the OpenImageIO module may be, in order: INKGRAPH_IMAGEIO_MODULE; the installed module relative to the
 *  binary holding this code (gl/BinaryLocation.h: `<bin>/../lib/inkgraph/`, `<bin>/../../lib/inkgraph/`); and, only
 *  for a binary in the build tree, the build tree's module. */
std::vector<std::filesystem::path> moduleCandidates() {
    std::vector<std::filesystem::path> candidates;
    if (const char* fromEnvironment = std::getenv("INKGRAPH_IMAGEIO_MODULE"); fromEnvironment && *fromEnvironment)
        candidates.emplace_back(fromEnvironment);
    for (const std::filesystem::path& installed : installedCandidates(installedModuleFolder() / kModuleName))
        candidates.push_back(installed);
    if (runsFromBuildTree()) candidates.emplace_back(INKGRAPH_IMAGEIO_MODULE_PATH);
    return candidates;
}

/** Loads the module; the result (functions, or the reason it failed) is kept for the whole process. */
struct LoadedModule {
    const ImageIoFunctions* functions = nullptr;
    std::filesystem::path path;
    std::string failure;
};

LoadedModule loadModule() {
    LoadedModule loaded;
    std::string missing;
    for (const std::filesystem::path& candidate : moduleCandidates()) {
        std::error_code error;
        if (!std::filesystem::exists(candidate, error)) {
            missing += (missing.empty() ? "'" : ", '") + candidate.string() + "'";
            continue;
        }
        // Never unloaded: OpenImageIO keeps global state until exit.
        void* handle = dlopen(candidate.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (handle == nullptr) {
            loaded.failure += std::string("\n  - ") + dlerror();
            continue;
        }
        using Entry = const ImageIoFunctions* (*)();
        auto entry = reinterpret_cast<Entry>(dlsym(handle, "inkgraph_image_io_functions"));
        if (entry == nullptr || entry()->version != kImageIoVersion) {
            loaded.failure += "\n  - " + detail::quotedFileName(candidate.string()) +
                              " is not an inkgraph image module of this version";
            continue;
        }
        loaded.functions = entry();
        loaded.path = candidate;
        return loaded;
    }
    if (!missing.empty()) loaded.failure += "\n  - not found at " + missing;
    return loaded;
}

/** The load's result, started on first call. `started` tells whether any call has been made yet. */
struct ModuleLoad {
    std::once_flag once;
    std::atomic<bool> started{false};
    std::shared_future<LoadedModule> future;
};

ModuleLoad& moduleLoad() {
    static ModuleLoad load;
    return load;
}

std::shared_future<LoadedModule>& moduleFuture() {
    ModuleLoad& load = moduleLoad();
    std::call_once(load.once, [&load] {
        load.future = std::async(std::launch::async, loadModule).share();
        load.started = true;
    });
    return load.future;
}

const LoadedModule& loadedImageIo() {
    const LoadedModule& loaded = moduleFuture().get();
    if (loaded.functions == nullptr)
        throw FileError("imageIo(): cannot load the OpenImageIO module '" + std::string(kModuleName) +
                        "' (install libopenimageio2.4, or set INKGRAPH_IMAGEIO_MODULE to its path):" + loaded.failure);
    return loaded;
}

const ImageIoFunctions& imageIo() { return *loadedImageIo().functions; }

} // namespace

bool usesImageIoModule(const std::filesystem::path& path) {
    std::string extension = path.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return extension != ".png";
}

void preloadImageIo() { moduleFuture(); }

std::string imageIoModuleState() {
    ModuleLoad& load = moduleLoad();
    if (!load.started) return "not loaded";
    const std::shared_future<LoadedModule>& future = moduleFuture();
    if (future.wait_for(std::chrono::seconds(0)) != std::future_status::ready) return "loading";
    return future.get().functions != nullptr ? "loaded" : "failed to load";
}

std::string imageIoLibrary() {
    const LoadedModule& loaded = loadedImageIo();
    return std::string(loaded.functions->libraryVersion()) + " (module " +
           detail::quotedFileName(loaded.path.string()) + ")";
}

void finishImageIoPreload() {
    // Only wait for a load someone started: starting one here would cost every exit ~0.2 s for nothing.
    if (moduleLoad().started) moduleFuture().wait();
}

std::filesystem::path temporarySibling(const std::filesystem::path& path) {
    // Short, and without the final name's extension (which may itself be near NAME_MAX): the format follows the
    // final name, never the temporary one.
    static std::atomic<int> counter{0};
    const std::string name = ".inkgraph-" + temporaryTag() + "-" + std::to_string(counter++) + ".tmp";
    return path.parent_path() / name;
}

int creationErrorIn(const std::filesystem::path& folder) {
    const std::filesystem::path probe = temporarySibling(folder / "probe");
    const int descriptor = createTemporaryFile(probe, 0600);
    if (descriptor < 0) return errno;
    ::close(descriptor);
    removeTemporary(probe);
    return 0;
}

int writeWhole(int descriptor, const void* data, std::size_t byteCount) {
    const auto* bytes = static_cast<const char*>(data);
    std::size_t written = 0;
    while (written < byteCount) {
        const ssize_t result = ::write(descriptor, bytes + written, byteCount - written);
        if (result > 0)
            written += std::size_t(result);
        else if (result == 0)
            return EIO;
        else if (errno != EINTR)
            return errno;
    }
    return 0;
}

void writeBytes(const std::filesystem::path& destination, const void* data, std::size_t byteCount,
                const std::string& shownName) {
    const int descriptor = createTemporaryFile(destination, 0644);
    if (descriptor < 0)
        throw FileError("writeFile(): cannot create " + detail::quotedFileName(shownName) + ": " +
                        std::strerror(errno));
    int failure = writeWhole(descriptor, data, byteCount);
    // fsync before the rename: after a crash the final name holds the whole file or the old one, never a prefix.
    if (failure == 0 && ::fsync(descriptor) != 0) failure = errno;
    if (::close(descriptor) != 0 && failure == 0) failure = errno;
    if (failure != 0) {
        removeTemporary(destination);
        throw FileError("writeFile(): cannot write " + detail::quotedFileName(shownName) + ": " +
                        std::strerror(failure));
    }
}

std::vector<unsigned char> encodeImageFile(const std::filesystem::path& finalPath, const cv::Mat& image) {
    std::vector<unsigned char> encoded;
    std::string error;
    // libjpeg ends the process (exit(1)) for a side above its limit instead of returning an error.
    std::string extension = finalPath.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    constexpr int kLargestJpegSide = 65500;
    if ((extension == ".jpg" || extension == ".jpeg" || extension == ".jpe" || extension == ".jfif" ||
         extension == ".jif" || extension == ".jfi") &&
        std::max(image.cols, image.rows) > kLargestJpegSide)
        throw FileError("writeImage(): cannot write " + detail::quotedFileName(finalPath.string()) +
                        ": JPEG holds at most " + std::to_string(kLargestJpegSide) + " pixels a side, the image is " +
                        std::to_string(image.cols) + "x" + std::to_string(image.rows));
    if (!usesImageIoModule(finalPath)) {
        try {
            encoded = encodePng(image);
        } catch (const std::runtime_error& failure) {
            throw FileError("writeImage(): cannot write " + detail::quotedFileName(finalPath.string()) + ": " +
                            failure.what());
        }
    } else if (!imageIo().encodeImage(finalPath.string(), image, encoded, error)) {
        throw FileError("writeImage(): cannot write " + detail::quotedFileName(finalPath.string()) + ": " + error);
    }
    return encoded;
}

void writeImageTo(const std::filesystem::path& destination, const std::filesystem::path& finalPath,
                  const cv::Mat& image) {
    const std::vector<unsigned char> encoded = encodeImageFile(finalPath, image);
    writeBytes(destination, encoded.data(), encoded.size(), finalPath.string());
}

void writeImage(const std::filesystem::path& path, const cv::Mat& image) {
    requireOutputPlace(path, "writeImage()", quotedPath(path));
    const std::filesystem::path temporary = temporarySibling(path);
    writeImageTo(temporary, path, image);
    renameIntoPlace(temporary, path);
}

std::string imageFilePixelType(const std::filesystem::path& path) {
    std::string type;
    std::string error;
    if (!imageIo().pixelType(path.string(), type, error))
        throw FileError("imageFilePixelType(): cannot read " + detail::quotedFileName(path.string()) + ": " + error);
    return type;
}

cv::Mat readImage(const std::filesystem::path& path, std::size_t maxPixels) {
    if (!usesImageIoModule(path)) {
        try {
            return readPngFile(path, maxPixels);
        } catch (const std::runtime_error& failure) {
            throw FileError("readImage(): cannot read " + detail::quotedFileName(path.string()) + ": " +
                            failure.what());
        }
    }
    cv::Mat image;
    std::string error;
    if (!imageIo().readImage(path.string(), maxPixels, image, error))
        throw FileError("readImage(): cannot read " + detail::quotedFileName(path.string()) + ": " + error);
    return image;
}

std::string readInputBytes(const std::filesystem::path& path, std::uintmax_t maxBytes, const std::string& who) {
    const std::string where = who + ": " + detail::quotedFileName(path.string());
    std::error_code error;
    const auto status = std::filesystem::status(path, error);
    if (status.type() == std::filesystem::file_type::not_found) throw FileError(where + ": file not found");
    if (status.type() != std::filesystem::file_type::regular) throw FileError(where + ": not a regular file");
    const std::uintmax_t size = std::filesystem::file_size(path, error);
    if (error) throw FileError(where + ": " + error.message());
    if (size > maxBytes)
        throw FileError(where + " is " + std::to_string(size) + " bytes; at most " + std::to_string(maxBytes) +
                        " bytes are read here");
    std::ifstream file(path, std::ios::binary);
    if (!file) throw FileError(where + ": cannot open the file for reading");
    return {std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
}

cv::Mat readPngImage(const std::filesystem::path& path, std::size_t maxPixels, std::size_t maxFileBytes,
                     const std::string& who) {
    const std::string where = who + ": " + detail::quotedFileName(path.string());
    const std::string bytes = readInputBytes(path, maxFileBytes, who);
    std::vector<unsigned char> png;
    try {
        png = criticalPngChunks(bytes);
    } catch (const std::invalid_argument& problem) {
        throw FileError(where + ": " + problem.what());
    }
    try {
        return decodePng(png.data(), png.size(), maxPixels);
    } catch (const std::runtime_error& failure) {
        throw FileError(where + ": " + failure.what());
    }
}

void writeTextFile(const std::filesystem::path& path, const std::string& text) {
    requireOutputPlace(path, "writeTextFile()", quotedPath(path));
    const std::filesystem::path temporary = temporarySibling(path);
    writeBytes(temporary, text.data(), text.size(), path.string());
    renameIntoPlace(temporary, path);
}

} // namespace inkgraph
