#include "app/BackgroundThreads.h"
#include "app/Cli.h"

#include <cstdio>
#include <cstdlib>
#include <iostream>

int main(int argc, char** argv) {
    const int exitCode = inkgraph::runCommandLine(argc, argv, std::cout, std::cerr);
    // Every output is closed and renamed by now. Leaving without static destructors means an early error does not
    // wait for the OpenImageIO module that may still be loading on its background thread (app/ImageIoModule.h).
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
