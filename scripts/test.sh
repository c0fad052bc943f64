#!/usr/bin/env bash
# Quick start 2: install what is missing, build (Release), run the whole test suite (GL tests on llvmpipe); then build
# the suite again with AddressSanitizer and UndefinedBehaviorSanitizer and run it there too (scripts/test-sanitized.sh).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/install-deps.sh"
"$root/scripts/build.sh"
# llvmpipe with two threads sometimes runs 2-3x slower for seconds on 2-core machines.
export LP_NUM_THREADS=1
(cd "$root/build" && ctest --output-on-failure --timeout 600 -j"$(nproc 2>/dev/null || echo 2)")
"$root/scripts/test-sanitized.sh"
