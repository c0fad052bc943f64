#include "app/FileLock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <utility>

namespace inkgraph {

namespace {

/** Whether `path` still names the file open as `descriptor` (a folder through links, as it was opened; a lock file,
 *  never opened through one, by its own name). */
bool namesTheSameFile(int descriptor, const std::filesystem::path& path, bool followLinks) {
    struct stat locked {
    }, named{};
    const int found = followLinks ? ::stat(path.c_str(), &named) : ::lstat(path.c_str(), &named);
    return ::fstat(descriptor, &locked) == 0 && found == 0 && locked.st_dev == named.st_dev &&
           locked.st_ino == named.st_ino;
}

} // namespace

FileLock::FileLock(const std::filesystem::path& path, Target target) : mPath(path) {
    const int flags = target == Target::Folder ? O_RDONLY | O_DIRECTORY | O_CLOEXEC
                                               : O_RDWR | O_CREAT | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC;
    for (int attempt = 0; attempt < 10; ++attempt) {
        const int descriptor = ::open(path.c_str(), flags, 0644);
        if (descriptor < 0) {
            mError = errno;
            return;
        }
        struct stat status {};
        if (target == Target::LockFile && (::fstat(descriptor, &status) != 0 || !S_ISREG(status.st_mode))) {
            ::close(descriptor); // a FIFO or a device in its place: never ours to lock
            mError = EINVAL;
            return;
        }
        if (::flock(descriptor, LOCK_EX | LOCK_NB) != 0) {
            mError = errno;
            ::close(descriptor);
            return;
        }
        mFollowsLinks = target == Target::Folder;
        if (namesTheSameFile(descriptor, path, mFollowsLinks)) {
            mDescriptor = descriptor;
            mError = 0;
            return;
        }
        ::close(descriptor);
    }
    mError = ESTALE;
}

FileLock::FileLock(FileLock&& other) noexcept
    : mPath(std::move(other.mPath)), mDescriptor(std::exchange(other.mDescriptor, -1)), mError(other.mError),
      mFollowsLinks(other.mFollowsLinks) {}

FileLock& FileLock::operator=(FileLock&& other) noexcept {
    if (this != &other) {
        release();
        mPath = std::move(other.mPath);
        mDescriptor = std::exchange(other.mDescriptor, -1);
        mError = other.mError;
        mFollowsLinks = other.mFollowsLinks;
    }
    return *this;
}

FileLock::~FileLock() { release(); }

void FileLock::release(bool removeLockFile) {
    if (mDescriptor < 0) return;
    if (removeLockFile && !mFollowsLinks && namesTheSameFile(mDescriptor, mPath, false)) ::unlink(mPath.c_str());
    ::close(mDescriptor);
    mDescriptor = -1;
}

bool isLockHeld(const std::filesystem::path& path) {
    const int descriptor = ::open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
    if (descriptor < 0) return false;
    struct stat status {};
    bool locked = false;
    if (::fstat(descriptor, &status) == 0 && S_ISREG(status.st_mode))
        locked = ::flock(descriptor, LOCK_SH | LOCK_NB) != 0 && errno == EWOULDBLOCK;
    ::close(descriptor); // a shared lock taken only to test is let go with it
    return locked;
}

} // namespace inkgraph
