#include "app/TemporaryFiles.h"

#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <mutex>
#include <string>

namespace inkgraph {
namespace {

constexpr int kMaxEntries = 256;
constexpr std::size_t kMaxPathBytes = 4096;

struct Entry {
    std::atomic<bool> used{false};
    char path[kMaxPathBytes];
};

Entry gEntries[kMaxEntries];
std::mutex gRegistryMutex; // writers only; the handler reads without locking (it may interrupt a writer)

void removeAll(int signalNumber) {
    for (int i = kMaxEntries - 1; i >= 0; --i) {
        if (!gEntries[i].used.load()) continue;
        if (::unlink(gEntries[i].path) != 0 && errno == EISDIR) ::rmdir(gEntries[i].path);
        ::rmdir(gEntries[i].path); // folders registered before their files are removed after them
    }
    ::signal(signalNumber, SIG_DFL);
    ::raise(signalNumber);
}

} // namespace

void registerTemporary(const std::filesystem::path& path) {
    const std::string text = path.string();
    if (text.size() >= kMaxPathBytes) return; // too long to register: it is still removed on ordinary failures
    std::lock_guard lock(gRegistryMutex);
    for (Entry& entry : gEntries) {
        if (entry.used.load()) continue;
        std::memcpy(entry.path, text.c_str(), text.size() + 1);
        entry.used.store(true);
        return;
    }
}

void forgetTemporary(const std::filesystem::path& path) {
    const std::string text = path.string();
    std::lock_guard lock(gRegistryMutex);
    for (Entry& entry : gEntries)
        if (entry.used.load() && text == entry.path) entry.used.store(false);
}

void removeTemporariesOnSignals() {
    static std::once_flag installed;
    std::call_once(installed, [] {
        for (int signalNumber : {SIGINT, SIGTERM, SIGHUP}) ::signal(signalNumber, removeAll);
        ::signal(SIGXFSZ, SIG_IGN);
    });
}

bool isStaleTemporary(const std::string& name) {
    constexpr const char* kPrefix = ".inkgraph-"; // then "<pid>-<n>.tmp" (app/ImageFiles.h temporarySibling)
    if (name.rfind(kPrefix, 0) != 0) return false;
    const char* digits = name.c_str() + std::strlen(kPrefix);
    char* end = nullptr;
    const long pid = std::strtol(digits, &end, 10);
    if (end == digits || *end != '-' || pid <= 0) return false;
    return ::kill(pid_t(pid), 0) != 0 && errno == ESRCH;
}

} // namespace inkgraph
