#include "render/CrashReport.h"

#include "render/TemporaryFiles.h"

#include <execinfo.h>
#include <signal.h>
#include <time.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>

namespace inkgraph {
namespace {

constexpr int kCrashSignals[] = {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT};
constexpr int kMaxFrames = 64;
constexpr unsigned kReportSeconds = 10;

/** Written once by reportCrashes(), read by the handler. */
char gBuild[256] = "inkgraph";
/** The installing thread's stack for the handler: a stack overflow leaves no room on its own. Static, so it lies
 *  untouched in .bss until a crash uses it. */
alignas(16) char gAlternateStack[64 * 1024];
std::atomic<bool> gReporting{false};

void writeText(const char* text) {
    std::size_t left = std::strlen(text);
    while (left > 0) {
        const ssize_t written = ::write(STDERR_FILENO, text, left);
        if (written < 0 && errno == EINTR) continue;
        if (written <= 0) return;
        text += written;
        left -= std::size_t(written);
    }
}

const char* crashSignalName(int signalNumber) {
    switch (signalNumber) {
    case SIGSEGV: return "SIGSEGV (segmentation fault)";
    case SIGBUS: return "SIGBUS (bus error)";
    case SIGFPE: return "SIGFPE (arithmetic exception)";
    case SIGILL: return "SIGILL (illegal instruction)";
    case SIGABRT: return "SIGABRT (aborted)";
    default: return "a signal"; // not installed for any other
    }
}

void reportAndEnd(int signalNumber) {
    if (gReporting.exchange(true)) {
        // Another thread crashed first and is reporting: its report ends the process (or SIGALRM does).
        const timespec second{1, 0};
        for (unsigned i = 0; i <= kReportSeconds; ++i) ::nanosleep(&second, nullptr);
        endBySignal(signalNumber);
    }
    // Unwinding can block for good (a crash inside the dynamic loader holds the lock it needs): SIGALRM's default
    // action ends the process then, so a crash never becomes a hang.
    ::alarm(kReportSeconds);
    writeText("\ninkgraph: internal error: ");
    writeText(crashSignalName(signalNumber));
    writeText(" in ");
    writeText(gBuild);
    writeText(". This is a bug: please report it with the command that caused it and the lines below.\n");
    void* frames[kMaxFrames];
    const int count = ::backtrace(frames, kMaxFrames);
    ::backtrace_symbols_fd(frames, count, STDERR_FILENO);
    writeText("inkgraph: (each line is FILE(+OFFSET): `addr2line -Cfe FILE OFFSET` names its function)\n");
    endBySignal(signalNumber);
}

} // namespace

void reportCrashes(const char* build) {
    static std::atomic<bool> installed{false};
    if (installed.exchange(true)) return;
    std::strncpy(gBuild, build, sizeof gBuild - 1);
    // backtrace() loads libgcc's unwinder on its first call, which allocates: done here, not on a corrupted heap.
    void* warmUp[1];
    ::backtrace(warmUp, 1);
    stack_t alternate{};
    alternate.ss_sp = gAlternateStack;
    alternate.ss_size = sizeof gAlternateStack;
    ::sigaltstack(&alternate, nullptr);
    struct sigaction action {};
    action.sa_handler = reportAndEnd;
    // Every crash signal blocked while a thread reports: a crash inside the report then takes the signal's default
    // action at once (the kernel does not hold back a fault's signal), while another thread's crash waits.
    sigemptyset(&action.sa_mask);
    for (const int signalNumber : kCrashSignals) sigaddset(&action.sa_mask, signalNumber);
    action.sa_flags = SA_ONSTACK;
    for (const int signalNumber : kCrashSignals) ::sigaction(signalNumber, &action, nullptr);
}

} // namespace inkgraph
