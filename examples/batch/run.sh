#!/usr/bin/env bash
# Every model of models.txt in one process: one GL context, each shader program compiled once, a progress line per
# model, and a picture, its stats and its contact sheet per model. A model that fails is reported and skipped.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
inkgraph=${INKGRAPH:-$root/build/inkgraph} # INKGRAPH, OUT and SIZE override the defaults (scripts/gallery.sh, tests)
out=${OUT:-$root/out/examples/batch}
mkdir -p "$out"
cd "$root" # the list's paths are relative to the repository root
"$inkgraph" render --list examples/batch/models.txt --size "${SIZE:-768x768}" \
    --shading comic --lines outline,contour \
    -o "$out/{index}-{name}.png" --stats "$out/{index}-{name}.json"
