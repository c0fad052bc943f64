#!/usr/bin/env bash
# The comic look (outline, contour, suggestive contours, creases) on the scans, suzanne and the characters, drawn as
# strokes (docs/lines.md, "Strokes"): chained through junctions and across types, specks dropped by the length rule,
# creases kept only where they are long on the mesh. Also the bunny with line weight, and its strokes as SVG.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
inkgraph=${INKGRAPH:-$root/build/inkgraph} # INKGRAPH, OUT and SIZE override the defaults (scripts/gallery.sh, tests)
out=${OUT:-$root/out/examples/clean-strokes}
size=${SIZE:-1024x1024}
mkdir -p "$out"
comic=(--shading comic --lines outline,contour,suggestive,crease)
for model in models/bunny_c3d_70k.obj models/armadillo_cgal_52k.obj models/lucy_blendify_15k.obj \
    models/suzanne_npm_4k.obj models/characters/fox.glb models/characters/godette.vrm; do
    name=$(basename "$model")
    name=${name%%_*}
    name=${name%.*}
    "$inkgraph" render "$root/$model" --size "$size" "${comic[@]}" -o "$out/$name.png" -q
done
# Line weight: thinner toward the back of the model, tapered stroke ends; the same strokes as vector paths.
"$inkgraph" render "$root/models/bunny_c3d_70k.obj" --size "$size" "${comic[@]}" --line-weight depth,taper \
    -o "$out/bunny-weight.png" --svg "$out/bunny-weight.svg" -q
"$inkgraph" render "$root/models/bunny_c3d_70k.obj" --size "$size" "${comic[@]}" --svg "$out/bunny.svg" -q
