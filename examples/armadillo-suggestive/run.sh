#!/usr/bin/env bash
# The armadillo's muscle folds as suggestive contours (DeCarlo et al.), both ways: found on the mesh from
# per-vertex curvature (suggestive-object) and in the float G-buffer by finite differences (suggestive).
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
inkgraph=${INKGRAPH:-$root/build/inkgraph} # INKGRAPH, OUT and SIZE override the defaults (scripts/gallery.sh, tests)
out=${OUT:-$root/out/examples/armadillo-suggestive}
mkdir -p "$out"
camera=(--eye 120,60,-330 --target 0,20,0)
"$inkgraph" render "$root/models/armadillo_cgal_52k.obj" --size "${SIZE:-1024x1024}" "${camera[@]}" \
    --lines contour,suggestive-object --suggestive-threshold 0.03 \
    -o "$out/armadillo-object.png" --stats "$out/armadillo-object-stats.json"
"$inkgraph" render "$root/models/armadillo_cgal_52k.obj" --size "${SIZE:-1024x1024}" "${camera[@]}" \
    --lines contour,suggestive --suggestive-threshold 0.03 --supersample 2 \
    -o "$out/armadillo-image.png" --stats "$out/armadillo-image-stats.json"
