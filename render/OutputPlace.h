#pragma once
/** @file The rule for the place of every file inkgraph writes, the command line's outputs (app/OutputFiles.h) and the
 *  library's (writeImage(), writeTextFile(): Image::write(), Still::write(), Python's write_image()). A file is
 *  written under a temporary name beside its place and renamed over it, so the place must be a regular file or a new
 *  name, judged through links: a device, a FIFO or a socket would be replaced by a regular file (as root, writing
 *  to /dev/null or to a `mknod x.png c 1 3` replaced the device). Its folder must be writable and its name must fit
 *  the file system, both said before any work rather than by the rename at the end. */

#include <filesystem>
#include <string>

namespace inkgraph {

/** The folder a file named `path` is written in: its parent, or "." for a bare name. */
std::filesystem::path folderOf(const std::filesystem::path& path);

/** Throws FileError "<who>: <what> is a FIFO; ..." (a folder, a device, a socket likewise), or naming the folder
 *  that does not exist or cannot be written, or the name too long for the file system. `what` names the output as
 *  the caller's user knows it ("-o 'x.png'", "'x.png'"). A dangling link is a new name: the file replaces the link. */
void requireOutputPlace(const std::filesystem::path& path, const std::string& who, const std::string& what);

} // namespace inkgraph
