#include "app/OutputFiles.h"

#include "app/ImageFiles.h"
#include "app/TemporaryFiles.h"

#include <nlohmann/json.hpp>

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <set>
#include <system_error>

namespace inkgraph {
namespace fs = std::filesystem;
namespace {

fs::path folderOf(const fs::path& file) { return file.has_parent_path() ? file.parent_path() : fs::path("."); }

bool isInside(const fs::path& path, const fs::path& folder) {
    const fs::path relative = path.lexically_relative(folder);
    return !relative.empty() && *relative.begin() != "..";
}

/** Leftovers of killed runs (".inkgraph-<pid>-..." whose process is gone) are removed when we meet them. */
void sweepStaleTemporaries(const fs::path& folder) {
    std::error_code error;
    for (fs::directory_iterator it(folder, error), end; !error && it != end; it.increment(error)) {
        if (!isStaleTemporary(it->path().filename().string())) continue;
        std::error_code ignored;
        fs::remove_all(it->path(), ignored);
    }
}

/** A probe file is the only reliable test of writability (permissions, read-only mounts, ACLs). */
void requireWritableFolder(const fs::path& folder, const std::string& what) {
    std::error_code error;
    if (!fs::is_directory(folder, error))
        throw FileError("checkOutputs(): the folder of " + what + " ('" + folder.string() + "') does not exist" +
                        (error && error != std::errc::no_such_file_or_directory ? ": " + error.message() : ""));
    const fs::path probe = temporarySibling(folder / "probe");
    const int descriptor = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (descriptor < 0)
        throw FileError("checkOutputs(): cannot write into the folder of " + what + " ('" + folder.string() +
                        "'): " + std::strerror(errno));
    ::close(descriptor);
    ::unlink(probe.c_str());
}

} // namespace

fs::path resolvedPath(const fs::path& path) {
    std::error_code error;
    fs::path result = fs::weakly_canonical(fs::absolute(path, error), error);
    return error ? fs::absolute(path).lexically_normal() : result;
}

std::optional<std::vector<std::string>> earlierDumpFiles(const fs::path& directory) {
    std::ifstream file(directory / "manifest.json");
    if (!file) return std::nullopt;
    const auto manifest = nlohmann::json::parse(file, nullptr, false);
    if (!manifest.is_object() || !manifest.contains("inkgraph") || !manifest.contains("files")) return std::nullopt;
    std::set<std::string> listed = {"manifest.json"};
    for (const auto& entry : manifest["files"])
        if (entry.contains("file") && entry["file"].is_string()) listed.insert(entry["file"].get<std::string>());
    std::error_code error;
    for (fs::directory_iterator it(directory, error), end; !error && it != end; it.increment(error)) {
        const std::string name = it->path().filename().string();
        if (name.rfind(".inkgraph-staging-", 0) == 0) continue; // another run's work in progress
        if (listed.count(name) == 0) return std::nullopt;
    }
    if (error) return std::nullopt;
    return std::vector<std::string>(listed.begin(), listed.end());
}

OutputSet::OutputSet(const RenderOptions& options) : mOptions(options) {
    struct Named {
        std::string flag;
        std::string path;
    };
    std::vector<Named> files; // every output file; the --dump folder is checked apart
    for (const auto& [flag, field] : outputPathFlags())
        if (flag != "--dump" && !(options.*field).empty()) files.push_back({flag, options.*field});

    // Collisions first: they are mistakes in the command line, whatever the file system says.
    const fs::path model = resolvedPath(options.modelPath);
    const fs::path shadeMap = options.shadeMapPath.empty() ? fs::path() : resolvedPath(options.shadeMapPath);
    for (std::size_t i = 0; i < files.size(); ++i) {
        const fs::path path = resolvedPath(files[i].path);
        if (path == model)
            throw UsageError(files[i].flag + " '" + files[i].path + "' is the model itself; choose another file");
        if (!shadeMap.empty() && path == shadeMap)
            throw UsageError(files[i].flag + " '" + files[i].path + "' is the --shademap itself; choose another file");
        for (std::size_t j = i + 1; j < files.size(); ++j)
            if (path == resolvedPath(files[j].path))
                throw UsageError(files[i].flag + " and " + files[j].flag + " name the same file '" + files[i].path +
                                 "'");
        if (!options.dumpDirectory.empty() && isInside(path, resolvedPath(options.dumpDirectory)))
            throw UsageError(files[i].flag + " '" + files[i].path + "' lies inside --dump '" + options.dumpDirectory +
                             "', whose contents each dump replaces; write it elsewhere");
    }

    for (const Named& file : files) {
        std::error_code error;
        const std::string what = file.flag + " '" + file.path + "'";
        if (fs::is_directory(file.path, error))
            throw FileError("checkOutputs(): " + what + " is a folder; give a file name");
        requireWritableFolder(folderOf(file.path), what);
        sweepStaleTemporaries(folderOf(file.path));
    }
    if (!options.dumpDirectory.empty()) checkDumpFolder();
}

void OutputSet::checkDumpFolder() {
    mDumpDirectory = fs::path(mOptions.dumpDirectory);
    const std::string what = "--dump '" + mOptions.dumpDirectory + "'";
    std::error_code error;
    const fs::file_status status = fs::status(mDumpDirectory, error);
    if (fs::exists(status)) {
        if (!fs::is_directory(status)) throw FileError("checkOutputs(): " + what + " is a file, not a folder");
        sweepStaleTemporaries(mDumpDirectory);
        if (!fs::is_empty(mDumpDirectory, error) && !earlierDumpFiles(mDumpDirectory))
            throw FileError("checkOutputs(): " + what + " holds files that are not an inkgraph dump; give a new or "
                            "empty folder (each dump replaces the previous one's files)");
    } else if (error && error != std::errc::no_such_file_or_directory) {
        throw FileError("checkOutputs(): " + what + ": " + error.message());
    } else {
        // Created now, and removed again (with any parents created for it) if the run fails.
        for (fs::path missing = fs::absolute(mDumpDirectory).lexically_normal();
             !missing.empty() && !fs::exists(missing, error); missing = missing.parent_path())
            mCreatedFolders.push_back(missing);
        fs::create_directories(mDumpDirectory, error);
        if (error) throw FileError("checkOutputs(): cannot create " + what + ": " + error.message());
        // Outermost first, so an interrupted run removes the innermost first (app/TemporaryFiles.h).
        for (auto folder = mCreatedFolders.rbegin(); folder != mCreatedFolders.rend(); ++folder)
            registerTemporary(*folder);
    }
    requireWritableFolder(mDumpDirectory, what);
    mStaging = mDumpDirectory / (".inkgraph-staging-" + std::to_string(::getpid()));
    fs::remove_all(mStaging, error);
    if (!fs::create_directory(mStaging, error))
        throw FileError("checkOutputs(): cannot create a staging folder in " + what + ": " + error.message());
    registerTemporary(mStaging);
}

OutputSet::~OutputSet() {
    if (mCommitted) return;
    std::error_code ignored;
    for (const Staged& file : mFiles) {
        fs::remove(file.temporary, ignored);
        forgetTemporary(file.temporary);
    }
    if (!mStaging.empty()) {
        fs::remove_all(mStaging, ignored);
        forgetTemporary(mStaging);
    }
    for (const fs::path& folder : mCreatedFolders) {
        fs::remove(folder, ignored); // only if empty
        forgetTemporary(folder);
    }
}

void OutputSet::stageFile(const fs::path& destination, const cv::Mat* image, const std::string* text) {
    const fs::path temporary = temporarySibling(destination);
    if (image != nullptr) writeImageTo(temporary, destination, *image);
    else writeBytes(temporary, text->data(), text->size(), destination.string());
    mFiles.push_back({temporary, destination});
}

void OutputSet::stageFinalImage(const cv::Mat& image) { stageFile(mOptions.outputPath, &image, nullptr); }
void OutputSet::stageStats(const std::string& json) { stageFile(mOptions.statsPath, nullptr, &json); }
void OutputSet::stageGraphviz(const std::string& dot) { stageFile(mOptions.graphvizPath, nullptr, &dot); }
void OutputSet::stageContactSheet(const cv::Mat& image) { stageFile(mOptions.contactSheetPath, &image, nullptr); }
void OutputSet::stageSvg(const std::string& svg) { stageFile(mOptions.svgPath, nullptr, &svg); }

void OutputSet::stageDumpImage(const std::string& fileName, const cv::Mat& image) {
    writeImageTo(mStaging / fileName, mDumpDirectory / fileName, image);
    mDumpNames.push_back(fileName);
}

void OutputSet::stageDumpManifest(const std::string& json) {
    writeBytes(mStaging / "manifest.json", json.data(), json.size(), (mDumpDirectory / "manifest.json").string());
    mDumpNames.push_back("manifest.json");
}

void OutputSet::commitDump() {
    // A lock on the folder itself: runs dumping into one folder in parallel commit one after the other.
    const int folder = ::open(mDumpDirectory.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (folder < 0 || ::flock(folder, LOCK_EX) != 0)
        throw FileError("OutputSet::commit(): cannot lock --dump '" + mDumpDirectory.string() +
                        "': " + std::strerror(errno));
    std::error_code error;
    // The manifest goes first and comes back last, so a folder with a manifest always holds one whole dump.
    if (const auto earlier = earlierDumpFiles(mDumpDirectory)) {
        fs::remove(mDumpDirectory / "manifest.json", error);
        for (const std::string& name : *earlier) fs::remove(mDumpDirectory / name, error);
    }
    for (const std::string& name : mDumpNames) {
        fs::rename(mStaging / name, mDumpDirectory / name, error);
        if (error) {
            ::close(folder);
            throw FileError("OutputSet::commit(): cannot move '" + name + "' into --dump '" +
                            mDumpDirectory.string() + "': " + error.message());
        }
        forgetTemporary(mStaging / name);
    }
    ::close(folder);
    fs::remove_all(mStaging, error);
    forgetTemporary(mStaging);
}

void OutputSet::commit() {
    if (!mStaging.empty()) commitDump();
    for (const Staged& file : mFiles) {
        std::error_code error;
        fs::rename(file.temporary, file.destination, error);
        if (error)
            throw FileError("OutputSet::commit(): cannot move the finished file into place as '" +
                            file.destination.string() + "': " + error.message());
        forgetTemporary(file.temporary);
    }
    for (const fs::path& folder : mCreatedFolders) forgetTemporary(folder);
    mCommitted = true;
}

} // namespace inkgraph
