// main() of the test binaries (tests/CMakeLists.txt, inkgraph_add_test): GoogleTest's, then the end that every
// inkgraph process shares (render/BackgroundThreads.h): the background threads joined and, in sanitized builds,
// LeakSanitizer's check run before any library's static teardown starts ending its own threads.
#include "render/BackgroundThreads.h"

#include <gtest/gtest.h>

int main(int argc, char** argv) {
    ::testing::InitGoogleTest(&argc, argv);
    const int result = RUN_ALL_TESTS();
    inkgraph::finishProcess();
    return result;
}
