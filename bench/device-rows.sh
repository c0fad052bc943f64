#!/usr/bin/env bash
# Issue 20's whole-process rows and the G-buffer benchmarks on a GPU machine that has none of our Debian libraries,
# through the device kit (bench/device-kit.sh, carried as .devicekit/), run from the repository root:
#   bash bench/device-rows.sh       (results in $OUT, default /tmp/out; under 7 minutes, 14 if every step times out)
# Steps, each under `timeout`: NVIDIA's glvnd vendor file as __EGL_VENDOR_LIBRARY_FILENAMES (when the environment does
# not set it), and its library's folder (searched in VENDOR_LIB_DIRS, default /usr/local/nvidia/lib64 and lib, then
# the system's) added to LD_LIBRARY_PATH when the kit's loader would not search it; one bunny still with
# --egl-platform device and --stats, which must report the device platform and a renderer that is not llvmpipe
# (ALLOW_LLVMPIPE=1 accepts it: a CPU machine testing the kit); whole-process.sh's rows (ROWS, default "probe tetra
# bunny batch large comic36 comic36-serial comic36-d2 comic36-d4 comic36-d8 comic36-p4 comic36-p8 comic36-p16", RUNS
# rounds, default 7, with GPU_BUSY=1: each comic36 row's mean nvidia-smi utilization) into $OUT/gpu-rows.md, then (READBACK_ROWS=1, the
# default) the comic36 row again with --readback early and late forced, into $OUT/gpu-readback-*.md, and
# (POST_STAGE_ROWS=1, the default) with --post-stage cpu and gpu forced, into $OUT/gpu-post-stage-*.md, the 36 PNGs
# of each compared byte for byte; the medians of --stats' steps over the 36 stills drawn serially, into
# $OUT/gpu-still-times.md; the kit's GL tests (bin/*_gl_tests, GoogleTest) into $OUT/gpu-gl-tests.txt;
# inkgraph_bench, when the kit has it, with BENCH_FILTER (default BM_GBufferVsBareDraw|BM_DeferredShading|BM_PostStage,
# one process per |-separated pattern) and BENCH_REPETITIONS (default 5) into $OUT/gpu-bench.txt and
# gpu-bench-PATTERN.json. The kit is .devicekit/, unpacked from .devicekit.tar.xz (device-kit.sh's KIT_ARCHIVE=1)
# when only the archive came. A failed still stops the script
# (its stderr, the probe's output and a loader trace in $OUT); a failed row or benchmark leaves its output in $OUT,
# the later steps still run and the exit status is 1. Everything printed is also in $OUT/device-rows.log.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
kit=${KIT:-$root/.devicekit}
if [ ! -e "$kit" ] && [ -f "$kit.tar.xz" ]; then
    echo "device-rows.sh: unpacking $kit.tar.xz"
    tar -C "$(dirname "$kit")" -xJf "$kit.tar.xz" ||
        python3 -c 'import sys, tarfile; tarfile.open(sys.argv[1]).extractall(sys.argv[2])' "$kit.tar.xz" \
            "$(dirname "$kit")" || { echo "device-rows.sh: $kit.tar.xz could not be unpacked" >&2; exit 1; }
fi
if [ ! -x "$kit/run/inkgraph" ]; then
    echo "device-rows.sh: no device kit in $kit (bench/device-kit.sh makes it)" >&2
    exit 1
fi
kit=$(cd "$kit" && pwd)
out=${OUT:-/tmp/out}
rows=${ROWS:-"probe tetra bunny batch large comic36 comic36-serial comic36-d2 comic36-d4 comic36-d8 comic36-p4
    comic36-p8 comic36-p16"}
runs=${RUNS:-7}
filter=${BENCH_FILTER:-"BM_GBufferVsBareDraw|BM_DeferredShading|BM_PostStage"}
repetitions=${BENCH_REPETITIONS:-5}
mkdir -p "$out"
out=$(cd "$out" && pwd)
exec > >(tee "$out/device-rows.log") 2>&1
failed=0
section() { printf '\n== %s (%s)\n' "$1" "$(date -u +%H:%M:%S)"; }

section "machine"
uname -srm
sed -n 's/^PRETTY_NAME=//p' /etc/os-release 2>/dev/null || true
echo "image glibc: $(getconf GNU_LIBC_VERSION 2>/dev/null || echo unknown)"
echo "kit: $(sed -n 2,6p "$kit/MANIFEST" | tr '\n' ' ')"
if command -v nvidia-smi >/dev/null; then
    timeout 20 nvidia-smi -L || echo "nvidia-smi -L failed"
    timeout 20 nvidia-smi --query-gpu=driver_version --format=csv,noheader | sed 's/^/driver /' || true
else
    echo "no nvidia-smi on PATH"
fi

section "EGL vendor"
if [ -z "${__EGL_VENDOR_LIBRARY_FILENAMES:-}" ]; then
    for vendor in /usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json \
        /usr/share/glvnd/egl_vendor.d/10_nvidia.json /etc/glvnd/egl_vendor.d/10_nvidia.json; do
        if [ -f "$vendor" ]; then
            export __EGL_VENDOR_LIBRARY_FILENAMES=$vendor
            break
        fi
    done
fi
echo "__EGL_VENDOR_LIBRARY_FILENAMES=${__EGL_VENDOR_LIBRARY_FILENAMES:-(unset: glvnd reads its own folders)}"
vendor_library=""
vendors=${__EGL_VENDOR_LIBRARY_FILENAMES:-}
for vendor in ${vendors//:/ }; do
    library=$(sed -n 's/.*"library_path"[[:space:]]*:[[:space:]]*"\([^"]*\)".*/\1/p' "$vendor" | head -1)
    case $library in
    "") echo "$vendor names no library_path" ;;
    /*) vendor_library=$library ;;
    *) # A bare name: the kit's loader finds it in LD_LIBRARY_PATH, the machine's ld.so.cache or the system folders.
        search=${LD_LIBRARY_PATH:-}
        for folder in ${search//:/ } ${VENDOR_LIB_DIRS:-/usr/local/nvidia/lib64 /usr/local/nvidia/lib} \
            /usr/lib/x86_64-linux-gnu /lib/x86_64-linux-gnu /usr/lib64 /usr/lib /lib64; do
            if [ -e "$folder/$library" ]; then
                vendor_library=$folder/$library
                break
            fi
        done
        if [ -z "$vendor_library" ] && command -v ldconfig >/dev/null; then
            vendor_library=$(ldconfig -p | awk -v name="$library" '$1 == name && /x86-64/ {print $NF; exit}')
        fi
        folder=$(dirname "${vendor_library:-/}")
        case ":${LD_LIBRARY_PATH:-}:/lib/x86_64-linux-gnu:/usr/lib/x86_64-linux-gnu:/lib:/usr/lib:/:" in
        *":$folder:"*) ;;
        *)
            export LD_LIBRARY_PATH=${LD_LIBRARY_PATH:+$LD_LIBRARY_PATH:}$folder
            echo "LD_LIBRARY_PATH=$LD_LIBRARY_PATH (the vendor library's folder added)"
            ;;
        esac
        ;;
    esac
    echo "$vendor: library_path $library -> ${vendor_library:-NOT FOUND}"
done
if [ -n "$vendor_library" ]; then
    # The vendor library's own libraries as the kit's loader resolves them: a mismatch with our glibc shows here.
    "$kit/lib/ld-linux-x86-64.so.2" --library-path "$kit/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" \
        --list "$vendor_library" >"$out/vendor-libs.txt" 2>&1 || true
    grep -E "not found|version|error" "$out/vendor-libs.txt" || echo "its libraries resolve ($out/vendor-libs.txt)"
fi

# The bench and the GL tests read models/ and bench/shaders/ from the source tree they were built in
# (INKGRAPH_SOURCE_ROOT).
source_root=$(sed -n 's/^source_root=//p' "$kit/MANIFEST")
if [ -n "$source_root" ] && [ ! -e "$source_root" ]; then
    mkdir -p "$(dirname "$source_root")"
    ln -s "$root" "$source_root"
    echo "made $source_root a link to $root (the build's source root)"
fi

section "one still: the device platform and the renderer"
stats=$out/bunny-stats.json
still=(render models/bunny_c3d_70k.obj -o "$out/bunny.png" --shading cel --lines silhouette,contour,suggestive
    --egl-platform device --stats "$stats")
if timeout 60 "$kit/run/inkgraph" "${still[@]}" 2>"$out/bunny-stderr.txt"; then
    field() { # gl.NAME of the stats file
        if command -v python3 >/dev/null; then
            python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["gl"][sys.argv[2]])' "$stats" "$1"
        else
            sed -n "s/^ *\"$1\": *\"\\(.*\\)\",\\?\$/\\1/p" "$stats" | head -1
        fi
    }
    platform=$(field platform)
    renderer=$(field renderer)
    echo "gl.platform: $platform"
    echo "gl.renderer: $renderer"
    echo "gl.version:  $(field version)"
    if [ "$platform" != device ]; then
        echo "FAILED: the still ran on the '$platform' platform, not EGL's device platform"
        exit 1
    fi
    software='llvmpipe|softpipe|swrast|SwiftShader'
    if [[ $renderer =~ $software ]] && [ "${ALLOW_LLVMPIPE:-0}" != 1 ]; then
        echo "FAILED: the renderer is '$renderer' (software), not the GPU's; ALLOW_LLVMPIPE=1 accepts it"
        exit 1
    fi
else
    status=$?
    echo "FAILED (exit $status): $kit/run/inkgraph ${still[*]}"
    cat "$out/bunny-stderr.txt"
    echo "-- the probe (nothing of inkgraph linked):"
    timeout 30 "$kit/run/inkgraph_egl_probe" || echo "the probe failed too (exit $?)"
    echo "-- a loader trace of the still: $out/ld-debug.txt; its errors:"
    LD_DEBUG=libs,versions timeout 60 "$kit/run/inkgraph" "${still[@]}" >/dev/null 2>"$out/ld-debug.txt" || true
    grep -iE "error|cannot|not found|fatal|find library=lib(EGL|nvidia)" "$out/ld-debug.txt" | tail -20 || true
    ls -l /dev/nvidia* 2>&1 | head -5 || true
    exit 1
fi

section "whole-process rows: $rows, $runs rounds"
gnu_time=/usr/bin/time
[ -x "$gnu_time" ] || gnu_time=$kit/run/time
echo "GNU time: $gnu_time"
if GPU_BUSY=1 FREESTYLE=0 ROWS=$rows INKGRAPH=$kit/run/inkgraph EGL_PROBE=$kit/run/inkgraph_egl_probe \
    MAKE_MESH=$kit/run/inkgraph_make_mesh GNU_TIME=$gnu_time timeout 300 bash bench/whole-process.sh "$runs" \
    >"$out/gpu-rows.md"; then
    echo "GL: $renderer ($platform platform); $(command -v nvidia-smi >/dev/null &&
        timeout 20 nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | head -1)" >>"$out/gpu-rows.md"
    cat "$out/gpu-rows.md"
else
    echo "FAILED (exit $?): bench/whole-process.sh (timeout 300 s)"
    cat "$out/gpu-rows.md"
    failed=1
fi

# The 36 stills of the comic36 row (whole-process.sh's list), for the renders below that are not its rows.
for _ in 1 2 3 4; do grep -v '^#' examples/batch/models.txt; done >"$out/comic36.txt"

# The comic36 row again with one flag forced to each of its words (a wrapper per word, so whole-process.sh runs the
# same row with the flag added): FLAG, NAME (the files' stem), the words.
flag_rows() {
    local flag=$1 name=$2 word
    shift 2
    section "$flag $*: the comic36 row, 3 rounds each"
    for word in "$@"; do
        printf '#!/bin/sh\nexec "%s" "$@" %s %s\n' "$kit/run/inkgraph" "$flag" "$word" >"$out/inkgraph-$name-$word"
        chmod +x "$out/inkgraph-$name-$word"
        if GPU_BUSY=1 ROWS=comic36 INKGRAPH=$out/inkgraph-$name-$word GNU_TIME=$gnu_time timeout 120 \
            bash bench/whole-process.sh 3 >"$out/gpu-$name-$word.md"; then
            echo "$flag $word:"
            sed -n 3p "$out/gpu-$name-$word.md"
        else
            echo "FAILED (exit $?): $flag $word"
            failed=1
        fi
    done
}
if [ "${READBACK_ROWS:-1}" = 1 ]; then flag_rows --readback readback early late; fi
if [ "${POST_STAGE_ROWS:-1}" = 1 ]; then
    flag_rows --post-stage post-stage cpu gpu
    # The same 36 stills from either post stage, compared byte for byte; the files that differ are named.
    for device in cpu gpu; do
        rm -rf "/tmp/post-$device" && mkdir -p "/tmp/post-$device"
        timeout 60 "$kit/run/inkgraph" render --list "$out/comic36.txt" -o "/tmp/post-$device/{index}.png" \
            --shading cel --lines silhouette,contour,suggestive --post-stage "$device" -q ||
            { echo "FAILED (exit $?): the comic36 stills with --post-stage $device"; failed=1; }
    done
    same=0 different=""
    for file in /tmp/post-cpu/*.png; do
        if cmp -s "$file" "/tmp/post-gpu/$(basename "$file")"; then same=$((same + 1)); else different+=" $(basename "$file")"; fi
    done
    echo "--post-stage cpu against gpu: $same of $(ls /tmp/post-cpu | wc -l) PNGs byte-identical${different:+; differ:$different}"
fi

section "where a comic still's time goes: the comic36 stills, --jobs 0, --stats each"
# Medians over the 36 stills of --stats' per-pass milliseconds (GL passes to glFinish, the post stage's), loading
# and writing, serial so that each still's numbers are its own; into $OUT/gpu-still-times.md.
rm -rf /tmp/still-stats && mkdir -p /tmp/still-stats
if timeout 90 "$kit/run/inkgraph" render --list "$out/comic36.txt" -o "/tmp/still-stats/{index}.png" --shading cel \
    --lines silhouette,contour,suggestive --jobs 0 --stats "/tmp/still-stats/{index}.json" -q &&
    command -v python3 >/dev/null; then
    python3 - /tmp/still-stats >"$out/gpu-still-times.md" <<'PYTHON'
import glob, json, statistics, sys
stills = [json.load(open(f)) for f in sorted(glob.glob(sys.argv[1] + "/*.json"))]
rows = {}
for still in stills:
    for key in ("load_ms", "context_ms", "write_ms", "total_ms"):
        rows.setdefault(key, []).append(still.get(key, 0) or 0)
    for stage in still.get("passes", []):
        rows.setdefault("pass " + stage["name"], []).append(stage["ms"])
print(f"| step | median ms over {len(stills)} stills | max ms |")
print("|---|---:|---:|")
for key, values in rows.items():
    print(f"| {key} | {statistics.median(values):.2f} | {max(values):.2f} |")
PYTHON
    cat "$out/gpu-still-times.md"
else
    echo "FAILED or no python3: the comic36 stills with --stats"
    failed=1
fi

section "the kit's GL tests"
tests_found=0
: >"$out/gpu-gl-tests.txt"
for test in "$kit"/run/*_gl_tests; do
    [ -x "$test" ] || continue
    tests_found=1
    if timeout 120 "$test" >>"$out/gpu-gl-tests.txt" 2>&1; then
        echo "$(basename "$test"): passed ($(grep -c '^\[       OK \]' "$out/gpu-gl-tests.txt") tests so far)"
    else
        echo "FAILED (exit $?): $(basename "$test") (timeout 120 s)"
        grep -E '^\[  FAILED  \]|Failure|error' "$out/gpu-gl-tests.txt" | head -20 || true
        failed=1
    fi
done
[ "$tests_found" = 1 ] || echo "skipped: the kit has no GL tests (KIT_TESTS)"

section "inkgraph_bench: $filter"
if [ -x "$kit/run/inkgraph_bench" ]; then
    if [ -f "$source_root/models/bunny_c3d_70k.obj" ] && [ -f "$source_root/bench/shaders/bare_draw.vert" ]; then
        : >"$out/gpu-bench.txt"
        for pattern in ${filter//|/ }; do # one process each: a benchmark that aborts loses only its own numbers
            if timeout 90 "$kit/run/inkgraph_bench" --benchmark_filter="$pattern" \
                --benchmark_repetitions="$repetitions" --benchmark_report_aggregates_only=true \
                --benchmark_out="$out/gpu-bench-${pattern//[^A-Za-z0-9_]/_}.json" --benchmark_out_format=json \
                >>"$out/gpu-bench.txt" 2>&1; then
                :
            else
                echo "FAILED (exit $?): inkgraph_bench --benchmark_filter=$pattern (timeout 90 s)" \
                    >>"$out/gpu-bench.txt"
                failed=1
            fi
        done
        cat "$out/gpu-bench.txt"
    else
        echo "skipped: '$source_root' lacks models/bunny_c3d_70k.obj or bench/shaders/bare_draw.vert"
    fi
else
    echo "skipped: the kit has no inkgraph_bench"
fi

section "done: $out"
ls "$out"
exit "$failed"
