#!/usr/bin/env bash
# Configures and builds inkgraph (Release) into build/. Usage: scripts/build.sh [extra cmake args]
# A unity build (CMAKE_UNITY_BUILD: each target's files compiled eight to a translation unit, so the headers are parsed
# and their templates instantiated once per batch): on the 2-core machine 825 task-seconds against 1,357 (ninja's log;
# docs/robustness.md, "Run time"). A plain `cmake -S . -B DIR` compiles every file alone; -DCMAKE_UNITY_BUILD=OFF here
# does too (a later -D wins).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
jobs=$(nproc 2>/dev/null || echo 2)
cmake -S "$root" -B "$root/build" -DCMAKE_BUILD_TYPE=Release -DCMAKE_UNITY_BUILD=ON "$@"
cmake --build "$root/build" -j"$jobs"
