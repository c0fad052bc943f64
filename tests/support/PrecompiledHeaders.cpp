// The translation unit of the test binaries' precompiled header (tests/CMakeLists.txt, inkgraph_test_precompiled):
// it defines nothing; CMake compiles the header beside it, and every test target reuses that.
