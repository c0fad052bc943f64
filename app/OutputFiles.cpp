#include "app/OutputFiles.h"

#include "app/ImageFiles.h"

#include <nlohmann/json.hpp>

#include <unistd.h>

#include <cstring>
#include <fstream>
#include <system_error>

namespace inkgraph {
namespace fs = std::filesystem;
namespace {

fs::path folderOf(const fs::path& file) { return file.has_parent_path() ? file.parent_path() : fs::path("."); }

/** A probe file is the only reliable test of writability (permissions, read-only mounts, ACLs). */
void requireWritableFolder(const fs::path& folder, const std::string& what) {
    std::error_code error;
    if (!fs::is_directory(folder, error))
        throw FileError("checkOutputs(): the folder of " + what + " ('" + folder.string() + "') does not exist" +
                        (error && error != std::errc::no_such_file_or_directory ? ": " + error.message() : ""));
    const fs::path probe = temporarySibling(folder / "probe");
    std::ofstream file(probe);
    if (!file) {
        throw FileError("checkOutputs(): cannot write into the folder of " + what + " ('" + folder.string() +
                        "'): " + std::strerror(errno));
    }
    file.close();
    fs::remove(probe, error);
}

void requireWritableFile(const std::string& path, const std::string& flag) {
    std::error_code error;
    const std::string what = flag + " '" + path + "'";
    if (fs::is_directory(path, error)) throw FileError("checkOutputs(): " + what + " is a folder; give a file name");
    if (error && error != std::errc::no_such_file_or_directory)
        throw FileError("checkOutputs(): " + what + ": " + error.message());
    requireWritableFolder(folderOf(path), what);
}

} // namespace

bool isInkgraphDump(const fs::path& directory) {
    std::ifstream file(directory / "manifest.json");
    if (!file) return false;
    const auto manifest = nlohmann::json::parse(file, nullptr, false);
    return manifest.is_object() && manifest.contains("inkgraph");
}

void OutputPlan::checkAll() const {
    if (!mOptions.outputPath.empty()) requireWritableFile(mOptions.outputPath, "-o");
    if (!mOptions.statsPath.empty()) requireWritableFile(mOptions.statsPath, "--stats");
    if (!mOptions.graphvizPath.empty()) requireWritableFile(mOptions.graphvizPath, "--graphviz");
    if (mOptions.dumpDirectory.empty()) return;

    const fs::path directory(mOptions.dumpDirectory);
    const std::string what = "--dump '" + mOptions.dumpDirectory + "'";
    std::error_code error;
    const fs::file_status status = fs::status(directory, error);
    if (fs::exists(status)) {
        if (!fs::is_directory(status)) throw FileError("checkOutputs(): " + what + " is a file, not a folder");
        if (!fs::is_empty(directory, error) && !isInkgraphDump(directory))
            throw FileError("checkOutputs(): " + what + " holds files that are not an inkgraph dump; give a new or "
                            "empty folder (a dump replaces the whole folder)");
    } else if (error && error != std::errc::no_such_file_or_directory) {
        throw FileError("checkOutputs(): " + what + ": " + error.message());
    }
    const fs::path parent = folderOf(fs::absolute(directory, error).lexically_normal());
    fs::create_directories(parent, error);
    requireWritableFolder(parent, what);
}

DumpFolder::DumpFolder(fs::path directory) : mDirectory(std::move(directory)) {
    while (!mDirectory.has_filename() && mDirectory.has_parent_path()) mDirectory = mDirectory.parent_path();
    const fs::path parent = folderOf(mDirectory);
    mStaging = parent / (".inkgraph-dump-" + std::to_string(::getpid()));
    std::error_code error;
    fs::remove_all(mStaging, error);
    if (!fs::create_directory(mStaging, error))
        throw FileError("DumpFolder(): cannot create '" + mStaging.string() + "' for --dump '" +
                        mDirectory.string() + "': " + error.message());
}

DumpFolder::~DumpFolder() {
    if (mCommitted) return;
    std::error_code ignored;
    fs::remove_all(mStaging, ignored);
}

void DumpFolder::commit() {
    std::error_code error;
    const fs::path old = folderOf(mDirectory) / (".inkgraph-old-" + std::to_string(::getpid()));
    const bool hadOld = fs::exists(mDirectory, error);
    if (hadOld) {
        fs::remove_all(old, error);
        fs::rename(mDirectory, old, error);
        if (error)
            throw FileError("DumpFolder::commit(): cannot move the earlier dump '" + mDirectory.string() +
                            "' aside: " + error.message());
    }
    fs::rename(mStaging, mDirectory, error);
    if (error) {
        std::error_code ignored;
        if (hadOld) fs::rename(old, mDirectory, ignored);
        throw FileError("DumpFolder::commit(): cannot put the dump in place as '" + mDirectory.string() +
                        "': " + error.message());
    }
    mCommitted = true;
    if (hadOld) fs::remove_all(old, error);
}

} // namespace inkgraph
