#include "render/BackgroundThreads.h"
#include "app/Cli.h"

#include <cstdio>
#include <cstdlib>
#include <iostream>

#include <malloc.h>

int main(int argc, char** argv) {
#if defined(__GLIBC__)
    // Buffers up to 32 MiB (a 1024^2 float image is 16) come from the heap and stay there when freed, instead of being
    // mapped and unmapped each time: the post stage's temporaries then reuse pages already faulted in. On the 2-core VM
    // the bunny's comic still takes about 8,000 page faults fewer (of 43,000) and 5-8 ms less, for 10 MiB more peak
    // memory (docs/performance.md).
    mallopt(M_MMAP_THRESHOLD, 32 << 20);
    mallopt(M_TRIM_THRESHOLD, 256 << 20);
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
