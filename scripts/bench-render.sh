#!/usr/bin/env bash
# Whole-process wall time of `inkgraph render` at 1024x1024: the bunny (70k triangles) and a generated 1M-triangle
# sphere, RUNS runs each (default 7), median and min printed. Run after scripts/build.sh.
#   scripts/bench-render.sh [RUNS]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
runs=${1:-7}
build="$root/build"
work="$build/bench-data"
mesh_tool="$build/bench/inkgraph_make_mesh"
mkdir -p "$work"
[ -f "$work/sphere-1m.obj" ] || "$mesh_tool" sphere 1000000 "$work/sphere-1m.obj"

time_runs() { # label model
    local label=$1 model=$2 times=()
    for _ in $(seq "$runs"); do
        local start end
        start=$(date +%s%N)
        "$build/inkgraph" render "$model" -o "$work/out.png" -q
        end=$(date +%s%N)
        times+=($(( (end - start) / 1000000 )))
    done
    local sorted
    sorted=$(printf '%s\n' "${times[@]}" | sort -n)
    printf '%-28s median %5d ms   min %5d ms   (%d runs: %s)\n' "$label" \
        "$(echo "$sorted" | sed -n "$(( (runs + 1) / 2 ))p")" "$(echo "$sorted" | head -1)" "$runs" "${times[*]}"
}

echo "inkgraph render, 1024x1024, --shading lambert; LP_NUM_THREADS=${LP_NUM_THREADS:-unset}"
time_runs "bunny (69,451 triangles)" "$root/models/bunny_c3d_70k.obj"
time_runs "sphere (1,000,000 triangles)" "$work/sphere-1m.obj"
