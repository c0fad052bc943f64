#pragma once
/** @file Every output of one run as a transaction. The constructor checks every output place before any work:
 *  outputs are regular files or new names (a device, FIFO or socket is refused: render/OutputPlace.h, whose rule the
 *  library's writes follow too), never one another, never a file the run reads (refuseInputs(), compared by device
 *  and inode). Files are then staged under temporary names, the dump in a staging folder (app/DumpFolder.h), and
 *  only commit() puts them in place: all of them, or, when any step fails, none (the steps done are undone). A run
 *  that fails at any point changes none of the user's files, and a signal removes what was staged
 *  (render/TemporaryFiles.h). A crash (kill -9) inside the commit leaves each output whole, old or new, and the next
 * run sweeps what the crash left.
 *
 *  Test hooks (tests/app/OutputTransactionGLTest.cpp): INKGRAPH_TEST_COMMIT_KILL=N ends the process with SIGKILL
 *  after the commit's N-th step, INKGRAPH_TEST_COMMIT_FAIL=N fails the commit there (both say on stderr which step it
 *  was), INKGRAPH_TEST_COMMIT_INTERRUPT=N sends the process SIGINT there (it must land after the commit). */

#include "app/DumpFolder.h"
#include "flags/Options.h"
#include "render/InputFiles.h"

#include <opencv2/core.hpp>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace inkgraph {

/** The files a render reads that its options name: the model, then inputsNamedBesidesModel(). */
std::vector<RunInput> inputsNamedBy(const RenderOptions& options);
/** The files every still of a run reads, whichever its model: --shademap, --outline-width-map's image, --style and
 *  --list (unless "-"). */
std::vector<RunInput> inputsNamedBesidesModel(const RenderOptions& options);

class OutputSet {
public:
    /** Throws UsageError when outputs collide (with each other, with the inputs the options name, or inside --dump
     *  DIR) and FileError when an output place cannot be written or is not a regular file, naming the flag and the
     *  path. May create DIR (removed again if the run fails). */
    explicit OutputSet(const RenderOptions& options);
    ~OutputSet();
    OutputSet(const OutputSet&) = delete;
    OutputSet& operator=(const OutputSet&) = delete;

    /** Throws UsageError when an output, or a file the commit would replace in --dump DIR, is one of `inputs`. The
     *  model, --shademap, --style and --list are checked by the constructor; the app adds what loading found. */
    void refuseInputs(const std::vector<RunInput>& inputs) const;

    void stageFinalImage(const std::vector<unsigned char>& encoded); ///< -o, as encodeImageFile() encoded it
    void stageStats(const std::string& json);                        ///< --stats
    void stageGraphviz(const std::string& dot);                      ///< --graphviz
    void stageContactSheet(const cv::Mat& image);                    ///< --contact-sheet
    void stageSvg(const std::string& svg);                           ///< --svg
    void stageStrokes(const std::string& json);                      ///< --strokes
    void stageDumpImage(const std::string& fileName, const cv::Mat& image);
    void stageDumpManifest(const std::string& json);

    /** Puts everything staged in place, or nothing (throws FileError). The files it replaced keep a second name
     *  until removeReplaced() or the destructor. */
    void commit();
    /** After commit(): removes the second names that kept the files it replaced, which frees their data (about half a
     *  millisecond a file on a VM's disk, so a batch leaves it to another thread: app/Render.cpp). */
    void removeReplaced();

private:
    struct Output {
        std::string flag;
        std::filesystem::path destination;
        std::filesystem::path temporary; ///< empty until staged
        std::filesystem::path backup;    ///< a hard link to the file it replaces, during the commit
        bool moved = false;
    };
    Output& output(const std::string& flag);
    void stageBytes(const std::string& flag, const void* data, std::size_t byteCount);
    void stageImage(const std::string& flag, const cv::Mat& image);
    void undo();

    std::vector<Output> mOutputs; ///< -o, --stats, --graphviz, --contact-sheet, --svg, as given
    std::optional<DumpFolder> mDump;
    bool mCommitted = false;
};

} // namespace inkgraph
