#!/usr/bin/env bash
# Builds the whole suite with AddressSanitizer and UndefinedBehaviorSanitizer (-DINKGRAPH_SANITIZE=ON, -O1 with line
# tables; the test binaries' own code at -O0, tests/CMakeLists.txt says why; a unity build, as scripts/build.sh's) into
# build-asan/ and runs every test there,
# GL tests on llvmpipe included. Any sanitizer report fails the test that triggered it (UBSan does not recover;
# LeakSanitizer runs at the end of each process).
# tests/sanitizers/lsan.supp lists the leaks of Debian's libraries that are not ours. Run after
# scripts/install-deps.sh; scripts/test.sh runs it too.
# Races at process exit (a thread still starting or being torn down while LeakSanitizer stops them all,
# docs/robustness.md "How a process ends") have two guards: the test exit_threads_are_quiet fails on such a thread
# whether or not it crashes the check, and the tests that run the program itself (Cli.*, whose child is the sanitized
# inkgraph ending through finishProcess()) run three times (the whole suite once, then --repeat until-fail:2), so one
# that fails once in three runs fails here rather than in a later CI run by chance. Every other test runs once: three
# runs of all of them had grown to 36 of the 87 minutes a clean clone's .ci/run took on 2 cores at issue 38
# (docs/robustness.md, "Run time").
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build="$root/build-asan"
jobs=$(nproc 2>/dev/null || echo 2)
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" \
    -DINKGRAPH_SANITIZE=ON -DCMAKE_UNITY_BUILD=ON
cmake --build "$build" -j"$jobs"
export LP_NUM_THREADS=1
# intercept_tls_get_addr=0: GCC 12's runtime takes a dynamic TLS block whose address is 16 past a page boundary for
# glibc 2.19's layout and records a bogus range, which LeakSanitizer's tracer then crashes reading (docs/robustness.md).
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1:intercept_tls_get_addr=0"
export LSAN_OPTIONS="suppressions=$root/tests/sanitizers/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
cd "$build"
# Not here: the tests labelled install (they install and package the Release build's programs), python (an
# instrumented extension cannot load into Debian's uninstrumented python3) and slurm (it runs the installed program);
# scripts/test.sh runs them in the Release build.
ctest --output-on-failure --timeout 900 -j"$jobs" --label-exclude '^(install|python|slurm)$'
ctest --output-on-failure --timeout 900 -j"$jobs" --repeat until-fail:2 --tests-regex '^Cli\.' \
    --label-exclude '^(install|python|slurm)$'
