#pragma once
/** @file The files a render read, and the one rule that no output replaces one of them: the command line's outputs
 *  (app/OutputFiles.h) and the library's Still::write() both keep it. */

#include "scene/Scene.h"

#include <sys/types.h>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace inkgraph {

/** A file a render reads: `what` completes "-o 'x' is ..." (e.g. "the model itself"). */
struct RunInput {
    std::string path;
    std::string what;
};

/** Device and inode: how two spellings, links or hard links of one file compare equal. */
struct FileIdentity {
    dev_t device = 0;
    ino_t inode = 0;
    bool operator==(const FileIdentity& other) const { return device == other.device && inode == other.inode; }
    bool operator<(const FileIdentity& other) const {
        return device != other.device ? device < other.device : inode < other.inode;
    }
};

/** The identity of what `path` names (links followed), or nothing when it does not exist or cannot be reached. */
std::optional<FileIdentity> fileIdentity(const std::filesystem::path& path);

/** The place a path names, for comparing outputs and inputs: absolute, with the links that exist resolved (two
 *  spellings of one file compare equal); lexically normalised where it cannot be resolved. */
std::filesystem::path resolvedPath(const std::filesystem::path& path);

/** One file by two names: the same place once links are resolved, or the same device and inode (a hard link). */
bool isSameFile(const std::filesystem::path& first, const std::filesystem::path& second);

/** Throws UsageError "<shownOutput> is <the input's what>; choose another file" when `output` is one of `inputs`. */
void refuseInputAsOutput(const std::filesystem::path& output, const std::string& shownOutput,
                         const std::vector<RunInput>& inputs);

/** The files a render read that only loading the model revealed: its buffers and images, and the shade maps its
 *  materials name. `modelPath` names the model in each `what`. */
std::vector<RunInput> inputsFoundByLoading(const std::string& modelPath, const Scene& scene);

} // namespace inkgraph
