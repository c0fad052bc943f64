#!/usr/bin/env bash
# Quick start 1: install what is missing, build (Release), render the bundled default model into out/.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/install-deps.sh"
"$root/scripts/build.sh"
mkdir -p "$root/out"
"$root/build/inkgraph" render "$root/models/bunny_c3d_70k.obj" -o "$root/out/bunny.png" --lines outline \
    --dump "$root/out/bunny-dump" --request 'gbuffer.*' --stats "$root/out/bunny-stats.json"
echo "Rendered $root/out/bunny.png (intermediates in $root/out/bunny-dump, timings in $root/out/bunny-stats.json)"
