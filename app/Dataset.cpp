#include "app/Dataset.h"

#include "app/DumpFolder.h"
#include "app/Stats.h"
#include "app/Version.h"
#include "flags/FlagTable.h"
#include "render/BuildInfo.h"
#include "render/ErrorReport.h"
#include "render/ImageFiles.h"
#include "render/InputFiles.h"
#include "render/TemporaryFiles.h"
#include "scene/Scene.h"
#include "scene/MessageText.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <optional>
#include <regex>
#include <set>
#include <sstream>

namespace inkgraph {
namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

namespace {

constexpr const char* kJournalFolder = ".inkgraph";

/** "size:mtime-nanoseconds" of a file, or "missing": what the digest knows of an input without reading it. */
std::string fileStamp(const fs::path& path) {
    struct stat status {};
    if (::stat(path.c_str(), &status) != 0 || !S_ISREG(status.st_mode)) return "missing";
    return std::to_string(status.st_size) + ":" + std::to_string(status.st_mtim.tv_sec) + "." +
           std::to_string(status.st_mtim.tv_nsec);
}

bool isRegularFile(const std::string& path) {
    struct stat status {};
    return ::stat(path.c_str(), &status) == 0 && S_ISREG(status.st_mode);
}

/** The files a flag's value names: the value itself when it is a file (--pose FILE, --shademap, a .vrma, ...), and
 *  each piece of a list that is one (--poses rest,wave.json; a SOURCE:FILE; a NAME=FILE), in the order given. */
std::vector<std::string> filesNamedBy(const std::string& value) {
    std::vector<std::string> files;
    const auto take = [&files](const std::string& piece) {
        if (!piece.empty() && std::find(files.begin(), files.end(), piece) == files.end() && isRegularFile(piece))
            files.push_back(piece);
    };
    take(value);
    for (const char* separators : {",", ";", ":", "=", ",;:="}) {
        std::size_t start = 0;
        for (;;) {
            const std::size_t end = value.find_first_of(separators, start);
            take(value.substr(start, end == std::string::npos ? std::string::npos : end - start));
            if (end == std::string::npos) break;
            start = end + 1;
        }
    }
    return files;
}

int hookFrom(const char* variable) {
    const char* value = std::getenv(variable);
    return value ? std::atoi(value) : 0;
}

/** Appends `line` to the journal: one write(2) with O_APPEND (so a kill leaves it whole or a torn tail), then
 *  fdatasync (so a finished line survives the machine too). `tearAt`: the test hook's byte count, else 0. */
void appendLine(const fs::path& journal, const std::string& line, std::size_t tearAt) {
    // Never through a link, never into a FIFO or a device: the journal is the data set's own plain file.
    const int descriptor =
        ::open(journal.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK, 0644);
    if (descriptor < 0)
        throw FileError("DatasetRun::recordCommitted(): cannot open the journal " +
                        detail::quotedFileName(journal.string()) + ": " + std::strerror(errno));
    struct stat status {};
    if (::fstat(descriptor, &status) != 0 || !S_ISREG(status.st_mode)) {
        ::close(descriptor);
        throw FileError("DatasetRun::recordCommitted(): the journal " + detail::quotedFileName(journal.string()) +
                        " is not a plain file; remove it and resume");
    }
    // One write for the whole line; a short write (a full disk) is continued, leaving a torn line at worst.
    int failure = writeWhole(descriptor, line.data(), tearAt > 0 ? tearAt : line.size());
    if (tearAt > 0) {
        std::cerr << "inkgraph: test hook: killed in the middle of a journal line" << std::endl;
        ::kill(::getpid(), SIGKILL);
    }
    if (failure == 0 && ::fdatasync(descriptor) != 0) failure = errno;
    if (::close(descriptor) != 0 && failure == 0) failure = errno;
    if (failure != 0)
        throw FileError("DatasetRun::recordCommitted(): cannot write the journal " +
                        detail::quotedFileName(journal.string()) + ": " + std::strerror(failure));
}

/** The lines of a journal or index that parse as a still's record; a torn tail of the journal is cut off, so the next
 *  line appended starts on a line of its own. */
std::vector<Json> readRecords(const fs::path& path, bool cutTornTail) {
    std::vector<Json> records;
    const std::optional<std::string> read = readDatasetFile(path, "DatasetRun");
    if (!read) return records;
    const std::string& text = *read;
    const std::size_t lastNewline = text.rfind('\n');
    const std::size_t whole = lastNewline == std::string::npos ? 0 : lastNewline + 1;
    if (cutTornTail && whole < text.size()) {
        if (::truncate(path.c_str(), off_t(whole)) != 0)
            throw FileError("DatasetRun: cannot cut the torn last line of " + detail::quotedFileName(path.string()) +
                            ": " + std::strerror(errno));
    }
    std::istringstream lines(text.substr(0, whole));
    std::string line;
    while (std::getline(lines, line)) {
        Json record = Json::parse(line, nullptr, false);
        if (record.is_discarded() || !record.is_object() || !record.contains("model") || !record["model"].is_string() ||
            !record.contains("position") || !record["position"].is_number_unsigned() || !record.contains("view") ||
            !record["view"].is_number_unsigned() || !record.contains("status"))
            continue;
        records.push_back(std::move(record));
    }
    return records;
}

/** True when an "ok" record has what --resume reads of it, each of its type: a settings digest, the checksums (each
 *  file's size and hash) and the files (each a path). A hand-edited or foreign line that fails this is as good as
 *  absent: its still renders again. */
bool isUsableRecord(const Json& record) {
    if (!record.contains("settings_digest") || !record["settings_digest"].is_string() ||
        !record.contains("checksums") || !record["checksums"].is_object())
        return false;
    for (const auto& [relative, checksum] : record["checksums"].items())
        if (!checksum.is_object() || !checksum.contains("size") || !checksum["size"].is_number_unsigned() ||
            !checksum.contains("fnv1a64") || !checksum["fnv1a64"].is_string())
            return false;
    if (record.contains("files")) {
        if (!record["files"].is_object()) return false;
        for (const auto& [flag, path] : record["files"].items())
            if (!path.is_string()) return false;
    }
    return true;
}

/** --seed with --views, else null. */
Json seedOf(const RenderOptions& still) { return still.viewsGiven ? Json(still.viewSampling.seed) : Json(nullptr); }

StillKey keyOf(const Json& record) {
    return {record["model"].get<std::string>(), record["position"].get<std::size_t>(),
            record["view"].get<std::size_t>()};
}

/** The camera of an index line: what a consumer needs to project a point (OpenCV's K and [R|t], the size) and
 *  OpenGL's matrices, without the manifest's prose (docs/datasets.md says it once). */
Json cameraRecord(const Json& camera, const RenderOptions& still) {
    Json record;
    record["width"] = still.width;
    record["height"] = still.height;
    for (const char* field : {"intrinsics", "extrinsics", "eye", "target", "up", "fov_y_degrees", "focal_pixels",
                              "near", "far", "view_matrix", "projection_matrix"})
        if (camera.contains(field)) record[field] = camera.at(field);
    return record;
}

} // namespace

std::uint64_t fnv1a64(const void* data, std::size_t byteCount, std::uint64_t hash) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < byteCount; ++i) {
        hash ^= bytes[i];
        hash *= 0x100000001b3ULL;
    }
    return hash;
}

std::string hexDigits(std::uint64_t value) {
    static const char kDigits[] = "0123456789abcdef";
    std::string text(16, '0');
    for (int i = 15; i >= 0; --i, value >>= 4) text[std::size_t(i)] = kDigits[value & 15];
    return text;
}

std::optional<std::string> readDatasetFile(const fs::path& path, const std::string& function) {
    // O_NONBLOCK: opening a FIFO returns at once (and fstat tells it apart) instead of waiting for a writer.
    const int descriptor = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK);
    if (descriptor < 0 && errno == ENOENT) return std::nullopt;
    struct stat status {};
    if (descriptor < 0 || ::fstat(descriptor, &status) != 0 || !S_ISREG(status.st_mode)) {
        const int cause = descriptor < 0 ? errno : 0;
        if (descriptor >= 0) ::close(descriptor);
        throw FileError(function + ": " + detail::quotedFileName(path.string()) + " " +
                        (cause == ELOOP || cause == 0
                             ? std::string("is not a plain file (a link, a FIFO, a device or a "
                                           "folder): a data set's own files are plain files; "
                                           "remove it")
                             : std::string("cannot be read: ") + std::strerror(cause)));
    }
    std::string text;
    text.resize(std::size_t(status.st_size));
    std::size_t done = 0;
    while (done < text.size()) {
        const ssize_t count = ::read(descriptor, text.data() + done, text.size() - done);
        if (count < 0 && errno == EINTR) continue;
        if (count <= 0) break; // shorter than its size said: what was read
        done += std::size_t(count);
    }
    ::close(descriptor);
    text.resize(done);
    return text;
}

std::optional<FileChecksum> fileChecksum(const fs::path& path) {
    // O_NONBLOCK: a FIFO in a listed file's place returns at once and is refused below as not a plain file.
    const int descriptor = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
    if (descriptor < 0) return std::nullopt;
    struct stat status {};
    if (::fstat(descriptor, &status) != 0 || !S_ISREG(status.st_mode)) {
        ::close(descriptor);
        return std::nullopt;
    }
    std::uint64_t hash = fnv1a64(nullptr, 0);
    std::uintmax_t size = 0;
    std::vector<char> block(std::size_t(1) << 20);
    for (;;) {
        const ssize_t count = ::read(descriptor, block.data(), block.size());
        if (count < 0 && errno == EINTR) continue;
        if (count < 0) {
            ::close(descriptor);
            return std::nullopt;
        }
        if (count == 0) break;
        hash = fnv1a64(block.data(), std::size_t(count), hash);
        size += std::uintmax_t(count);
    }
    ::close(descriptor);
    return FileChecksum{size, hexDigits(hash)};
}

const std::vector<std::string>& flagsOutsideDigest() {
    // How the run goes, not what a still writes: resuming, progress lines, the share of an array job, the memory
    // bound (a still either fits or fails), the EGL platform (the same pixels on any), the list (each still's model
    // is in its key), the data set's folder (outputs are hashed relative to it), the plan on standard output, and
    // --style (its settings are in the arguments already; its file's stamp would re-render for a comment), and
    // --jobs and --draw-threads (the same bytes with any number of workers and drawing threads).
    static const std::vector<std::string> kFlags = {"--resume",       "-q",     "--shard",       "--memory-limit",
                                                    "--egl-platform", "--list", "--dataset",     "--print-plan",
                                                    "--style",        "--jobs", "--draw-threads"};
    return kFlags;
}

std::string shardSuffix(const RenderOptions& options) {
    if (!options.shard) return "";
    std::string suffix = "-";
    suffix += std::to_string(options.shard->index);
    suffix += "-of-" + std::to_string(options.shard->count);
    return suffix;
}

std::string shellWord(const std::string& argument) {
    const bool plain = !argument.empty() && std::all_of(argument.begin(), argument.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || std::strchr("-_./=,:+@%", c) != nullptr;
    });
    if (plain) return argument;
    std::string quoted = "'";
    for (char c : argument) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return quoted + "'";
}

DatasetRun::DatasetRun(const RenderOptions& options, const BatchList& list, const std::vector<BatchStill>& stills,
                       std::vector<std::string> givenArguments, const std::vector<std::string>& expandedArguments)
    : mOptions(options), mFolder(resolvedPath(options.datasetDirectory)), mSuffix(shardSuffix(options)),
      mGivenArguments(std::move(givenArguments)), mKillBeforeLine(hookFrom("INKGRAPH_TEST_JOURNAL_KILL")),
      mTearLine(hookFrom("INKGRAPH_TEST_JOURNAL_TEAR")) {
    const std::string shown = "--dataset " + detail::quotedFileName(options.datasetDirectory);
    std::error_code error;
    if (fs::exists(mFolder, error) && !fs::is_directory(mFolder, error)) throw UsageError(shown + " is not a folder");
    mModelCount = list.models.size();
    mListLength = list.total;

    // The index and the card are JSON, which holds UTF-8 text only: a name that is not was recorded with U+FFFD in
    // place of its bytes, so check-dataset missed the file and --resume rendered it again on every run.
    const auto refuseUnlessUtf8 = [&shown](const std::string& what, const std::string& text) {
        try {
            (void)Json(text).dump();
        } catch (const Json::type_error&) {
            throw UsageError(shown + ": " + what + " " + detail::quotedFileName(text) +
                             " is not UTF-8, and the data set's index and card (JSON) hold UTF-8 text only: rename it");
        }
    };

    // Every output of every still inside DIR, none of them the data set's own files.
    const std::set<fs::path> reserved = {mFolder / kJournalFolder, indexPath(), cardPath()};
    for (const BatchStill& batchStill : stills) {
        refuseUnlessUtf8("the model", batchStill.model.path);
        const RenderOptions still = stillOptions(options, batchStill, list.total);
        for (const auto& [flag, field] : outputPathFlags()) {
            const std::string& value = still.*field;
            if (value.empty()) continue;
            refuseUnlessUtf8(flag, value);
            const fs::path place = resolvedPath(value);
            const fs::path relative = place.lexically_relative(mFolder);
            if ((relative.empty() || relative == "." || *relative.begin() == "..") &&
                fs::is_symlink(fs::symlink_status(value, error)))
                throw UsageError(flag + " " + detail::quotedFileName(value) + " is a link to " +
                                 detail::quotedFileName(place.string()) + ", outside " + shown +
                                 "; every output of a data set is a file inside it: remove the link");
            if (relative.empty() || relative == "." || *relative.begin() == "..")
                throw UsageError(flag + " " + detail::quotedFileName(value) + " lies outside " + shown +
                                 "; every output of a data set goes inside it, e.g. " + flag + " '" +
                                 (fs::path(options.datasetDirectory) / fs::path(value).filename()).string() + "'");
            if (reserved.count(place) != 0 || reserved.count(mFolder / *relative.begin()) != 0)
                throw UsageError(flag + " " + detail::quotedFileName(value) + " is a file of the data set itself (" +
                                 relative.begin()->string() + "); choose another name");
        }
    }

    for (const std::string& argument : mGivenArguments) refuseUnlessUtf8("the argument", argument);

    // Checked before anything is made (a refused run changes nothing), and again under the lock: a run of this split
    // that held it until now may have finished meanwhile.
    refuseOtherRunsFiles();

    // The canonical settings: each flag by its first name with its value, in the table's spelling, stably sorted by
    // name so that flag order does not matter (a flag given twice keeps its own order: the last one wins).
    const std::vector<std::string>& outside = flagsOutsideDigest();
    for (std::size_t i = 0; i < expandedArguments.size(); ++i) {
        const std::string& argument = expandedArguments[i];
        if (argument.empty() || argument[0] != '-') continue; // a MODEL: each still's is in its key
        const Flag* flag = findFlag(argument);
        if (flag == nullptr) continue;
        std::string value;
        if (!flag->valueName.empty() && i + 1 < expandedArguments.size()) value = expandedArguments[++i];
        const std::string& name = flag->names.front();
        bool isOutput = false;
        for (const auto& [outputFlag, field] : outputPathFlags()) isOutput = isOutput || outputFlag == name;
        if (isOutput || std::find(outside.begin(), outside.end(), name) != outside.end()) continue;
        mCanonicalSettings.emplace_back(name, value);
    }
    std::stable_sort(mCanonicalSettings.begin(), mCanonicalSettings.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });

    lockThisSplit();
    try {
        refuseOtherRunsFiles();
        if (options.resume) {
            readEarlierRecords();
            // The card is replaced only at the end, after the index: one that is not a plain file is refused now,
            // before the run changes anything.
            readDatasetFile(cardPath(), "DatasetRun");
        }
    } catch (...) {
        letGoOfThisSplit(/*finished=*/false); // a constructor that throws runs no destructor
        throw;
    }
}

DatasetRun::~DatasetRun() { letGoOfThisSplit(/*finished=*/false); }

void DatasetRun::lockThisSplit() {
    // One lock per split (a shard's beside the others', which run at once by design): a second run of the same split
    // (a requeued array task beside the one it replaces, a command started twice) is refused at once instead of
    // interleaving its journal, index and outputs with the first one's.
    const fs::path path = mFolder / kJournalFolder / ("lock" + mSuffix);
    std::error_code error;
    // A run of this data set that finishes removes the .inkgraph folder when it leaves it empty, and may do so between
    // this run's making it and opening the lock inside: made again then (a few times; each such run ends for good).
    int folderTakenAway = hookFrom("INKGRAPH_TEST_LOCK_FOLDER_REMOVED"); // that many times, as such a run would
    for (int attempt = 0; attempt < 10; ++attempt) {
        if (!fs::exists(fs::symlink_status(path.parent_path(), error))) {
            mMadeJournalFolder = true;
            if (!mFolderModifiedBeforeLock) {
                const fs::file_time_type modified = fs::last_write_time(mFolder, error);
                if (!error) mFolderModifiedBeforeLock = modified; // none when this run makes DIR too
            }
        }
        fs::create_directories(path.parent_path(), error);
        if (error)
            throw FileError("DatasetRun: cannot create the data set's own folder " +
                            detail::quotedFileName(path.parent_path().string()) + ": " + error.message());
        if (folderTakenAway-- > 0) fs::remove(path.parent_path(), error);
        mLock = FileLock(path, FileLock::Target::LockFile);
        if (mLock.held()) {
            const fs::file_time_type modified = fs::last_write_time(mFolder, error);
            if (!error) mFolderModifiedWithLock = modified;
            return;
        }
        if (mLock.error() != ENOENT) break;
    }
    if (mMadeJournalFolder) fs::remove(path.parent_path(), error); // only when empty
    const std::string shown = "--dataset " + detail::quotedFileName(mOptions.datasetDirectory);
    const std::string split = mSuffix.empty() ? "" : " (shard " + mSuffix.substr(1) + ")";
    if (mLock.error() == EWOULDBLOCK)
        throw FileError("DatasetRun: " + shown + split +
                        " is being written by another inkgraph run; wait until it has finished, then --resume");
    throw FileError("DatasetRun: cannot lock " + shown + split + " (" + detail::quotedFileName(path.string()) +
                    "): " + (mLock.error() == EINVAL ? std::string("not a plain file") : std::strerror(mLock.error())));
}

void DatasetRun::letGoOfThisSplit(bool finished) {
    if (!mLock.held()) return;
    mLock.release(/*removeLockFile=*/true);
    // A run refused after taking the lock (a memory limit too low for a still) made .inkgraph and nothing else: DIR's
    // modification time is put back with it, so the folder reads as untouched (to make, rsync, a backup). Only when no
    // other entry of DIR changed meanwhile (its time stayed) and nothing was rendered or made into it.
    std::error_code error;
    const bool onlyTheJournalFolder = !finished && mMadeJournalFolder && mFolderModifiedBeforeLock &&
                                      mFolderModifiedWithLock && mRendered == 0 && !mMadeOutputFolder &&
                                      fs::last_write_time(mFolder, error) == *mFolderModifiedWithLock && !error;
    // Only when empty (a journal or another shard's lock may be in it), and on a failure only when this run made it.
    const bool removed = (finished || mMadeJournalFolder) && fs::remove(mFolder / kJournalFolder, error);
    if (removed && onlyTheJournalFolder) fs::last_write_time(mFolder, *mFolderModifiedBeforeLock, error);
}

void DatasetRun::refuseOtherRunsFiles() const {
    const RenderOptions& options = mOptions;
    const std::string shown = "--dataset " + detail::quotedFileName(options.datasetDirectory);
    std::error_code error;
    // One layout per folder, resumed or not: every index, shard card and journal there must be of this run's split
    // (unsharded, or --shard K/N with this N), so no two splits' files ever mix in one data set.
    const auto layoutOf = [](const std::string& suffix) -> std::string {
        if (suffix.empty()) return "without --shard";
        static const std::regex kShard(R"(-([0-9]{1,9})-of-([0-9]{1,9}))");
        std::smatch match;
        if (std::regex_match(suffix, match, kShard)) return "with --shard K/" + match[2].str();
        return "by another run ('" + suffix + "')";
    };
    const std::string layout = layoutOf(mSuffix.empty() ? "" : "-0-of-" + std::to_string(options.shard->count));
    const auto refuseOtherLayout = [&](const fs::path& path, const std::string& suffix) {
        const std::string theirs = layoutOf(suffix);
        if (theirs != layout)
            throw UsageError(shown + " holds a data set made " + theirs + " (" +
                             detail::quotedFileName(path.lexically_relative(mFolder).generic_string()) +
                             "), this run is " + layout + "; run it as it was made, or choose a new or empty folder");
    };
    const auto suffixBetween = [](const std::string& name, const std::string& prefix,
                                  const std::string& extension) -> std::optional<std::string> {
        if (name.size() < prefix.size() + extension.size() || name.rfind(prefix, 0) != 0 ||
            name.compare(name.size() - extension.size(), extension.size(), extension) != 0)
            return std::nullopt;
        return name.substr(prefix.size(), name.size() - prefix.size() - extension.size());
    };
    // The journal's folder is the data set's own: through a link, its journals would be read, cut and removed
    // elsewhere.
    if (fs::is_symlink(fs::symlink_status(mFolder / kJournalFolder, error)))
        throw FileError("DatasetRun: '" + (mFolder / kJournalFolder).string() +
                        "' is a link: a data set's own files are plain files; remove it");
    for (const fs::path& folder : {mFolder, mFolder / kJournalFolder}) {
        if (!fs::is_directory(folder, error)) continue;
        for (const auto& entry : fs::directory_iterator(folder, error)) {
            const std::string name = entry.path().filename().string();
            if (folder == mFolder) {
                if (const auto suffix = suffixBetween(name, "index", ".jsonl"))
                    refuseOtherLayout(entry.path(), *suffix);
                if (const auto suffix = suffixBetween(name, "README-", ".md");
                    suffix && suffix->find("-of-") != std::string::npos)
                    refuseOtherLayout(entry.path(), "-" + *suffix);
            } else if (const auto suffix = suffixBetween(name, "journal", ".jsonl")) {
                refuseOtherLayout(entry.path(), *suffix);
            } else if (name.rfind("journal", 0) == 0) {
                refuseOtherLayout(entry.path(), "?");
            }
        }
    }
    // A data set of this split there already: refused unless resumed, so no run replaces an index, a card or a
    // journal by mistake. (Another shard's files of the same split are that shard's: this one starts beside them.)
    std::vector<fs::path> existing;
    for (const fs::path& path : {journalPath(), indexPath(), cardPath()})
        if (fs::exists(fs::symlink_status(path, error))) existing.push_back(path);
    if (!existing.empty() && !options.resume)
        throw UsageError(shown + " already holds a data set (" +
                         detail::quotedFileName(existing.front().lexically_relative(mFolder).string()) +
                         "); add --resume to complete or update it, or choose a new or empty folder");
}

fs::path DatasetRun::journalPath() const { return mFolder / kJournalFolder / ("journal" + mSuffix + ".jsonl"); }
fs::path DatasetRun::indexPath() const { return mFolder / ("index" + mSuffix + ".jsonl"); }
fs::path DatasetRun::cardPath() const { return mFolder / ("README" + mSuffix + ".md"); }

std::string DatasetRun::relativeToDataset(const std::string& path) const {
    return resolvedPath(path).lexically_relative(mFolder).generic_string();
}

void DatasetRun::readEarlierRecords() {
    // The index first, then the journal, which is newer: a later record of a key replaces an earlier one.
    for (const auto& [path, isJournal] : {std::pair{indexPath(), false}, std::pair{journalPath(), true}})
        for (Json& record : readRecords(path, isJournal)) {
            if (record["status"] != "ok" || !isUsableRecord(record)) continue;
            const StillKey key = keyOf(record);
            mEarlier[key] = std::move(record);
        }
}

std::string DatasetRun::settingsDigest(const StillKey& key, const RenderOptions& still) const {
    std::string text;
    const auto add = [&text](const std::string& name, const std::string& value) {
        text += name;
        text += '\0';
        text += value;
        text += '\n';
    };
    add("version", inkgraphVersion());
    for (const auto& [flag, value] : mCanonicalSettings) {
        add(flag, value);
        for (const std::string& file : filesNamedBy(value)) add("file " + file, fileStamp(file));
    }
    for (const auto& [flag, field] : outputPathFlags())
        if (!(still.*field).empty()) add(flag, relativeToDataset(still.*field));
    add("model", fileStamp(key.model));
    // The files a .gltf or .obj names (buffers, images, material libraries): a changed texture renders again. Read
    // once per model (its views share them). A .glb or .vrm holds its resources: finding the rare external one would
    // read the whole file for every still of a resumed run.
    std::string extension = fs::path(key.model).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    if (extension == ".gltf" || extension == ".obj") {
        auto named = mNamedFiles.find(key.model);
        if (named == mNamedFiles.end()) named = mNamedFiles.emplace(key.model, referencedFiles(key.model)).first;
        for (const std::string& file : named->second) add("named " + file, fileStamp(file));
    }
    // The whole list's length: --stats records it (batch.list_length), so a longer list renders every still again.
    add("list_length", std::to_string(mListLength));
    add("view", std::to_string(key.view));
    add("sample", viewRecord(still).dump()); // the view drawn for the seed, the model path and the index
    return hexDigits(fnv1a64(text.data(), text.size()));
}

bool DatasetRun::isComplete(const StillKey& key, const std::string& digest) {
    const auto earlier = mEarlier.find(key);
    if (earlier == mEarlier.end()) return false;
    const Json& record = earlier->second;
    if (!record.contains("settings_digest") || record["settings_digest"] != digest || !record.contains("checksums") ||
        !record["checksums"].is_object() || record["checksums"].empty())
        return false;
    // Every recorded file whole: a file is only recorded after its commit, so a size and checksum that match are the
    // committed bytes, never a half-written file.
    for (const auto& [relative, expected] : record["checksums"].items()) {
        const auto found = fileChecksum(mFolder / relative);
        if (!found || !expected.is_object() || !expected.contains("size") || !expected["size"].is_number_unsigned() ||
            expected["size"].get<std::uintmax_t>() != found->size || !expected.contains("fnv1a64") ||
            !expected["fnv1a64"].is_string() || expected["fnv1a64"].get<std::string>() != found->fnv1a64)
            return false;
    }
    mRecords[key] = record;
    ++mSkipped;
    return true;
}

void DatasetRun::recordCommitted(const StillKey& key, const RenderOptions& still, const std::string& digest,
                                 const Json& camera, const Json& look) {
    Json record;
    record["model"] = key.model;
    record["position"] = key.position;
    record["view"] = key.view;
    record["seed"] = seedOf(still);
    record["sample"] = viewRecord(still);
    record["status"] = "ok";
    record["settings_digest"] = digest;
    record["camera"] = cameraRecord(camera, still);
    Json files = Json::object();
    Json checksums = Json::object();
    const auto addChecksum = [&](const fs::path& path) {
        const auto checksum = fileChecksum(path);
        if (!checksum)
            throw FileError("DatasetRun::recordCommitted(): cannot read back " + detail::quotedFileName(path.string()) +
                            ", committed a moment ago");
        checksums[path.lexically_relative(mFolder).generic_string()] = {{"size", checksum->size},
                                                                        {"fnv1a64", checksum->fnv1a64}};
    };
    for (const auto& [flag, field] : outputPathFlags()) {
        const std::string& value = still.*field;
        if (value.empty()) continue;
        files[flag] = relativeToDataset(value);
        const fs::path place = resolvedPath(value);
        if (flag != "--dump") {
            addChecksum(place);
            continue;
        }
        std::vector<fs::path> dumped;
        for (const auto& entry : fs::directory_iterator(place))
            if (entry.is_regular_file() && entry.path().filename().string().rfind(".inkgraph", 0) != 0)
                dumped.push_back(entry.path());
        std::sort(dumped.begin(), dumped.end());
        for (const fs::path& file : dumped) addChecksum(file);
    }
    record["files"] = files;
    record["checksums"] = checksums;
    record["look"] = look;

    const std::string line = record.dump(-1, ' ', false, Json::error_handler_t::replace) + "\n";
    ++mJournalLines;
    if (mJournalLines == mKillBeforeLine) {
        std::cerr << "inkgraph: test hook: killed before journal line " << mJournalLines << std::endl;
        ::kill(::getpid(), SIGKILL);
    }
    std::error_code error;
    fs::create_directories(journalPath().parent_path(), error);
    appendLine(journalPath(), line, mJournalLines == mTearLine ? line.size() / 2 : 0);
    mRecords[key] = std::move(record);
    ++mRendered;
}

void DatasetRun::makeOutputFolders(const RenderOptions& still) const {
    for (const auto& [flag, field] : outputPathFlags()) {
        if ((still.*field).empty()) continue;
        // Every output lies inside DIR (checked by the constructor), so this never makes a folder outside it.
        const fs::path folder = fs::path(still.*field).parent_path();
        if (folder.empty()) continue;
        std::error_code error;
        if (fs::create_directories(folder, error)) mMadeOutputFolder = true;
        if (error)
            throw FileError("DatasetRun::makeOutputFolders(): cannot make the folder " +
                            detail::quotedFileName(folder.string()) + " of " + flag + ": " + error.message());
    }
}

void DatasetRun::recordFailed(const StillKey& key, const RenderOptions& still, const std::string& error) {
    Json record;
    record["model"] = key.model;
    record["position"] = key.position;
    record["view"] = key.view;
    record["seed"] = seedOf(still);
    record["status"] = "failed";
    record["error"] = error;
    mRecords[key] = std::move(record);
}

void DatasetRun::finish(std::ostream& log) {
    std::string index;
    std::size_t stills = 0;
    std::size_t failed = 0;
    for (const auto& [key, record] : mRecords) {
        index += record.dump(-1, ' ', false, Json::error_handler_t::replace) + "\n";
        (record["status"] == "ok" ? stills : failed) += 1;
    }
    writeTextFile(indexPath(), index);
    writeTextFile(cardPath(), cardText(mModelCount, stills, failed));
    // Only now: the index holds everything the journal did.
    std::error_code error;
    fs::remove(journalPath(), error);
    // What killed runs left under DIR (temporaries of stills that were skipped this time are nobody else's to sweep).
    std::vector<fs::path> folders = {mFolder};
    for (auto it = fs::recursive_directory_iterator(mFolder, error); !error && it != fs::recursive_directory_iterator();
         it.increment(error)) {
        const fs::path path = it->path();
        if (it->is_directory(error) && !it->is_symlink(error)) folders.push_back(path);
        if (it->is_regular_file(error) && isStaleTemporary(path.filename().string())) ::unlink(path.c_str());
    }
    for (const fs::path& folder : folders) sweepStaleStagingFolders(folder);
    // A kill between a dump's swap and its tidying leaves the staging marker in the finished dump; a skipped still's
    // dump is tidied by nobody else.
    for (const auto& [key, record] : mRecords)
        if (record.contains("files") && record["files"].is_object() && record["files"].contains("--dump") &&
            record["files"]["--dump"].is_string())
            ::unlink((mFolder / record["files"]["--dump"].get<std::string>() / kStagingMarker).c_str());
    if (mOptions.resume && !mOptions.quiet)
        log << "inkgraph: resumed: " << mSkipped << " stills complete, " << mRendered << " rendered"
            << (failed > 0 ? ", " + std::to_string(failed) + " failed" : std::string()) << "\n";
    letGoOfThisSplit(/*finished=*/true);
}

std::string DatasetRun::cardText(std::size_t models, std::size_t stills, std::size_t failed) const {
    std::string command = "inkgraph render";
    for (const std::string& argument : mGivenArguments)
        if (argument != "--resume") {
            command += ' ';
            command += shellWord(argument);
        }
    std::string outputs;
    for (const auto& [flag, field] : outputPathFlags())
        if (!(mOptions.*field).empty())
            outputs += "| `" + flag + "` | `" + relativeToDataset(mOptions.*field) + "` |\n";
    // The look of the first still that has one (all stills share the flags; a model's own materials may differ).
    Json look;
    std::string lookOf;
    for (const auto& [key, record] : mRecords)
        if (record.contains("look")) {
            look = record["look"];
            lookOf = " (as the first still, '" + record.value("model", std::string()) + "' view " +
                     std::to_string(record.value("view", std::size_t(0))) +
                     ", resolved it: the flags above decide it, a model's materials and edges may add to it; each "
                     "still's is in the index)";
            break;
        }
    const std::string index = indexPath().filename().string();
    std::string text;
    text += "# Data set" + (mSuffix.empty() ? std::string() : " (shard " + mSuffix.substr(1) + ")") + "\n\n";
    text += "Rendered by " + versionLine() + " with this command (relative paths are from the folder it ran in):\n\n";
    text += "```sh\n" + command + "\n```\n\n";
    text += "## Counts\n\n| what | count |\n| --- | --- |\n";
    text += "| models | " + std::to_string(models) + " |\n";
    text += "| views per model | " +
            std::to_string(mOptions.viewsGiven ? mOptions.viewSampling.count : std::size_t(1)) + " |\n";
    text += "| stills in the set | " + std::to_string(stills) + " |\n";
    text += "| failed | " + std::to_string(failed) + " |\n\n";
    text += "## Files per still\n\nPaths relative to this folder ({name}: the model's file name without its extension, "
            "{index}: its list position from 1, {view}: the view from 0):\n\n| flag | path |\n| --- | --- |\n" +
            outputs + "\n";
    text += "`" + index +
            "` lists every still, one JSON object a line: its model, list position, view, camera (OpenCV's "
            "intrinsics K and extrinsics [R|t], OpenGL's view and projection matrices, the size), its files with "
            "their sizes and FNV-1a 64-bit checksums, and its status (`ok`, or `failed` with the error).\n\n";
    text += "## Look\n\nThe look" + lookOf + ":\n\n```json\n" + (look.is_null() ? std::string("null") : look.dump(2)) +
            "\n```\n\n";
    text += "## Checking\n\n```sh\ninkgraph check-dataset .\n```\n\nchecks that every still's files are there and "
            "whole and that no run was left unfinished.\n\n";
    text += "## Reproducing and citing\n\nThe command above, run with the same inkgraph version on the same models, "
            "writes the same files byte for byte (--stats files and --dump's manifest.json excepted: they hold "
            "timings). Cite the data set by this card: the command and the version.\n";
    return text;
}

} // namespace inkgraph
