#include "app/OutputFiles.h"

#include "render/ImageFiles.h"
#include "render/OutputPlace.h"
#include "render/TemporaryFiles.h"
#include "scene/MessageText.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <stdexcept>
#include <system_error>
#include <utility>

namespace inkgraph {
namespace fs = std::filesystem;
namespace {

bool isInside(const fs::path& path, const fs::path& folder) {
    const fs::path relative = path.lexically_relative(folder);
    return !relative.empty() && *relative.begin() != "..";
}

/** Leftover files of killed runs (".inkgraph-<host>-<pid>-..." made here whose process is gone) are removed when we
 * meet them: plain files only, never a folder of that name (app/DumpFolder.h sweeps staging folders by their marker).
 */
void sweepStaleTemporaries(const fs::path& folder) {
    std::error_code error;
    for (fs::directory_iterator it(folder, error), end; !error && it != end; it.increment(error)) {
        if (!isStaleTemporary(it->path().filename().string())) continue;
        struct stat status {};
        if (::lstat(it->path().c_str(), &status) == 0 && S_ISREG(status.st_mode)) ::unlink(it->path().c_str());
    }
}

/** The commit's test hooks: INKGRAPH_TEST_COMMIT_KILL / _FAIL / _INTERRUPT / _MOVE = the step after which to stop
 *  the process, fail the commit, send the process SIGINT, or rename the first output's folder (the --dump folder itself
 *  when --dump is the only output) to "<folder>.moved", as a user moving it away during a batch. */
class CommitSteps {
public:
    explicit CommitSteps(fs::path outputFolder)
        : mKillAfter(stepFrom("INKGRAPH_TEST_COMMIT_KILL")), mFailAfter(stepFrom("INKGRAPH_TEST_COMMIT_FAIL")),
          mInterruptAfter(stepFrom("INKGRAPH_TEST_COMMIT_INTERRUPT")),
          mMoveAfter(stepFrom("INKGRAPH_TEST_COMMIT_MOVE")), mOutputFolder(std::move(outputFolder)) {}

    /** A step that can still be undone. */
    void done(const std::string& step) {
        doneAfterCommit(step);
        if (mCount == mFailAfter)
            throw FileError("OutputSet::commit(): test hook: failed after commit step " + std::to_string(mCount) +
                            " (" + step + ")");
    }

    /** A step after the commit point: it can be killed, not failed. */
    void doneAfterCommit(const std::string& step) {
        ++mCount;
        if (mCount == mInterruptAfter) ::kill(::getpid(), SIGINT); // to the process: any thread may take it
        if (mCount == mMoveAfter) {
            fs::path moved = mOutputFolder;
            moved += ".moved";
            ::rename(mOutputFolder.c_str(), moved.c_str());
        }
        if (mCount == mKillAfter) {
            std::cerr << "inkgraph: test hook: killed after commit step " << mCount << " (" << step << ")" << std::endl;
            ::kill(::getpid(), SIGKILL);
        }
    }

private:
    static int stepFrom(const char* variable) {
        const char* value = std::getenv(variable);
        return value ? std::atoi(value) : 0;
    }
    int mKillAfter;
    int mFailAfter;
    int mInterruptAfter;
    int mMoveAfter;
    fs::path mOutputFolder;
    int mCount = 0;
};

} // namespace

OutputSet::OutputSet(const RenderOptions& options) {
    for (const auto& [flag, field] : outputPathFlags())
        if (flag != "--dump" && !(options.*field).empty()) mOutputs.push_back({flag, options.*field, {}, {}, false});

    // Collisions first: they are mistakes in the command line, whatever the file system says.
    for (std::size_t i = 0; i < mOutputs.size(); ++i) {
        const Output& file = mOutputs[i];
        const fs::path path = resolvedPath(file.destination);
        for (std::size_t j = i + 1; j < mOutputs.size(); ++j)
            if (isSameFile(file.destination, mOutputs[j].destination))
                throw UsageError(file.flag + " and " + mOutputs[j].flag + " name the same file " +
                                 detail::quotedFileName(file.destination.string()));
        if (!options.dumpDirectory.empty() && isInside(path, resolvedPath(options.dumpDirectory)))
            throw UsageError(file.flag + " " + detail::quotedFileName(file.destination.string()) +
                             " lies inside --dump " + detail::quotedFileName(options.dumpDirectory) +
                             ", whose contents each dump replaces; write it elsewhere");
    }
    const std::vector<RunInput> inputs = inputsNamedBy(options);
    refuseInputs(inputs);

    for (const Output& file : mOutputs) {
        const std::string what = file.flag + " " + detail::quotedFileName(file.destination.string());
        requireOutputPlace(file.destination, "checkOutputs()", what);
        sweepStaleTemporaries(folderOf(file.destination));
    }
    if (!options.dumpDirectory.empty()) {
        mDump.emplace(options.dumpDirectory);
        refuseInputs(inputs); // the files of an earlier dump are known now
    }
}

std::vector<RunInput> inputsNamedBy(const RenderOptions& options) {
    std::vector<RunInput> inputs = {{options.modelPath, "the model itself"}};
    for (RunInput& input : inputsNamedBesidesModel(options)) inputs.push_back(std::move(input));
    return inputs;
}

std::vector<RunInput> inputsNamedBesidesModel(const RenderOptions& options) {
    std::vector<RunInput> inputs;
    if (!options.look.shadeMapPath.empty()) inputs.push_back({options.look.shadeMapPath, "the --shademap itself"});
    // A model image's name is no file: the identity check skips it.
    if (options.look.outlineWidthMap.source == WidthMap::Source::Texture)
        inputs.push_back({options.look.outlineWidthMap.texture, "the --outline-width-map image"});
    if (!options.stylePath.empty()) inputs.push_back({options.stylePath, "the --style file"});
    if (!options.listPath.empty() && options.listPath != "-") inputs.push_back({options.listPath, "the --list file"});
    return inputs;
}

void OutputSet::refuseInputs(const std::vector<RunInput>& inputs) const {
    for (const Output& file : mOutputs)
        refuseInputAsOutput(file.destination, file.flag + " " + detail::quotedFileName(file.destination.string()),
                            inputs);
    if (!mDump) return;
    for (const RunInput& input : inputs) {
        const auto identity = fileIdentity(input.path);
        if (!identity) continue;
        for (const std::string& name : mDump->earlierFiles())
            if (fileIdentity(mDump->folder() / name) == identity)
                throw UsageError("--dump " + detail::quotedFileName(mDump->shownName()) + " holds " +
                                 detail::quotedFileName(name) + ", which is " + input.what +
                                 ", and a dump replaces its folder's files; choose another folder");
    }
}

OutputSet::~OutputSet() {
    if (mCommitted) {
        removeReplaced();
        return;
    }
    for (const Output& file : mOutputs)
        if (!file.temporary.empty()) removeTemporary(file.temporary);
}

OutputSet::Output& OutputSet::output(const std::string& flag) {
    for (Output& file : mOutputs)
        if (file.flag == flag) return file;
    throw std::logic_error("OutputSet::output(): '" + flag + "' was not given");
}

void OutputSet::stageBytes(const std::string& flag, const void* data, std::size_t byteCount) {
    Output& file = output(flag);
    const fs::path temporary = temporarySibling(file.destination);
    writeBytes(temporary, data, byteCount, file.destination.string());
    file.temporary = temporary;
}

void OutputSet::stageImage(const std::string& flag, const cv::Mat& image) {
    Output& file = output(flag);
    const fs::path temporary = temporarySibling(file.destination);
    writeImageTo(temporary, file.destination, image);
    file.temporary = temporary;
}

void OutputSet::stageFinalImage(const std::vector<unsigned char>& encoded) {
    stageBytes("-o", encoded.data(), encoded.size());
}
void OutputSet::stageStats(const std::string& json) { stageBytes("--stats", json.data(), json.size()); }
void OutputSet::stageGraphviz(const std::string& dot) { stageBytes("--graphviz", dot.data(), dot.size()); }
void OutputSet::stageContactSheet(const cv::Mat& image) { stageImage("--contact-sheet", image); }
void OutputSet::stageSvg(const std::string& svg) { stageBytes("--svg", svg.data(), svg.size()); }
void OutputSet::stageStrokes(const std::string& json) { stageBytes("--strokes", json.data(), json.size()); }

void OutputSet::stageDumpImage(const std::string& fileName, const cv::Mat& image) {
    writeImageTo(mDump->stage(fileName), mDump->folder() / fileName, image);
}

void OutputSet::stageDumpManifest(const std::string& json) {
    writeBytes(mDump->stage("manifest.json"), json.data(), json.size(), (mDump->folder() / "manifest.json").string());
}

void OutputSet::undo() {
    for (auto file = mOutputs.rbegin(); file != mOutputs.rend(); ++file) {
        // One step each, so no moment lacks the destination: the old file renamed back over our new one, or our new
        // one removed where there was none. Each in the folder the files were made in, wherever it is now: a folder
        // moved during the commit gets its old files back too.
        if (file->moved && !file->backup.empty()) {
            if (renameTemporary(file->backup, file->destination)) {
                file->backup.clear();
                file->moved = false;
            } else {
                // The backup is the replaced file's only name now: kept (a signal no longer removes it), and told.
                std::cerr << "inkgraph: the earlier " << file->flag << " '" << file->destination.string()
                          << "' could not be put back (" << std::strerror(errno) << "); it is kept beside it as '"
                          << file->backup.filename().string() << "'" << std::endl;
                forgetTemporary(file->backup);
                file->backup.clear();
            }
        } else if (file->moved && removeBesideTemporary(file->temporary, file->destination)) {
            file->moved = false;
        }
        if (!file->backup.empty()) removeTemporary(file->backup); // a second name of the file still in place
        file->backup.clear();
    }
    if (mDump) mDump->undo();
}

void OutputSet::commit() {
    const SignalsDeferred signalsDeferred; // a Ctrl-C lands after the commit, with every output old or every one new
    CommitSteps steps(!mOutputs.empty() ? mOutputs.front().destination.parent_path()
                      : mDump           ? mDump->folder()
                                        : fs::path());
    try {
        steps.done("everything staged");
        if (mDump) {
            mDump->markEarlier();
            steps.done("earlier dump marked");
        }
        for (Output& file : mOutputs) {
            if (file.temporary.empty() || !fs::exists(fs::symlink_status(file.destination))) continue;
            // A second name for the file being replaced, so a failure further on can put it back.
            const fs::path backup = temporarySibling(file.destination);
            const TemporaryCreation creating;
            if (::link(file.destination.c_str(), backup.c_str()) == 0) {
                file.backup = backup;
                // Until removeReplaced(), which may come after the commit: a signal then removes it with the rest.
                registerTemporary(backup);
            } else if (errno != EPERM && errno != EOPNOTSUPP && errno != EMLINK) {
                // (Those three: a file system without hard links. The file is then replaced without a way back.)
                throw FileError("OutputSet::commit(): cannot keep the earlier " + file.flag + " " +
                                detail::quotedFileName(file.destination.string()) +
                                " until the commit ends: " + std::strerror(errno));
            }
            steps.done("earlier " + file.flag + " kept");
        }
        if (mDump) {
            mDump->swapIn();
            steps.done("dump swapped in");
        }
        for (Output& file : mOutputs) {
            if (file.temporary.empty()) continue;
            if (::rename(file.temporary.c_str(), file.destination.c_str()) != 0)
                throw FileError("OutputSet::commit(): cannot move the finished file into place as " +
                                detail::quotedFileName(file.destination.string()) + ": " + std::strerror(errno));
            file.moved = true;
            steps.done(file.flag + " moved into place");
        }
    } catch (...) {
        undo();
        throw;
    }
    // Committed. What is left is tidying: a crash here leaves names the next run sweeps.
    mCommitted = true;
    for (Output& file : mOutputs) forgetTemporary(file.temporary);
    if (mDump) {
        mDump->finish();
        steps.doneAfterCommit("dump tidied");
    }
}

void OutputSet::removeReplaced() {
    if (!mCommitted) throw std::logic_error("OutputSet::removeReplaced(): nothing is committed yet");
    for (Output& file : mOutputs) {
        if (file.backup.empty()) continue;
        removeTemporary(file.backup);
        file.backup.clear();
    }
}

} // namespace inkgraph
