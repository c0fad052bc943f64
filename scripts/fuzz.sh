#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, ASan + UBSan, -DINKGRAPH_FUZZ=ON) into build-fuzz/ and runs each for SECONDS
# (default 600), one after the other, starting from its corpus in tests/fuzz/corpus/. What the fuzzer learns goes to
# build-fuzz/corpus/<target>/; a crash, leak, hang (> 10 s per input) or single allocation above 1 GiB stops that
# target and leaves its input in build-fuzz/artifacts/<target>/. Copy such an input to tests/fuzz/regressions/<target>/
# once fixed: the fuzz_replay_<target> ctest test replays it from then on.
#   scripts/fuzz.sh [SECONDS] [TARGET...]     targets: obj stl ply gltf shademap style texture mtoon skin referenced
#                                             python_args (default: all)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
seconds=${1:-600}
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(obj stl ply gltf shademap style texture mtoon skin referenced python_args)
build="$root/build-fuzz"

if ! command -v clang++ >/dev/null || ! dpkg-query -W -f='${Status}' libclang-rt-14-dev 2>/dev/null | grep -q "ok installed"; then
    echo "fuzz: needs clang and libFuzzer (Debian: apt-get install clang libclang-rt-14-dev)" >&2
    exit 1
fi
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
    -DINKGRAPH_FUZZ=ON -DINKGRAPH_BUILD_TESTS=OFF -DINKGRAPH_BUILD_BENCH=OFF >/dev/null
cmake --build "$build" -j"$(nproc 2>/dev/null || echo 2)" --target $(printf 'fuzz_%s ' "${targets[@]}")

export LP_NUM_THREADS=1
export LSAN_OPTIONS="suppressions=$root/tests/sanitizers/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
status=0
for target in "${targets[@]}"; do
    corpus="$build/corpus/$target"
    artifacts="$build/artifacts/$target"
    mkdir -p "$corpus" "$artifacts" "$build/work/$target"
    echo "fuzz: $target for ${seconds}s (log: $build/fuzz-$target.log)"
    # Run in an empty folder: glTF buffer URIs are resolved against it.
    if (cd "$build/work/$target" && "$build/tests/fuzz/fuzz_$target" "$corpus" "$root/tests/fuzz/corpus/$target" \
            -max_total_time="$seconds" -timeout=10 -malloc_limit_mb=1024 -rss_limit_mb=2048 -max_len=65536 \
            -artifact_prefix="$artifacts/" -print_final_stats=1 >"$build/fuzz-$target.log" 2>&1); then
        echo "fuzz: $target: $(grep -E 'stat::number_of_executed_units' "$build/fuzz-$target.log" | awk '{print $2}') runs, no failure"
    else
        echo "fuzz: $target FAILED; see $build/fuzz-$target.log and $artifacts/" >&2
        status=1
    fi
done
exit $status
