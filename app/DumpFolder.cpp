#include "app/DumpFolder.h"
#include "app/FileLock.h"

#include "render/ImageFiles.h"
#include "render/TemporaryFiles.h"
#include "scene/MessageText.h"

#include <nlohmann/json.hpp>

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <linux/fs.h>
#include <sys/file.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <set>

namespace inkgraph {
namespace fs = std::filesystem;
namespace {

constexpr const char* kStagingPrefix = ".inkgraph-dump-";
constexpr const char* kManifest = "manifest.json";
/** A manifest is a few KiB; anything far larger is not one of ours and is not read. */
constexpr std::uintmax_t kMaxManifestBytes = std::uintmax_t(16) << 20;

/** A name from a file, quoted in a message: at most 80 bytes of it. */
std::string quotedName(const std::string& name) {
    // Appended, not "'" + name: GCC 12 warns falsely (-Wrestrict, bug 105329) on that inlined.
    std::string quoted = "'";
    if (name.size() <= 80) return quoted.append(detail::oneLineText(name)).append("'");
    return quoted.append(detail::oneLineText(std::string_view(name).substr(0, 60)))
        .append("...' (")
        .append(std::to_string(name.size()))
        .append(" bytes)");
}

bool isPlainFileName(const std::string& name) {
    return !name.empty() && name != "." && name != ".." && name.find('/') == std::string::npos &&
           name.find('\0') == std::string::npos;
}

/** The names in a folder, "." and ".." left out; nothing when it cannot be read. */
std::optional<std::vector<std::string>> namesIn(const fs::path& folder) {
    DIR* directory = ::opendir(folder.c_str());
    if (directory == nullptr) return std::nullopt;
    std::vector<std::string> names;
    while (const dirent* entry = ::readdir(directory)) {
        const std::string name = entry->d_name;
        if (name != "." && name != "..") names.push_back(name);
    }
    ::closedir(directory);
    return names;
}

/** Removes the plain files and links directly inside the folder `folderDescriptor` (never a subfolder, never
 *  anything a link points to), `last` after the others and only when they are all gone: `last` is the staging marker,
 *  which must stay with anything left so that a later run's sweep tries again. */
void removePlainFilesIn(int folderDescriptor, const std::string& last) {
    const int listing = ::dup(folderDescriptor);
    if (listing < 0) return;
    DIR* directory = ::fdopendir(listing);
    if (directory == nullptr) {
        ::close(listing);
        return;
    }
    std::vector<std::string> names;
    while (const dirent* entry = ::readdir(directory)) names.push_back(entry->d_name);
    ::closedir(directory);
    bool removedAll = true;
    for (const std::string& name : names) {
        struct stat status {};
        if (name == "." || name == ".." || name == last) continue;
        if (::fstatat(folderDescriptor, name.c_str(), &status, AT_SYMLINK_NOFOLLOW) != 0) continue;
        if (!(S_ISREG(status.st_mode) || S_ISLNK(status.st_mode)) || ::unlinkat(folderDescriptor, name.c_str(), 0) != 0)
            removedAll = false;
    }
    if (removedAll) ::unlinkat(folderDescriptor, last.c_str(), 0);
}

/** Why a file cannot be removed from its folder, or renamed, whoever asks (root too): its immutable or append-only
 *  attribute (chattr +i, +a), which must be cleared first. Empty when it has neither, or its attributes cannot be
 *  read (a file system without them). */
std::string attributeKeepingInPlace(const fs::path& path) {
    const int file = ::open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
    if (file < 0) return "";
    int attributes = 0; // FS_IOC_GETFLAGS fills an int, whatever its declaration says
    const bool known = ::ioctl(file, FS_IOC_GETFLAGS, &attributes) == 0;
    ::close(file);
    if (known && (attributes & FS_IMMUTABLE_FL)) return "immutable (chattr +i)";
    if (known && (attributes & FS_APPEND_FL)) return "append-only (chattr +a)";
    return "";
}

/** The pid in ".inkgraph-dump-<host>-<pid>-<n>" made on this machine, or 0. */
long stagingFolderPid(const std::string& name) {
    if (name.rfind(kStagingPrefix, 0) != 0) return 0;
    // Exactly "<host>-<digits>-<digits>" after the prefix, as newStagingName() writes it.
    return pidOfNumberedName(name.substr(std::strlen(kStagingPrefix)));
}

fs::path newStagingName(const fs::path& parent) {
    static std::atomic<int> counter{0};
    return parent / (kStagingPrefix + temporaryTag() + "-" + std::to_string(counter++));
}

/** Swaps two names atomically (Linux 3.15 and later; ext4, xfs, btrfs, tmpfs and overlayfs support it); relative
 *  names are looked up in `folder`. */
int exchangeFolders(const fs::path& first, const fs::path& second, int folder = AT_FDCWD) {
    return ::renameat2(folder, first.c_str(), folder, second.c_str(), RENAME_EXCHANGE);
}

/** Test hook (tests/app/OutputTransactionGLTest.cpp): INKGRAPH_TEST_NO_RENAME_EXCHANGE=1 takes the path of file
 *  systems that lack RENAME_EXCHANGE. */
bool exchangeIsUnsupported() {
    const char* value = std::getenv("INKGRAPH_TEST_NO_RENAME_EXCHANGE");
    return value != nullptr && std::string(value) == "1";
}

} // namespace

EarlierDump readEarlierDump(const fs::path& folder) {
    EarlierDump dump;
    const auto names = namesIn(folder);
    if (!names) return {{}, std::string("it cannot be read: ") + std::strerror(errno)};
    std::set<std::string> present(names->begin(), names->end());
    struct stat status {};
    if (present.erase(kStagingMarker) &&
        (::lstat((folder / kStagingMarker).c_str(), &status) != 0 || !S_ISREG(status.st_mode)))
        return {{}, std::string("its ") + kStagingMarker + " is not a file inkgraph wrote"};
    if (present.empty()) return dump;
    if (!present.count(kManifest)) return {{}, "it has no manifest.json"};

    const fs::path manifestPath = folder / kManifest;
    if (::lstat(manifestPath.c_str(), &status) != 0 || !S_ISREG(status.st_mode) ||
        std::uintmax_t(status.st_size) > kMaxManifestBytes)
        return {{}, "its manifest.json is not a file inkgraph wrote"};
    std::ifstream file(manifestPath);
    const auto manifest = nlohmann::json::parse(file, nullptr, false);
    if (!manifest.is_object() || !manifest.contains("inkgraph") || !manifest.contains("files") ||
        !manifest["files"].is_array())
        return {{}, "its manifest.json is not an inkgraph manifest"};
    std::set<std::string> listed = {kManifest};
    for (const auto& entry : manifest["files"]) {
        if (!entry.is_object() || !entry.contains("file") || !entry["file"].is_string())
            return {{}, "its manifest.json has a file entry without a name"};
        const std::string name = entry["file"].get<std::string>();
        if (!isPlainFileName(name))
            return {{}, "its manifest.json names " + quotedName(name) + ", which is not a plain file name"};
        if (::lstat((folder / name).c_str(), &status) != 0) {
            // A file of the dump lost since (deleted, or a copy that stopped short): a damaged dump is still one, so
            // a run, --resume's included, replaces it; what is there is all the manifest's, nothing of the user's.
            if (errno == ENOENT) continue;
            return {{},
                    "its manifest.json names " + quotedName(name) +
                        ", which cannot be looked at: " + std::strerror(errno)};
        }
        if (!S_ISREG(status.st_mode))
            return {{}, "its manifest.json names " + quotedName(name) + ", which is not a file in it"};
        listed.insert(name);
    }
    for (const std::string& name : present)
        if (!listed.count(name))
            return {{}, "it holds " + quotedName(name) + ", which its manifest.json does not name"};
    dump.files.assign(listed.begin(), listed.end());
    return dump;
}

void sweepStaleStagingFolders(const fs::path& parent) {
    const auto names = namesIn(parent);
    if (!names) return;
    for (const std::string& name : *names) {
        const long pid = stagingFolderPid(name);
        if (pid == 0 || !(::kill(pid_t(pid), 0) != 0 && errno == ESRCH)) continue;
        const fs::path path = parent / name;
        const int folder = ::open(path.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
        if (folder < 0) continue;
        struct stat marker {};
        if (::fstatat(folder, kStagingMarker, &marker, AT_SYMLINK_NOFOLLOW) == 0 && S_ISREG(marker.st_mode)) {
            removePlainFilesIn(folder, kStagingMarker);
            ::rmdir(path.c_str()); // fails, and leaves it, if anything else is inside
        } else {
            // Unmarked but empty: killed between the staging folder's mkdir and its marker, or between the marker's
            // removal and the rmdir. It holds nothing, so it goes (rmdir fails on anything that is not empty).
            ::rmdir(path.c_str());
        }
        ::close(folder);
    }
}

DumpFolder::DumpFolder(const std::string& flagValue) : mShownName(flagValue) {
    try {
        check(flagValue);
    } catch (...) {
        abandon(); // a constructor that throws runs no destructor
        throw;
    }
}

void DumpFolder::check(const std::string& flagValue) {
    const std::string what = "--dump " + detail::quotedFileName(flagValue);
    const auto fail = [&](const std::string& problem) { throw FileError("checkOutputs(): " + what + " " + problem); };
    std::error_code error;
    fs::path folder = fs::absolute(flagValue, error);
    if (error) fail("cannot be found: " + error.message());
    folder = folder.lexically_normal();
    if (!folder.has_filename()) folder = folder.parent_path(); // "d/" and "d/." name d itself
    const fs::file_status status = fs::status(folder, error);
    if (error && error != std::errc::no_such_file_or_directory) fail("cannot be read: " + error.message());
    if (!fs::exists(status) && fs::is_symlink(fs::symlink_status(folder)))
        fail("is a link to a folder that does not exist (" + detail::quotedFileName(fs::read_symlink(folder).string()) +
             ")");
    if (fs::exists(status)) {
        if (!fs::is_directory(status)) fail("is a file, not a folder");
        folder = fs::canonical(folder, error); // the swap replaces the folder itself, never a link to it
        if (error) fail("cannot be resolved: " + error.message());
    } else {
        // Created now (its missing parents too), removed again if the run fails; the commit swaps the dump in for it.
        for (fs::path missing = folder; !missing.empty() && !fs::exists(missing, error);
             missing = missing.parent_path())
            mCreatedFolders.push_back({missing});
        {
            const TemporaryCreation creating;
            fs::create_directories(folder, error);
            for (auto created = mCreatedFolders.rbegin(); !error && created != mCreatedFolders.rend(); ++created)
                registerTemporary(created->path);
        }
        if (error) fail("cannot be created: " + error.message());
        for (CreatedFolder& created : mCreatedFolders) {
            struct stat identity {};
            if (::lstat(created.path.c_str(), &identity) != 0) continue; // unknown: never removed
            created.device = identity.st_dev;
            created.inode = identity.st_ino;
        }
    }
    if (folder == folder.root_path()) fail("is the root folder; give a folder of its own");
    mFolder = folder;
    const fs::path parent = folder.parent_path();
    // Held open: the undo, the tidying and the abandoning of a commit act in the folder the dump was staged in, even if
    // the user moves it away meanwhile (the forward steps go by name, so nothing lands in a folder moved away).
    mParent = ::open(parent.c_str(), O_PATH | O_DIRECTORY | O_CLOEXEC);
    if (mParent < 0) fail("cannot be staged: " + detail::quotedFileName(parent.string()) + ": " + std::strerror(errno));

    struct stat folderStatus {
    }, parentStatus{};
    if (::stat(folder.c_str(), &folderStatus) != 0 || ::stat(parent.c_str(), &parentStatus) != 0)
        fail(std::string("cannot be read: ") + std::strerror(errno));
    if (folderStatus.st_dev != parentStatus.st_dev)
        fail("is a mount point; a dump is staged beside its folder and swapped in, so give a folder inside it");
    mFolderMode = folderStatus.st_mode & 07777;
    mFolderOwner = folderStatus.st_uid;
    mFolderGroup = folderStatus.st_gid;
    if (const int reason = creationErrorIn(parent))
        fail("cannot be staged: a dump is written beside its folder, in " + detail::quotedFileName(parent.string()) +
             ", and swapped in whole: " + std::strerror(reason));

    // Locked until the commit ends. The lock is on the folder's inode, and a commit swaps another inode in under the
    // name, so a lock taken on a folder that was swapped out meanwhile is let go and taken again on the new one.
    mLock = FileLock(folder, FileLock::Target::Folder);
    if (!mLock.held()) {
        if (mLock.error() == EWOULDBLOCK) {
            mTakenByAnotherRun = true;
            fail("is being written by another inkgraph run; wait until it has finished, or give another folder");
        }
        if (mLock.error() == ESTALE) fail("keeps being replaced by another run");
        fail(std::string("cannot be locked: ") + std::strerror(mLock.error()));
    }

    sweepStaleStagingFolders(parent);
    const auto names = namesIn(folder);
    mHadEarlierDump = names && !names->empty();
    if (mHadEarlierDump) {
        mEarlierFolder = ::open(folder.c_str(), O_PATH | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
        if (mEarlierFolder < 0) fail("cannot be opened: " + std::string(std::strerror(errno)));
        EarlierDump earlier = readEarlierDump(folder);
        if (!earlier.problem.empty())
            fail("holds files that are not an inkgraph dump (" + earlier.problem +
                 "); give a new or empty folder (each dump replaces the previous one's files)");
        mEarlierFiles = std::move(earlier.files);
    }
    // The commit removes the earlier dump's files once it is swapped out, and moves the folder itself: a file or a
    // folder that refuses (found only after the swap, it used to leave a hidden staging folder and exit 0) is said now.
    if (const std::string why = attributeKeepingInPlace(folder); !why.empty())
        fail("is " + why + "; a dump replaces the folder, so clear the attribute or give another folder");
    for (const std::string& name : mEarlierFiles)
        if (const std::string why = attributeKeepingInPlace(folder / name); !why.empty())
            fail("holds " + quotedName(name) + ", which is " + why +
                 ", and a dump removes the earlier dump's files; clear the attribute or give another folder");

    mStaging = newStagingName(parent);
    const fs::path marker = mStaging / kStagingMarker;
    int markerFile = -1;
    int markerError = 0;
    {
        const TemporaryCreation creating;
        if (::mkdir(mStaging.c_str(), 0700) != 0) fail("cannot be staged: " + std::string(std::strerror(errno)));
        registerTemporary(mStaging);
        mStagingFolder = ::openat(mParent, mStaging.filename().c_str(), O_PATH | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
        if (mStagingFolder >= 0)
            markerFile = ::openat(mStagingFolder, kStagingMarker, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
        if (markerFile >= 0)
            registerTemporary(marker);
        else
            markerError = errno;
    }
    if (markerFile < 0) fail("cannot be staged: " + std::string(std::strerror(markerError)));
    ::close(markerFile);
}

DumpFolder::~DumpFolder() { abandon(); }

void DumpFolder::abandon() {
    if (!mSwapped && !mStaging.empty()) {
        const int staging =
            ::openat(mParent, mStaging.filename().c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
        if (staging >= 0) {
            removePlainFilesIn(staging, kStagingMarker);
            ::close(staging);
        }
        ::unlinkat(mParent, mStaging.filename().c_str(), AT_REMOVEDIR);
        forgetTemporary(mStaging / kStagingMarker);
        forgetTemporary(mStaging);
    }
    // Innermost first, only if empty, and never one another run has locked: a folder this run created but another
    // run locked first is that run's now.
    if (!mSwapped && !mTakenByAnotherRun)
        for (std::size_t i = 0; i < mCreatedFolders.size(); ++i) {
            // The dump folder itself (the innermost) where it now is; its missing parents, above mParent, by name.
            const bool inParent = i == 0 && mParent >= 0;
            const int base = inParent ? mParent : AT_FDCWD;
            const std::string name = inParent ? mFolder.filename().string() : mCreatedFolders[i].path.string();
            struct stat now {};
            if (::fstatat(base, name.c_str(), &now, AT_SYMLINK_NOFOLLOW) == 0 &&
                now.st_dev == mCreatedFolders[i].device && now.st_ino == mCreatedFolders[i].inode)
                ::unlinkat(base, name.c_str(), AT_REMOVEDIR);
        }
    for (const CreatedFolder& created : mCreatedFolders) forgetTemporary(created.path);
    mCreatedFolders.clear();
    mStaging.clear();
    mLock.release();
    for (int* descriptor : {&mParent, &mEarlierFolder, &mStagingFolder}) {
        if (*descriptor >= 0) ::close(*descriptor);
        *descriptor = -1;
    }
}

fs::path DumpFolder::stage(const std::string& name) {
    mStagedNames.push_back(name);
    return mStaging / name;
}

void DumpFolder::markEarlier() {
    if (!mHadEarlierDump) return;
    // Never through a link, never blocking: the check saw a regular file or none, but the folder is the user's.
    const int file =
        ::openat(mEarlierFolder, kStagingMarker, O_WRONLY | O_CREAT | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC, 0644);
    if (file < 0)
        throw FileError("OutputSet::commit(): cannot mark the earlier dump in --dump " +
                        detail::quotedFileName(mShownName) + ": " + std::strerror(errno));
    ::close(file);
    mMarked = true;
}

void DumpFolder::swapIn() {
    const auto fail = [&](int reason) {
        throw FileError("OutputSet::commit(): cannot swap the new dump into --dump " +
                        detail::quotedFileName(mShownName) + ": " + std::strerror(reason));
    };
    // The folder keeps its permissions and owner (the owner only where this process may give it: root).
    ::chmod(mStaging.c_str(), mFolderMode);
    if (::geteuid() == 0) (void)::chown(mStaging.c_str(), mFolderOwner, mFolderGroup);
    if (!mHadEarlierDump) {
        if (::rename(mStaging.c_str(), mFolder.c_str()) != 0) fail(errno);
    } else if (!exchangeIsUnsupported() && exchangeFolders(mStaging, mFolder) == 0) {
        mAside = mStaging;
    } else {
        if (errno != EINVAL && errno != ENOSYS && errno != EOPNOTSUPP && !exchangeIsUnsupported()) fail(errno);
        // A file system without RENAME_EXCHANGE (NFS, some cluster file systems): two renames. A crash between them
        // leaves no DIR, the earlier dump set aside (marked) and the new one staged: never a mix.
        // Unmarked first: should the process die before the second rename, the earlier dump stays set aside under
        // this name for the user to rename back, and no later run's sweep deletes it.
        if (mMarked && ::unlinkat(mEarlierFolder, kStagingMarker, 0) == 0) mMarked = false;
        mAside = newStagingName(mFolder.parent_path());
        if (::rename(mFolder.c_str(), mAside.c_str()) != 0) fail(errno);
        if (::rename(mStaging.c_str(), mFolder.c_str()) != 0) {
            const int reason = errno;
            ::rename(mAside.c_str(), mFolder.c_str());
            fail(reason);
        }
        mExchanged = false;
        // Marked again now that the new dump is in place: from here a crash leaves it for the next run's sweep.
        const int marker = ::openat(mEarlierFolder, kStagingMarker,
                                    O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC, 0644);
        if (marker >= 0) ::close(marker);
    }
    mSwapped = true;
    // The staged names now name the earlier dump's files (or nothing): a signal must not remove them any more.
    for (const std::string& name : mStagedNames) forgetTemporary(mStaging / name);
    forgetTemporary(mStaging / kStagingMarker);
    forgetTemporary(mStaging);
}

void DumpFolder::undo() {
    // By the names in the folder the dump was staged in, wherever it is now (mParent), and the earlier dump's marker
    // in that dump wherever it is.
    const fs::path folder = mFolder.filename(), staging = mStaging.filename(), aside = mAside.filename();
    if (mSwapped) {
        if (!mHadEarlierDump) {
            if (::renameat(mParent, folder.c_str(), mParent, staging.c_str()) == 0) {
                struct stat made {};
                if (::mkdirat(mParent, folder.c_str(), mFolderMode) == 0 && !mCreatedFolders.empty() &&
                    ::fstatat(mParent, folder.c_str(), &made, AT_SYMLINK_NOFOLLOW) == 0) {
                    mCreatedFolders.front().device = made.st_dev; // the folder made again is this run's to remove
                    mCreatedFolders.front().inode = made.st_ino;
                }
                mSwapped = false;
            }
        } else if (mExchanged) {
            if (exchangeFolders(staging, folder, mParent) == 0) mSwapped = false;
        } else if (::renameat(mParent, folder.c_str(), mParent, staging.c_str()) == 0 &&
                   ::renameat(mParent, aside.c_str(), mParent, folder.c_str()) == 0) {
            ::unlinkat(mEarlierFolder, kStagingMarker, 0); // the mark swapIn() gave it once set aside
            mSwapped = false;
        }
    }
    if (mMarked && !mSwapped && ::unlinkat(mEarlierFolder, kStagingMarker, 0) == 0) mMarked = false;
}

bool DumpFolder::finish() {
    bool clean = ::unlinkat(mStagingFolder, kStagingMarker, 0) == 0; // the new dump's: it was the staging folder
    if (!mHadEarlierDump) return clean;
    // The earlier dump, swapped out: only the files it was checked to hold, the marker last.
    const int aside = ::openat(mParent, mAside.filename().c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    if (aside < 0) return false;
    bool removedAll = true;
    for (const std::string& name : mEarlierFiles)
        if (::unlinkat(aside, name.c_str(), 0) != 0 && errno != ENOENT) removedAll = false;
    // The marker stays with a file left, so a later run's sweep removes the rest (sweepStaleStagingFolders()).
    if (removedAll) ::unlinkat(aside, kStagingMarker, 0);
    ::close(aside);
    return ::unlinkat(mParent, mAside.filename().c_str(), AT_REMOVEDIR) == 0 && clean;
}

} // namespace inkgraph
