#!/usr/bin/env bash
# The Stanford bunny in cel shading with every kind of line a scan has: Lander's outline, contours, suggestive
# contours found on the mesh, and the scan's holes as borders. Also writes the contact sheet and the SVG.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
inkgraph=${INKGRAPH:-$root/build/inkgraph} # INKGRAPH, OUT and SIZE override the defaults (scripts/gallery.sh, tests)
out=${OUT:-$root/out/examples/bunny-cel-lines}
mkdir -p "$out"
"$inkgraph" render "$root/models/bunny_c3d_70k.obj" --size "${SIZE:-1024x1024}" \
    --shading cel --lines outline,border,suggestive-object,contour \
    --outline-width 3 \
    --suggestive-threshold 0.08 --suggestive-object-width 1.5 --suggestive-object-color 0.2,0.2,0.35 \
    --border-width 1.5 --border-color 0.7,0.15,0.1 \
    -o "$out/bunny.png" --contact-sheet "$out/bunny-sheet.png" --svg "$out/bunny-lines.svg" \
    --stats "$out/bunny-stats.json"
