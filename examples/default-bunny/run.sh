#!/usr/bin/env bash
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
out="$root/out/examples/default-bunny"
mkdir -p "$out"
"$root/build/inkgraph" render "$root/models/bunny_c3d_70k.obj" -o "$out/bunny.png" \
    --request 'gbuffer.*' --dump "$out/dump" --stats "$out/stats.json" --print-plan
