#include "render/OutputPlace.h"

#include "render/ImageFiles.h"
#include "scene/MessageText.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cstring>
#include <system_error>

namespace inkgraph {
namespace fs = std::filesystem;
namespace {

/** What a non-regular file is, for the message that refuses it as an output. */
std::string kindOf(mode_t mode) {
    if (S_ISCHR(mode)) return "a character device";
    if (S_ISBLK(mode)) return "a block device";
    if (S_ISFIFO(mode)) return "a FIFO";
    if (S_ISSOCK(mode)) return "a socket";
    if (S_ISDIR(mode)) return "a folder";
    return "not a regular file";
}

void requireRegularFileOrNewName(const fs::path& path, const std::string& who, const std::string& what) {
    struct stat status {};
    if (::stat(path.c_str(), &status) != 0) return; // a new name (a dangling link is replaced by the file)
    if (S_ISDIR(status.st_mode)) throw FileError(who + ": " + what + " is a folder; give a file name");
    if (!S_ISREG(status.st_mode))
        throw FileError(who + ": " + what + " is " + kindOf(status.st_mode) +
                        "; outputs are written as new files and renamed into place, which would replace it, so give "
                        "the name of a regular file or a new one");
}

void requireWritableFolder(const fs::path& folder, const std::string& who, const std::string& what) {
    std::error_code error;
    if (!fs::is_directory(folder, error))
        throw FileError(who + ": the folder of " + what + " (" + detail::quotedFileName(folder.string()) +
                        ") does not exist" +
                        (error && error != std::errc::no_such_file_or_directory ? ": " + error.message() : ""));
    if (const int reason = creationErrorIn(folder))
        throw FileError(who + ": cannot write into the folder of " + what + " (" +
                        detail::quotedFileName(folder.string()) + "): " + std::strerror(reason));
}

/** The rename at the end would fail on a name the file system cannot hold: said now, before any work. */
void requireNameFits(const fs::path& path, const std::string& who, const std::string& what) {
    const std::string name = path.filename().string();
    const long limit = ::pathconf(folderOf(path).c_str(), _PC_NAME_MAX);
    if (limit > 0 && name.size() > std::size_t(limit))
        throw FileError(who + ": " + what + ": its file name is " + std::to_string(name.size()) +
                        " bytes; this file system holds names of at most " + std::to_string(limit));
}

} // namespace

fs::path folderOf(const fs::path& path) { return path.has_parent_path() ? path.parent_path() : fs::path("."); }

void requireOutputPlace(const fs::path& path, const std::string& who, const std::string& what) {
    requireRegularFileOrNewName(path, who, what);
    requireWritableFolder(folderOf(path), who, what);
    requireNameFits(path, who, what);
}

} // namespace inkgraph
