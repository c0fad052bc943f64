#pragma once
/** @file Every output of one run as a transaction. The constructor checks every output place before any work;
 *  files are then staged under temporary names and only commit() puts them in place, so a run that fails at any
 *  point changes none of the user's files (and a signal removes what was staged: app/TemporaryFiles.h).
 *  --dump DIR is filled from a staging folder inside DIR: at commit the previous dump's files are removed and the
 *  new ones moved in, the manifest last, under a lock on DIR so parallel runs never mix. */

#include "app/Options.h"

#include <opencv2/core.hpp>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace inkgraph {

class OutputSet {
public:
    /** Throws UsageError when outputs collide (with each other, with the model, or inside --dump DIR) and FileError
     *  when an output place cannot be written, naming the flag and the path. May create DIR (removed again if the
     *  run fails). */
    explicit OutputSet(const RenderOptions& options);
    ~OutputSet();
    OutputSet(const OutputSet&) = delete;
    OutputSet& operator=(const OutputSet&) = delete;

    void stageFinalImage(const cv::Mat& image);   ///< -o
    void stageStats(const std::string& json);     ///< --stats
    void stageGraphviz(const std::string& dot);   ///< --graphviz
    void stageContactSheet(const cv::Mat& image); ///< --contact-sheet
    void stageSvg(const std::string& svg);        ///< --svg
    void stageDumpImage(const std::string& fileName, const cv::Mat& image);
    void stageDumpManifest(const std::string& json);

    /** Moves everything staged into place. */
    void commit();

private:
    struct Staged {
        std::filesystem::path temporary;
        std::filesystem::path destination;
    };
    void stageFile(const std::filesystem::path& destination, const cv::Mat* image, const std::string* text);
    void checkDumpFolder();
    void commitDump();

    const RenderOptions& mOptions;
    std::vector<Staged> mFiles;          ///< -o, --stats, --graphviz, --contact-sheet, --svg
    std::vector<std::string> mDumpNames; ///< staged in mStaging, manifest.json last
    std::filesystem::path mDumpDirectory;
    std::filesystem::path mStaging;
    std::vector<std::filesystem::path> mCreatedFolders; ///< outermost last; removed if the run fails
    bool mCommitted = false;
};

/** The place a path names, for comparing outputs and inputs: absolute, with the links that exist resolved (two
 *  spellings of one file compare equal); lexically normalised where it cannot be resolved. */
std::filesystem::path resolvedPath(const std::filesystem::path& path);

/** The files an earlier --dump wrote into `directory` (from its manifest.json, which is included), or nothing when
 *  `directory` holds anything else: then it is not ours to replace. Staging folders of running inkgraph processes
 *  are ignored. */
std::optional<std::vector<std::string>> earlierDumpFiles(const std::filesystem::path& directory);

} // namespace inkgraph
