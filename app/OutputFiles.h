#pragma once
/** @file Where a run's outputs go, checked before any work, and the --dump folder, replaced as a whole when the run
 *  has written everything (a failed run leaves the old folder, or none, never a mix of two runs). */

#include "app/Options.h"

#include <filesystem>
#include <string>

namespace inkgraph {

class OutputPlan {
public:
    explicit OutputPlan(const RenderOptions& options) : mOptions(options) {}

    /** Throws FileError naming the flag and the path when -o, --stats, --graphviz or --dump cannot be written:
     *  a missing or unwritable folder, a folder where a file is expected, a --dump folder holding other files. */
    void checkAll() const;

private:
    const RenderOptions& mOptions;
};

class DumpFolder {
public:
    /** Files are written into a hidden sibling of `directory` until commit(). */
    explicit DumpFolder(std::filesystem::path directory);
    ~DumpFolder();
    DumpFolder(const DumpFolder&) = delete;
    DumpFolder& operator=(const DumpFolder&) = delete;

    std::filesystem::path path(const std::string& fileName) const { return mStaging / fileName; }
    /** Puts the new folder in place of the old one (if any) and removes the old one. */
    void commit();

private:
    std::filesystem::path mDirectory;
    std::filesystem::path mStaging;
    bool mCommitted = false;
};

/** True when `directory` is a folder written by --dump: it holds a manifest.json with an "inkgraph" entry. */
bool isInkgraphDump(const std::filesystem::path& directory);

} // namespace inkgraph
