#include "app/Render.h"

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
    std::_Exit(exitCode);
}
