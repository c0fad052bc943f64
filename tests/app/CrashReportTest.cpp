// The crash report (render/CrashReport.h) on real faults, each in a process of its own (a death test): a null
// dereference, a stack overflow (the report runs on a stack of its own), glibc's abort on a double free, and two
// threads crashing at once (one report, whole). The command line's own report is checked through the executable by
// Cli.ACrashTellsTheSignalTheBuildAndTheStackThenEndsByTheSignal.
#include "render/CrashReport.h"

#include <gtest/gtest.h>

#include <signal.h>
#include <sys/resource.h>

#include <cstdlib>
#include <string>
#include <thread>

namespace inkgraph {
namespace {

int* volatile gNowhere = nullptr;

/** In the death test's child: the report installed, and no core file left where the tests run. */
void reportWithoutCoreFile() {
    const rlimit none{0, 0};
    ::setrlimit(RLIMIT_CORE, &none);
    reportCrashes("crash-test");
}
volatile int gNeverReached = -1;

[[noreturn]] void dereferenceNull() {
    reportWithoutCoreFile();
    *gNowhere = 1;
    std::abort(); // not reached
}

/** Not a tail call (the frame's array is read after the call), so every call takes stack. */
int recurseWithoutEnd(int depth) {
    volatile char frame[512];
    frame[0] = char(depth);
    if (depth == gNeverReached) return 0;
    return recurseWithoutEnd(depth + 1) + frame[0];
}

[[noreturn]] void overflowTheStack() {
    reportWithoutCoreFile();
    recurseWithoutEnd(0);
    std::abort(); // not reached
}

[[noreturn]] void freeTwice() {
    reportWithoutCoreFile();
    char* volatile block = static_cast<char*>(std::malloc(64));
    std::free(block);
    std::free(block);
    std::abort(); // not reached when glibc finds the double free
}

[[noreturn]] void crashInTwoThreads() {
    reportWithoutCoreFile();
    std::thread first([] { *gNowhere = 1; });
    std::thread second([] { *gNowhere = 2; });
    first.join();
    second.join();
    std::abort(); // not reached
}

std::size_t occurrences(const std::string& text, const std::string& part) {
    std::size_t count = 0;
    for (std::size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++count;
    return count;
}

/** The report's first line once, a stack of at least three frames, and its last line once. */
class OneWholeReport : public ::testing::MatcherInterface<const std::string&> {
public:
    explicit OneWholeReport(const std::string& signal)
        : mFirst("inkgraph: internal error: " + signal +
                 " in crash-test. This is a bug: please report it with the command that caused it and the lines "
                 "below.\n") {}

    bool MatchAndExplain(const std::string& err, ::testing::MatchResultListener* listener) const override {
        const std::size_t start = err.find(mFirst);
        const std::size_t end = err.find(kLast);
        const std::size_t frames =
            start < end && end != std::string::npos ? occurrences(err.substr(start, end - start), ")[0x") : 0;
        *listener << occurrences(err, mFirst) << " first lines, " << occurrences(err, kLast) << " last lines, "
                  << frames << " frames between them";
        return occurrences(err, mFirst) == 1 && occurrences(err, kLast) == 1 && frames >= 3;
    }
    void DescribeTo(std::ostream* os) const override { *os << "one whole report starting '" << mFirst << "'"; }

private:
    static constexpr const char* kLast =
        "inkgraph: (each line is FILE(+OFFSET): `addr2line -Cfe FILE OFFSET` names its function)\n";
    std::string mFirst;
};

::testing::Matcher<const std::string&> oneWholeReport(const std::string& signal) {
    return ::testing::MakeMatcher(new OneWholeReport(signal));
}

class CrashReport : public ::testing::Test {
protected:
    void SetUp() override {
#if defined(__SANITIZE_ADDRESS__)
        GTEST_SKIP()
            << "a sanitized build reports crashes through its sanitizer: app/main.cpp installs no report there";
#endif
        GTEST_FLAG_SET(death_test_style, "threadsafe");
    }
};

TEST_F(CrashReport, ANullDereferenceIsReportedAndEndsBySigsegv) {
    EXPECT_EXIT(dereferenceNull(), ::testing::KilledBySignal(SIGSEGV), oneWholeReport("SIGSEGV (segmentation fault)"));
}

TEST_F(CrashReport, AStackOverflowIsReportedOnTheReportsOwnStack) {
    EXPECT_EXIT(overflowTheStack(), ::testing::KilledBySignal(SIGSEGV), oneWholeReport("SIGSEGV (segmentation fault)"));
}

TEST_F(CrashReport, GlibcsAbortOnACorruptedHeapIsReportedAndEndsBySigabrt) {
    EXPECT_EXIT(freeTwice(), ::testing::KilledBySignal(SIGABRT), oneWholeReport("SIGABRT (aborted)"));
}

TEST_F(CrashReport, TwoThreadsCrashingAtOnceGiveOneWholeReport) {
    EXPECT_EXIT(crashInTwoThreads(), ::testing::KilledBySignal(SIGSEGV),
                oneWholeReport("SIGSEGV (segmentation fault)"));
}

} // namespace
} // namespace inkgraph
