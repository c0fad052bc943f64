#include "render/TemporaryFiles.h"

#include <fcntl.h>
#include <pthread.h>
#include <sys/stat.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cstdint>
#include <cerrno>
#include <cstring>
#include <mutex>
#include <new>
#include <string>
#include <system_error>
#include <thread>

namespace inkgraph {
namespace {

constexpr int kEntriesPerChunk = 256;
/** Chunks after the first are allocated as a run needs them: a batch of 64 jobs with --dump (the most --jobs allows)
 *  holds about 1,400 temporaries at once, and those past a fixed 256 went unregistered, left behind by a signal. */
constexpr int kMaxChunks = 16;
constexpr std::size_t kMaxPathBytes = 4096;

struct Entry {
    std::atomic<bool> used{false};
    /** The folder `path` was made in, opened O_PATH, when `holdsFolder`: removal goes through it, so a folder moved
     *  or renamed meanwhile is still found. (No -1 for "none": an initializer other than zero would put the table in
     *  the binary's data instead of .bss.) */
    bool holdsFolder = false;
    int folder = 0;
    std::size_t nameAt = 0; ///< where the file name starts in `path`
    char path[kMaxPathBytes]{};
};

// Constant-initialized (constinit: the build fails otherwise), so the megabyte lies untouched in .bss until a path is
// registered: initialized at start-up it cost every process, and the restart for the malloc tunables, 256 page faults
// (about 3 ms).
constinit Entry gFirstChunk[kEntriesPerChunk];
/** The chunks, the first `gChunkCount` of them in use: a chunk is stored before the count grows past it, so a signal
 *  handler reading without the lock sees only whole chunks. Never freed (the process's lifetime). */
constinit Entry* gChunks[kMaxChunks] = {gFirstChunk};
constinit std::atomic<int> gChunkCount{1};

int entryCount() { return gChunkCount.load(std::memory_order_acquire) * kEntriesPerChunk; }
Entry& entryAt(int index) { return gChunks[index / kEntriesPerChunk][index % kEntriesPerChunk]; }

/** A new chunk's first entry, or null when none can be had (every chunk in use, or no memory); the registry is
 *  locked. */
Entry* newChunk() {
    const int count = gChunkCount.load();
    if (count == kMaxChunks) return nullptr;
    Entry* chunk = new (std::nothrow) Entry[kEntriesPerChunk];
    if (!chunk) return nullptr;
    gChunks[count] = chunk;
    gChunkCount.store(count + 1, std::memory_order_release);
    return chunk;
}
/** Writers, creators (TemporaryCreation: recursive, as a creator registers what it made) and the signal thread's
 *  removal; a signal handler reads without locking (it may interrupt a writer). */
std::recursive_mutex gRegistryMutex;
/** Held by a commit (SignalsDeferred) and by the signal thread's removal, which so waits for the commit to end. */
std::mutex gCommitMutex;

/** While an output commit runs, a signal only records itself here (any thread may take it: the library threads do
 *  not block signals); SignalsDeferred acts on it once the commit has ended. */
std::atomic<bool> gDeferring{false};
std::atomic<int> gDeferredSignal{0};
/** Whether the signal thread runs (the handled signals then wait for it, blocked in the threads started after it),
 *  and whether it has taken a signal, which it acts on once it holds the commit lock. */
std::atomic<bool> gSignalThreadRuns{false};
std::atomic<bool> gSignalTaken{false};

/** Removes `name` (a file, or else an empty folder) from `folder` (a descriptor, or AT_FDCWD for a path). */
bool removeAt(int folder, const char* name) {
    if (::unlinkat(folder, name, 0) == 0) return true;
    return errno == EISDIR && ::unlinkat(folder, name, AT_REMOVEDIR) == 0;
}

/** The descriptor and name through which `entry` is reached: its folder's, or the working directory and its path. */
int folderOf(const Entry& entry) { return entry.holdsFolder ? entry.folder : AT_FDCWD; }
const char* nameIn(const Entry& entry) { return entry.holdsFolder ? entry.path + entry.nameAt : entry.path; }

/** Removes every registered path, then ends the process as `signalNumber` would (its default action, unblocked in the
 *  calling thread). Async-signal-safe. Files first, then the folders, again and again while one goes: entries are
 *  reused, so a folder (a dump's staging) may lie in a later entry than its files, or an earlier one. */
[[noreturn]] void sweepAndEnd(int signalNumber) {
    bool gone[kEntriesPerChunk * kMaxChunks] = {}; // 4 KiB of the stack
    const int count = entryCount();
    for (int i = 0; i < count; ++i) {
        const Entry& entry = entryAt(i);
        gone[i] = !entry.used.load() || ::unlinkat(folderOf(entry), nameIn(entry), 0) == 0 || errno == ENOENT;
    }
    for (bool removedOne = true; removedOne;) {
        removedOne = false;
        for (int i = 0; i < count; ++i) {
            if (gone[i] || ::unlinkat(folderOf(entryAt(i)), nameIn(entryAt(i)), AT_REMOVEDIR) != 0) continue;
            gone[i] = removedOne = true;
        }
    }
    endBySignal(signalNumber);
}

std::size_t nameOffset(const std::string& path) {
    const std::size_t slash = path.rfind('/');
    return slash == std::string::npos ? 0 : slash + 1;
}

/** `path`'s folder opened O_PATH (search permission is all it needs), or -1. */
int openFolderOf(const std::string& path) {
    const std::size_t at = nameOffset(path);
    const std::string folder = at == 0 ? "." : path.substr(0, at); // "a/" and "/" name their folders as they stand
    return ::open(folder.c_str(), O_PATH | O_DIRECTORY | O_CLOEXEC);
}

/** An entry's descriptor for the same folder as `folder` (the same inode, reached by the same text), or -1; the
 *  registry is locked. Entries in one folder share one descriptor: a dump's twenty files held twenty, which a low
 *  `ulimit -n` ran out of. */
int sharedFolder(const std::string& text, int folder) {
    struct stat wanted {};
    if (::fstat(folder, &wanted) != 0) return -1;
    const std::size_t nameAt = nameOffset(text);
    for (int i = 0, count = entryCount(); i < count; ++i) {
        const Entry& entry = entryAt(i);
        if (!entry.used.load() || !entry.holdsFolder || entry.nameAt != nameAt ||
            text.compare(0, nameAt, entry.path, nameAt) != 0)
            continue;
        struct stat held {};
        if (::fstat(entry.folder, &held) == 0 && held.st_dev == wanted.st_dev && held.st_ino == wanted.st_ino)
            return entry.folder;
    }
    return -1;
}

/** A free entry, in a new chunk when every one is taken, or null; the registry is locked. */
Entry* freeEntry() {
    for (int i = 0, count = entryCount(); i < count; ++i)
        if (!entryAt(i).used.load()) return &entryAt(i);
    return newChunk();
}

/** Stores `text` with `folder` (-1: none) in a free entry, sharing the descriptor of an entry in the same folder
 *  (`folder` is then closed); the registry is locked. False when it cannot be kept (too long, the table full): the
 *  caller closes `folder` then. */
bool remember(const std::string& text, int folder) {
    if (text.size() >= kMaxPathBytes) return false;
    Entry* entry = freeEntry();
    if (!entry) return false;
    if (folder >= 0) {
        if (const int shared = sharedFolder(text, folder); shared >= 0) {
            ::close(folder);
            folder = shared;
        }
    }
    std::memcpy(entry->path, text.c_str(), text.size() + 1);
    entry->nameAt = nameOffset(text);
    entry->holdsFolder = folder >= 0;
    entry->folder = folder >= 0 ? folder : 0;
    entry->used.store(true); // last: a signal handler reading without the lock sees a whole entry
    return true;
}

/** The newest entry for `text`, or null; the registry is locked. */
Entry* entryOf(const std::string& text) {
    for (int i = entryCount() - 1; i >= 0; --i)
        if (entryAt(i).used.load() && text == entryAt(i).path) return &entryAt(i);
    return nullptr;
}

/** Whether a remembered entry holds the descriptor `folder`; the registry is locked. */
bool folderInUse(int folder) {
    for (int i = 0, count = entryCount(); i < count; ++i)
        if (const Entry& entry = entryAt(i); entry.used.load() && entry.holdsFolder && entry.folder == folder)
            return true;
    return false;
}

/** Forgets every entry for `text` and closes their folders unless another entry shares one; the registry is
 *  locked. errno is kept. */
void forgetLocked(const std::string& text) {
    const int error = errno;
    for (int i = 0, count = entryCount(); i < count; ++i) {
        Entry& entry = entryAt(i);
        if (!entry.used.load() || text != entry.path) continue;
        entry.used.store(false); // first: a signal handler no longer reads the folder about to be closed
        if (entry.holdsFolder && !folderInUse(entry.folder)) ::close(entry.folder);
        entry.holdsFolder = false;
    }
    errno = error;
}

/** The handler, for a thread that does not block the signals (one started before removeTemporariesOnSignals()). */
void removeAll(int signalNumber) {
    if (gDeferring.load()) {
        gDeferredSignal.store(signalNumber);
        // The commit may have ended between the test and the store, its SignalsDeferred finding no signal: whichever
        // of the two takes it back acts on it.
        if (gDeferring.load()) return;
        signalNumber = gDeferredSignal.exchange(0);
        if (signalNumber == 0) return;
    }
    sweepAndEnd(signalNumber);
}

constexpr int kHandledSignals[] = {SIGINT, SIGTERM, SIGHUP};

/** Whether a signal for the signal thread has come and is not yet acted on: taken by it, or still pending (sent to
 *  the process, which leaves it pending while every thread but that one blocks it). */
bool signalOnItsWay() {
    if (!gSignalThreadRuns.load()) return false;
    if (gSignalTaken.load()) return true;
    sigset_t pending;
    if (::sigpending(&pending) != 0) return false;
    for (int signalNumber : kHandledSignals)
        if (::sigismember(&pending, signalNumber) == 1) return true;
    return false;
}

/** The thread the handled signals go to (every other thread started after the handling was installed blocks them):
 *  it is no signal handler, so it can wait for the commit and hold the registry while it sweeps. */
[[noreturn]] void waitForSignals(sigset_t signals) {
    for (;;) {
        int signalNumber = 0;
        if (::sigwait(&signals, &signalNumber) != 0) continue;
        gSignalTaken.store(true);
        gCommitMutex.lock();   // a commit runs whole: every output old or every one new
        gRegistryMutex.lock(); // no temporary half made; none made after the sweep, as the lock is never given back
        sweepAndEnd(signalNumber);
    }
}

} // namespace

void endBySignal(int signalNumber) {
    ::signal(signalNumber, SIG_DFL);
    sigset_t only;
    sigemptyset(&only);
    sigaddset(&only, signalNumber);
    ::pthread_sigmask(SIG_UNBLOCK, &only, nullptr);
    ::raise(signalNumber);
    ::_exit(128 + signalNumber); // not reached: the default action of the signals we take ends the process
}

TemporaryCreation::TemporaryCreation() { gRegistryMutex.lock(); }
TemporaryCreation::~TemporaryCreation() { gRegistryMutex.unlock(); }

void registerTemporary(const std::filesystem::path& path) {
    const std::string text = path.string();
    if (text.size() >= kMaxPathBytes) return; // too long to register: it is still removed on ordinary failures
    std::lock_guard lock(gRegistryMutex);
    const int folder = openFolderOf(text);
    if (!remember(text, folder) && folder >= 0) ::close(folder);
}

void forgetTemporary(const std::filesystem::path& path) {
    std::lock_guard lock(gRegistryMutex);
    forgetLocked(path.string());
}

int createTemporaryFile(const std::filesystem::path& path, unsigned mode) {
    const std::string text = path.string();
    constexpr int kFlags = O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC;
    std::lock_guard lock(gRegistryMutex); // created and registered before a signal's removal can look
    // The folder first, the file in it: so the folder removal goes through is the one the file was made in.
    const int folder = text.size() < kMaxPathBytes ? openFolderOf(text) : -1;
    const int descriptor = folder >= 0 ? ::openat(folder, text.c_str() + nameOffset(text), kFlags, mode_t(mode))
                                       : ::open(text.c_str(), kFlags, mode_t(mode));
    if (descriptor < 0) {
        const int error = errno;
        if (folder >= 0) ::close(folder);
        errno = error;
        return -1;
    }
    if (!remember(text, folder) && folder >= 0) ::close(folder);
    return descriptor;
}

bool removeTemporary(const std::filesystem::path& path) {
    const std::string text = path.string();
    std::lock_guard lock(gRegistryMutex);
    const Entry* entry = entryOf(text);
    const bool removed = entry ? removeAt(folderOf(*entry), nameIn(*entry)) : removeAt(AT_FDCWD, text.c_str());
    forgetLocked(text);
    return removed;
}

bool renameTemporary(const std::filesystem::path& temporary, const std::filesystem::path& sibling) {
    const std::string text = temporary.string();
    std::lock_guard lock(gRegistryMutex);
    const Entry* entry = entryOf(text);
    const bool renamed = entry && entry->holdsFolder
                             ? ::renameat(entry->folder, nameIn(*entry), entry->folder, sibling.filename().c_str()) == 0
                             : ::rename(text.c_str(), sibling.c_str()) == 0;
    if (renamed) forgetLocked(text);
    return renamed;
}

bool removeBesideTemporary(const std::filesystem::path& temporary, const std::filesystem::path& sibling) {
    std::lock_guard lock(gRegistryMutex);
    const Entry* entry = entryOf(temporary.string());
    return entry && entry->holdsFolder ? ::unlinkat(entry->folder, sibling.filename().c_str(), 0) == 0
                                       : ::unlink(sibling.c_str()) == 0;
}

void removeTemporariesOnSignals() {
    static std::once_flag installed;
    std::call_once(installed, [] {
        for (int signalNumber : kHandledSignals) ::signal(signalNumber, removeAll);
        ::signal(SIGXFSZ, SIG_IGN);
        sigset_t signals;
        sigemptyset(&signals);
        for (int signalNumber : kHandledSignals) sigaddset(&signals, signalNumber);
        // Blocked before the thread starts, so it inherits the mask too; sigwait takes them there.
        if (::pthread_sigmask(SIG_BLOCK, &signals, nullptr) != 0) return;
        try {
            std::thread(waitForSignals, signals).detach();
            gSignalThreadRuns.store(true);
        } catch (const std::system_error&) {
            ::pthread_sigmask(SIG_UNBLOCK, &signals, nullptr); // no thread: the handler takes them, as before
        }
    });
}

SignalsDeferred::SignalsDeferred() {
    gCommitMutex.lock();
    gDeferredSignal.store(0);
    gDeferring.store(true);
}

SignalsDeferred::~SignalsDeferred() {
    gDeferring.store(false);
    gCommitMutex.unlock();
    if (const int signalNumber = gDeferredSignal.exchange(0)) removeAll(signalNumber);
    // A signal that came during the commit ends the process once the signal thread has the commit lock. Until then
    // this thread waits: going on, it could end the process first (a run whose last commit it was), with status 0.
    if (signalOnItsWay())
        for (;;) ::pause();
}

std::string temporaryTag() {
    static const std::string kHost = [] {
        char host[256] = {};
        if (::gethostname(host, sizeof host - 1) != 0) host[0] = '\0';
        std::uint32_t hash = 2166136261u; // FNV-1a, 32 bits
        for (const char* c = host; *c != '\0'; ++c) hash = (hash ^ static_cast<unsigned char>(*c)) * 16777619u;
        static const char kDigits[] = "0123456789abcdef";
        std::string tag(8, '0');
        for (int i = 7; i >= 0; --i, hash >>= 4) tag[std::size_t(i)] = kDigits[hash & 15];
        return tag;
    }();
    // The pid asked each time: a forked child (Python's multiprocessing) has its own.
    return kHost + "-" + std::to_string(::getpid());
}

bool isStaleTemporary(const std::string& name) {
    // Exactly ".inkgraph-<host>-<pid>-<n>.tmp" (render/ImageFiles.h temporarySibling): a user's
    // ".inkgraph-1234-notes.txt" is not ours, whatever its name suggests.
    constexpr const char* kPrefix = ".inkgraph-";
    constexpr const char* kSuffix = ".tmp";
    const std::size_t prefix = std::strlen(kPrefix), suffix = std::strlen(kSuffix);
    if (name.size() <= prefix + suffix || name.rfind(kPrefix, 0) != 0 ||
        name.compare(name.size() - suffix, suffix, kSuffix) != 0)
        return false;
    const long pid = pidOfNumberedName(name.substr(prefix, name.size() - prefix - suffix));
    return pid > 0 && ::kill(pid_t(pid), 0) != 0 && errno == ESRCH;
}

long pidOfNumberedName(const std::string& fullText) {
    // "<host>-" first: this machine's tag only (8 hexadecimal digits, so no pid can be taken for it).
    const std::string tag = temporaryTag();
    const std::size_t hostLength = tag.find('-') + 1;
    if (fullText.size() <= hostLength || fullText.compare(0, hostLength, tag, 0, hostLength) != 0) return 0;
    const std::string text = fullText.substr(hostLength);
    const auto dash = text.find('-');
    const auto allDigits = [](const std::string& part) {
        return !part.empty() && part.size() <= 10 && part.find_first_not_of("0123456789") == std::string::npos;
    };
    if (dash == std::string::npos || !allDigits(text.substr(0, dash)) || !allDigits(text.substr(dash + 1))) return 0;
    return std::stol(text.substr(0, dash));
}

} // namespace inkgraph
