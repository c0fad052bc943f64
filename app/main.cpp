#include "render/BackgroundThreads.h"
#include "render/CrashReport.h"
#include "app/Cli.h"
#include "app/Version.h"

#include <cstdio>
#include <cstdlib>
#include <iostream>

#include <malloc.h>

#if defined(__GLIBC__)
#include <sys/auxv.h>
#include <unistd.h>
#endif

// Not in a sanitized build: its allocator replaces glibc's, so there is nothing to tune.
#if defined(__GLIBC__) && !defined(__SANITIZE_ADDRESS__)
namespace {

/** What the command line asks of glibc's malloc (docs/performance.md, "Huge pages"):
 *  - transparent huge pages (madvise(MADV_HUGEPAGE)) for the heap and for mapped blocks. A still touches a few
 *    hundred MiB of fresh memory (llvmpipe's textures, the read-backs, the post stage's images); on the 2-core VM
 *    every 4 KiB page costs a page fault of about 7 us, a third of a single still's CPU, and the TLB misses of 4 KiB
 *    pages slow every pass that sweeps a whole image. The bunny's comic still 0.58 -> 0.38 s as a whole process, the
 *    36-still comic batch 2.16 -> 1.98 s. Where the kernel has transparent huge pages off, the madvise does nothing;
 *  - one arena for every thread. A worker thread's arena grows by heaps of at most 64 MiB and unmaps all but its
 *    first once a still's images are freed, so each still faulted its post stage's images in again; in the main
 *    arena they stay (M_TRIM_THRESHOLD below). 7-13% less CPU over the 36-still comic batch. */
constexpr const char* kMallocTunables = "glibc.malloc.hugetlb=1:glibc.malloc.arena_max=1";

/** glibc reads its tunables only when a process starts, from GLIBC_TUNABLES, so the program runs itself again with
 *  them (the same process id, arguments and files; about 20 ms). Whoever sets GLIBC_TUNABLES, even empty, keeps
 *  glibc's own choice: the variable is then left alone, which also ends the second start here. A setuid start
 *  (AT_SECURE), where glibc would drop the variable, a start through the dynamic loader and a failed exec run on as
 *  they are. */
void restartWithMallocTunables(char** argv) {
    if (std::getenv("GLIBC_TUNABLES") != nullptr || getauxval(AT_SECURE) != 0) return;
    // Started through the dynamic loader (ld-linux.so PROGRAM ...), /proc/self/exe is the loader, and the kernel
    // gave it no interpreter (AT_BASE 0): it runs on as it is.
    if (getauxval(AT_BASE) == 0) return;
    if (setenv("GLIBC_TUNABLES", kMallocTunables, 1) != 0) return;
    execv("/proc/self/exe", argv);
    unsetenv("GLIBC_TUNABLES");
}

} // namespace
#endif

int main(int argc, char** argv) {
#if defined(__GLIBC__)
#if !defined(__SANITIZE_ADDRESS__) // the sanitizer's allocator replaces glibc's: nothing to tune
    restartWithMallocTunables(argv);
#endif
    // Buffers up to 32 MiB (a 1024^2 float image is 16) come from the heap and stay there when freed, instead of being
    // mapped and unmapped each time: the post stage's temporaries then reuse pages already faulted in. On the 2-core VM
    // the bunny's comic still takes about 8,000 page faults fewer (of 43,000) and 5-8 ms less, for 10 MiB more peak
    // memory (docs/performance.md).
    mallopt(M_MMAP_THRESHOLD, 32 << 20);
    mallopt(M_TRIM_THRESHOLD, 256 << 20);
#endif
#if !defined(__SANITIZE_ADDRESS__) && !defined(__SANITIZE_THREAD__) // the sanitizers report crashes themselves
    inkgraph::reportCrashes(inkgraph::versionLine().c_str());
#endif
    const int exitCode = inkgraph::runCommandLine(argc, argv, std::cout, std::cerr);
    // Every output is closed and renamed by now. Leaving without static destructors means an early error does not
    // wait for the OpenImageIO module that may still be loading on its background thread (render/ImageIoModule.h).
    std::cout.flush();
    std::cerr.flush();
    std::fflush(nullptr);
#if defined(__SANITIZE_ADDRESS__)
    // _Exit skips LeakSanitizer's check at exit. Sanitized builds (scripts/test-sanitized.sh) join the background
    // threads and run it here instead, so the CLI tests check the real program for leaks; a leak is reported and ends
    // the run with LeakSanitizer's code.
    inkgraph::finishProcess();
#endif
    std::_Exit(exitCode);
}
