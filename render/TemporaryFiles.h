#pragma once
/** @file Temporary files and folders of this process, removed if it is interrupted (SIGINT, SIGTERM, SIGHUP), so
 *  that a stopped run leaves nothing behind. Paths are kept in a table of fixed-size chunks (256 paths each, up to
 *  4,096, added as a run needs them) so the signal handler can walk it with async-signal-safe calls only (unlink,
 *  rmdir). */

#include <filesystem>

namespace inkgraph {

/** Remembers a file or an (eventually empty) folder to remove on a signal: files first, then folders. Its folder
 *  is opened (O_PATH) and held while it is remembered, so the functions below, and a signal's removal, find it there
 *  even if that folder has been moved or renamed since (a user moving the output folder during a batch). */
void registerTemporary(const std::filesystem::path& path);
/** Forgets it: it was renamed into place or removed. */
void forgetTemporary(const std::filesystem::path& path);

/** Creates `path` exclusively (O_EXCL: an existing name is someone else's, never ours to overwrite) for writing, and
 *  registers it with the folder it was made in (no moment in between). Returns the open descriptor, or -1 with errno
 *  set. */
int createTemporaryFile(const std::filesystem::path& path, unsigned mode);
/** Removes a registered temporary (a file, or an empty folder) from the folder it was made in, wherever that folder
 *  is now, and forgets it; one not registered (its path too long, or 4,096 held) is removed by its path. False, with
 *  errno set, when nothing was removed. */
bool removeTemporary(const std::filesystem::path& path);
/** Renames a registered temporary to `sibling`'s file name in the folder it was made in (and forgets it), wherever that
 *  folder is now: putting back the file a failed commit replaced. False, with errno set, when it could not. */
bool renameTemporary(const std::filesystem::path& temporary, const std::filesystem::path& sibling);
/** Removes `sibling`'s file name from the folder a registered temporary was made in, wherever that folder is now:
 *  taking back a file a failed commit moved into place beside it. False, with errno set, when nothing was removed. */
bool removeBesideTemporary(const std::filesystem::path& temporary, const std::filesystem::path& sibling);
/** Installs the handling (idempotent): SIGINT, SIGTERM and SIGHUP are blocked in the calling thread and so in every
 *  thread it starts later, and a thread of their own waits for them (sigwait). A signal then waits for a commit in
 *  progress (SignalsDeferred) and for a file being created and registered (TemporaryCreation), removes what is
 *  registered and ends the process as the signal would have, holding the registry so no thread creates a file after
 *  the sweep. Threads that do not block them (started before the call) have a handler that does the same as well as
 *  a signal handler can. Call it before the process starts threads (the command line does, first thing). SIGXFSZ is
 *  ignored, so a write past the file-size limit fails with EFBIG and is reported. */
void removeTemporariesOnSignals();

/** Ends the process as `signalNumber`'s default action does (its exit status, its core dump), from a handler or any
 *  thread: the default restored, the signal unblocked in this thread and raised. Async-signal-safe. */
[[noreturn]] void endBySignal(int signalNumber);

/** Held while a temporary file or folder is created and registered (open, link or mkdir, then registerTemporary()): a
 *  signal's removal waits for it, so a file made just before the signal is never left behind unregistered. */
class TemporaryCreation {
public:
    TemporaryCreation();
    ~TemporaryCreation();
    TemporaryCreation(const TemporaryCreation&) = delete;
    TemporaryCreation& operator=(const TemporaryCreation&) = delete;
};

/** While one lives, SIGINT, SIGTERM and SIGHUP wait, in whichever thread they land: the output commit runs as a whole,
 *  then a signal that came meanwhile removes what is still registered and ends the process as it would have. */
class SignalsDeferred {
public:
    SignalsDeferred();
    ~SignalsDeferred();
    SignalsDeferred(const SignalsDeferred&) = delete;
    SignalsDeferred& operator=(const SignalsDeferred&) = delete;
};

/** "<host>-<pid>": what numbers this process's temporary and staging names, <host> being 8 hexadecimal digits of a
 *  hash of the host name. Processes on other machines writing into the same shared folder have other tags, so no
 *  process ever takes another machine's live temporaries for a killed run's (their pids mean nothing here). */
std::string temporaryTag();

/** True when `name` is one of our temporary names (".inkgraph-<host>-<pid>-<n>.tmp"), made on this machine, and that
 *  process no longer runs: left by a killed run. (Staging folders of --dump have their own test: app/DumpFolder.h.) */
bool isStaleTemporary(const std::string& name);

/** The pid in "<host>-<pid>-<n>" (how our temporary and staging names are numbered) when <host> is this machine's
 *  tag, or 0: for other text and for names another machine made. */
long pidOfNumberedName(const std::string& text);

} // namespace inkgraph
