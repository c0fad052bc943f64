#pragma once
/** @file --dump DIR as one transaction: the new dump is written whole into a staging folder beside DIR and swapped
 *  in with one rename (renameat2 RENAME_EXCHANGE when DIR holds an earlier dump), so after any crash DIR holds
 *  either the earlier dump or the new one, whole. (On a file system without RENAME_EXCHANGE, such as NFS, the swap is
 *  two renames: a crash between them leaves no DIR, never a mix.)
 *
 *  The staging folder is ".inkgraph-dump-<host>-<pid>-<n>" in DIR's parent and holds the marker file
 * ".inkgraph-staging". A later run removes such a folder only when both hold (its name and its marker) and process
 * <pid> is gone, and then only the plain files directly inside it, the marker last and only once they are all gone (a
 * file that could not be removed is tried again by the next run): nothing is ever deleted because a file's content says
 * so. An earlier dump is recognised by its manifest.json, whose "files" must all be plain names (no separators) of
 *  regular files the folder holds, with nothing else beside them.
 *
 *  DIR is locked (flock) from the check until the commit ends: a second run on the same folder is refused at once,
 *  naming it, instead of mixing its files in. */

#include "app/FileLock.h"
#include "render/InputFiles.h"

#include <sys/types.h>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace inkgraph {

/** The marker of a staging folder (app/DumpFolder.h). Tolerated inside a dump: a crash between the swap and its
 *  removal leaves it there. */
inline constexpr const char* kStagingMarker = ".inkgraph-staging";

/** The files of an earlier dump in `folder` (manifest.json included), or why `folder` is not one: every entry of
 *  the manifest's "files" must be a plain file name (no '/', not "." or "..") of a regular file in `folder` or of
 *  none (a file lost since: the dump is damaged, still a dump, and `files` leaves it out), and `folder` may hold
 *  nothing else but the staging marker. */
struct EarlierDump {
    std::vector<std::string> files; ///< valid when `problem` is empty
    std::string problem;            ///< e.g. "its manifest.json names '../x', which is not a plain file name"
};
EarlierDump readEarlierDump(const std::filesystem::path& folder);

/** Removes, in `parent`, the staging folders of inkgraph runs that no longer run (app/DumpFolder.h). */
void sweepStaleStagingFolders(const std::filesystem::path& parent);

class DumpFolder {
public:
    /** Checks `--dump` `flagValue` (a new name, an empty folder or an earlier dump; its parent writable and on the
     *  same file system; neither it nor the earlier dump's files immutable or append-only, which the commit could not
     *  move or remove), creates it and its missing parents when needed (removed again on failure), locks it, sweeps
     *  stale staging folders beside it and makes this run's. Throws FileError naming --dump and the problem. */
    explicit DumpFolder(const std::string& flagValue);
    ~DumpFolder();
    DumpFolder(const DumpFolder&) = delete;
    DumpFolder& operator=(const DumpFolder&) = delete;

    /** The folder as given on the command line, for messages. */
    const std::string& shownName() const { return mShownName; }
    /** The folder itself, links resolved. */
    const std::filesystem::path& folder() const { return mFolder; }
    /** Where the file `name` of the new dump is to be written before the swap. */
    std::filesystem::path stage(const std::string& name);
    /** The files of the earlier dump the commit will replace (none for a new or empty folder). */
    const std::vector<std::string>& earlierFiles() const { return mEarlierFiles; }

    // The commit, in steps (app/OutputFiles.cpp runs them with the other outputs and undoes them on failure):
    /** Puts the staging marker into an earlier dump, so that once swapped out it is recognised as ours. */
    void markEarlier();
    /** Swaps the staging folder in (RENAME_EXCHANGE with an earlier dump; rename over an empty folder). */
    void swapIn();
    /** Undoes swapIn() and markEarlier(): the earlier dump is back in place, the new one in staging. */
    void undo();
    /** After the swap: removes the marker from the new dump and the earlier dump's files from beside it. Errors are
     *  left for a later run's sweep: the dump itself is committed. Returns false when something was left. */
    bool finish();

private:
    void check(const std::string& flagValue);
    /** Removes what this run made (staging, folders it created) unless the dump was swapped in; lets the lock go. */
    void abandon();

    std::string mShownName;
    std::filesystem::path mFolder;
    /** mFolder's parent (O_PATH), where the staging and set-aside folders lie: held from the check until abandon(), so
     *  the undo and the tidying act there even if the user moves it away during the commit. */
    int mParent = -1;
    /** The earlier dump's folder and the staging folder (the new dump), O_PATH: their markers are put and removed
     *  through these, wherever the user has moved or renamed them. -1 when there is none. */
    int mEarlierFolder = -1;
    int mStagingFolder = -1;
    std::filesystem::path mStaging;
    std::filesystem::path mAside; ///< where the earlier dump is after the swap (mStaging when exchanged)
    std::vector<std::string> mEarlierFiles;
    std::vector<std::string> mStagedNames;
    bool mHadEarlierDump = false;
    mode_t mFolderMode = 0;
    uid_t mFolderOwner = 0;
    gid_t mFolderGroup = 0;
    FileLock mLock;
    bool mTakenByAnotherRun = false; ///< its lock was held: never remove what this run created of it
    /** A folder this run created, and which inode it was: on failure it is removed only if its name still holds
     *  that one (never a folder the user made at the name after moving this run's away). */
    struct CreatedFolder {
        std::filesystem::path path;
        dev_t device = 0;
        ino_t inode = 0;
    };
    std::vector<CreatedFolder> mCreatedFolders; ///< innermost first; removed on failure when empty
    bool mMarked = false;
    bool mSwapped = false;
    bool mExchanged = true; ///< false: swapped by two renames (no RENAME_EXCHANGE on this file system)
    bool mFinished = false;
};

} // namespace inkgraph
