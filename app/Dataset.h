#pragma once
/** @file `--dataset DIR` and `--resume` (docs/datasets.md): a run as a data set that survives a crash.
 *
 *  Every output lies inside DIR. After each still's outputs are committed (app/OutputFiles.h), one line is appended to
 *  the journal DIR/.inkgraph/journal[-K-of-N].jsonl: the still's key (model, list position, view), its settings
 *  digest, its files relative to DIR with their sizes and checksums, its camera and look. The line is one write(2)
 *  with O_APPEND, then fdatasync: a kill leaves it whole or torn, and a torn or unparsable line is ignored (and a torn
 *  tail cut off before the next append). At the end of the run the index DIR/index[-K-of-N].jsonl (one such record per
 *  still, in list order, failures included) and the card DIR/README[-K-of-N].md are written, each through a temporary
 *  and a rename, and only then is the journal removed.
 *
 *  With --resume a still is skipped when the journal or the index holds its key with the same settings digest and
 *  every recorded file is there with its size and checksum; its record is carried into the new index. Nothing in the
 *  index or the card depends on timing or on whether the run was resumed.
 *
 *  Test hooks (tests/app/dataset-kill-test.sh): INKGRAPH_TEST_JOURNAL_KILL=N ends the process with SIGKILL just before
 *  the N-th journal line of the run is written (its still committed, not journaled); INKGRAPH_TEST_JOURNAL_TEAR=N
 *  writes the first half of the N-th line, then SIGKILL; INKGRAPH_TEST_LOCK_FOLDER_REMOVED=N removes DIR/.inkgraph
 *  between its making and the lock's opening N times, as a run of the data set that finishes then does. */

#include "app/Batch.h"
#include "app/FileLock.h"
#include "flags/Options.h"

#include <nlohmann/json.hpp>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <map>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

namespace inkgraph {

/** Which still of a run: its model, its place in the whole list and its view (0 without --views). */
struct StillKey {
    std::string model;
    std::size_t position = 0;
    std::size_t view = 0;
    bool operator<(const StillKey& other) const {
        return std::tie(position, view, model) < std::tie(other.position, other.view, other.model);
    }
};

/** FNV-1a, 64 bits, continuing from `hash`: the data set's file checksum and settings digest. */
std::uint64_t fnv1a64(const void* data, std::size_t byteCount, std::uint64_t hash = 0xcbf29ce484222325ULL);
/** A 64-bit value as 16 lowercase hex digits. */
std::string hexDigits(std::uint64_t value);
/** The file's size and FNV-1a checksum, read in blocks; nullopt when it cannot be read. */
struct FileChecksum {
    std::uintmax_t size = 0;
    std::string fnv1a64; ///< hexDigits()
};
std::optional<FileChecksum> fileChecksum(const std::filesystem::path& path);

/** The whole text of one of the data set's own files (an index, a journal, a card); nullopt when there is none.
 *  Throws FileError, naming `function` and the file, for a link, a FIFO, a device or a folder in its place: such a file
 *  is never the data set's own (a FIFO would block the read forever, /dev/zero fill the memory, and a link lead the
 *  journal's writes and cuts to a file outside the set). */
std::optional<std::string> readDatasetFile(const std::filesystem::path& path, const std::string& function);

/** The flags the settings digest leaves out: they change how the run goes, not what a still writes. */
const std::vector<std::string>& flagsOutsideDigest();

/** "-K-of-N" with --shard, else "": the suffix of this process's journal, index and card. */
std::string shardSuffix(const RenderOptions& options);

/** A shell word for `argument`: as it is when it needs no quoting, else in single quotes. */
std::string shellWord(const std::string& argument);

/** One --dataset run. */
class DatasetRun {
public:
    /** Checks the run against DIR before any work: every output path of every still (`stills` of `list`) inside DIR
     * (and not its .inkgraph folder, index or card), DIR not holding a data set unless --resume (then the journal and
     * the index of this shard are read). `givenArguments` are the arguments after "render" as typed (for the card),
     *  `expandedArguments` the same with --style's settings (for the digest). Throws UsageError naming the flag. */
    DatasetRun(const RenderOptions& options, const BatchList& list, const std::vector<BatchStill>& stills,
               std::vector<std::string> givenArguments, const std::vector<std::string>& expandedArguments);
    /** Lets go of this split's lock (removing its file, and the .inkgraph folder when that leaves it empty). */
    ~DatasetRun();
    DatasetRun(const DatasetRun&) = delete;
    DatasetRun& operator=(const DatasetRun&) = delete;

    /** The settings digest of one still: the canonical options, the still's outputs relative to DIR, the model's and
     *  its named files' size and modification time, those of any file a flag names, the view index and its sampled
     *  view (--views, --seed and their companions are among the options), and the inkgraph version. */
    std::string settingsDigest(const StillKey& key, const RenderOptions& still) const;

    /** Whether --resume may skip the still: an earlier record of `key` with `digest` whose files are all whole.
     *  Counts it, and keeps its record for the index. */
    bool isComplete(const StillKey& key, const std::string& digest);

    /** Makes the folders inside DIR that the still's outputs go into (its -o's folder, --dump's parent, ...), so a
     *  data set's layout ('{name}/{view}.png') needs no folders made by hand. Only before the still renders, so a
     *  still that --resume skips makes none. Throws FileError naming the folder. */
    void makeOutputFolders(const RenderOptions& still) const;

    /** After the still's outputs were committed: appends its journal line. Throws FileError. */
    void recordCommitted(const StillKey& key, const RenderOptions& still, const std::string& digest,
                         const nlohmann::ordered_json& camera, const nlohmann::ordered_json& look);
    /** A still that failed (bad input): in the index as "failed" with `error`; not journaled (a resumed run tries it
     *  again and fails the same way). */
    void recordFailed(const StillKey& key, const RenderOptions& still, const std::string& error);

    /** Every still done: writes the index and the card, removes the journal, sweeps temporaries left under DIR by
     *  killed runs; with --resume tells `log` how many stills were complete and how many rendered. */
    void finish(std::ostream& log);

    const std::filesystem::path& folder() const { return mFolder; }

private:
    std::filesystem::path journalPath() const;
    std::filesystem::path indexPath() const;
    std::filesystem::path cardPath() const;
    std::string relativeToDataset(const std::string& path) const;
    void readEarlierRecords();
    /** Throws UsageError when DIR holds an index, card or journal of another split, or one of this split without
     *  --resume. */
    void refuseOtherRunsFiles() const;
    /** Takes DIR/.inkgraph/lock[-K-of-N]; throws FileError when another run holds it. */
    void lockThisSplit();
    /** Lets go of the lock and removes its file; `finished`: the run wrote its index (else the .inkgraph folder goes
     *  only when this run made it, and DIR's modification time is put back when nothing else changed it). */
    void letGoOfThisSplit(bool finished);
    std::string cardText(std::size_t models, std::size_t stills, std::size_t failed) const;

    RenderOptions mOptions;
    std::filesystem::path mFolder; ///< DIR, links resolved
    std::string mSuffix;
    std::vector<std::string> mGivenArguments;
    std::vector<std::pair<std::string, std::string>> mCanonicalSettings; ///< (flag, value), sorted by flag
    mutable std::map<std::string, std::vector<std::string>> mNamedFiles; ///< each .gltf's or .obj's named files
    std::map<StillKey, nlohmann::ordered_json> mEarlier;                 ///< --resume: journal over index
    std::map<StillKey, nlohmann::ordered_json> mRecords;                 ///< this run's index, by key
    std::size_t mModelCount = 0;                                         ///< this process's share of the list
    std::size_t mListLength = 0; ///< the whole list's length (--stats' batch.list_length): in the digest
    std::size_t mSkipped = 0;
    std::size_t mRendered = 0;
    int mJournalLines = 0;
    int mKillBeforeLine = 0;
    int mTearLine = 0;
    bool mMadeJournalFolder = false;                                          ///< DIR/.inkgraph was made by this run
    mutable bool mMadeOutputFolder = false;                                   ///< makeOutputFolders() made one
    std::optional<std::filesystem::file_time_type> mFolderModifiedBeforeLock; ///< DIR's, before .inkgraph was made
    std::optional<std::filesystem::file_time_type> mFolderModifiedWithLock;   ///< DIR's, once the lock was taken
    FileLock mLock; ///< held from the constructor's checks until finish() or destruction
};

} // namespace inkgraph
