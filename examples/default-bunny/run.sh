#!/usr/bin/env bash
# The default model with every G-buffer intermediate dumped (float32 EXR), its stats, and the plan printed.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
inkgraph=${INKGRAPH:-$root/build/inkgraph} # INKGRAPH, OUT and SIZE override the defaults (scripts/gallery.sh, tests)
out=${OUT:-$root/out/examples/default-bunny}
mkdir -p "$out"
"$inkgraph" render "$root/models/bunny_c3d_70k.obj" --size "${SIZE:-1024x1024}" -o "$out/bunny.png" \
    --request 'gbuffer.*' --dump "$out/dump" --stats "$out/stats.json" --print-plan
