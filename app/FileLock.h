#pragma once
/** @file One run per folder: an exclusive flock(2) held by the run that writes a --dump folder or a data set's split,
 *  so a second run on it is refused at once instead of mixing its files with the first one's (docs/robustness.md). */

#include <filesystem>

namespace inkgraph {

/** An exclusive, non-blocking flock(2) on a folder or on a plain lock file, held until destruction. */
class FileLock {
public:
    enum class Target {
        Folder,   ///< an existing folder, locked on its own inode
        LockFile, ///< a plain file, created when missing; never followed through a link
    };

    FileLock() = default;
    /** Takes the lock. held() says whether it was taken; when it was not, error() says why: EWOULDBLOCK when another
     *  run holds it, EINVAL when a LockFile's path is not a plain file (a FIFO, a device), ESTALE when the path kept
     *  naming another file after each of 10 locks (a holder that replaces or removes it lets go of an inode that
     *  nobody finds by its name any more, so a lock on it guards nothing), else the errno of open(2) or flock(2). */
    FileLock(const std::filesystem::path& path, Target target);
    FileLock(FileLock&& other) noexcept;
    FileLock& operator=(FileLock&& other) noexcept;
    FileLock(const FileLock&) = delete;
    FileLock& operator=(const FileLock&) = delete;
    ~FileLock();

    bool held() const { return mDescriptor >= 0; }
    int error() const { return mError; }
    /** Lets go of the lock (and closes the descriptor); a LockFile is removed first, while still held, when
     *  `removeLockFile`: a run that waits for it then finds its inode gone from the path and takes a new one. */
    void release(bool removeLockFile = false);

private:
    std::filesystem::path mPath;
    int mDescriptor = -1;
    int mError = 0;
    bool mFollowsLinks = false; ///< a Folder: opened, and checked, through links
};

/** Whether a run (another process, or another FileLock of this one) holds an exclusive flock(2) on the plain file
 *  `path` now; false when there is no such file or it cannot be opened. */
bool isLockHeld(const std::filesystem::path& path);

} // namespace inkgraph
