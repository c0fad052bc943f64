#!/usr/bin/env bash
# A glTF scene of four objects: no camera or light flags, the file's camera and its KHR_lights_punctual key light
# frame and light it; each material names its own comic shade map, so one render shows four of them.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
inkgraph=${INKGRAPH:-$root/build/inkgraph} # INKGRAPH, OUT and SIZE override the defaults (scripts/gallery.sh, tests)
out=${OUT:-$root/out/examples/still-life}
mkdir -p "$out"
"$inkgraph" render "$root/examples/still-life/still-life.gltf" --size "${SIZE:-1280x800}" \
    --shading comic --lines outline,contour \
    -o "$out/still-life.png" --stats "$out/stats.json"
