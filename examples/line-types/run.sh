#!/usr/bin/env bash
# Every line type alone on the same model and camera (toggling one pass at a time), in one process: the list of
# looks is the same model rendered with --lines TYPE each time. --stats shows which passes ran and which were culled.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
inkgraph=${INKGRAPH:-$root/build/inkgraph} # INKGRAPH, OUT and SIZE override the defaults (scripts/gallery.sh, tests)
out=${OUT:-$root/out/examples/line-types}
mkdir -p "$out"
for type in outline silhouette contour suggestive suggestive-object depth-edge normal-edge mesh-silhouette crease \
            border; do
    "$inkgraph" render "$root/models/suzanne_npm_4k.obj" --size "${SIZE:-512x512}" --shading none \
        --lines "$type" --"$type"-width 2 -o "$out/$type.png" --stats "$out/$type-stats.json" -q
done
"$inkgraph" render "$root/models/suzanne_npm_4k.obj" --size "${SIZE:-512x512}" --shading cel \
    --lines outline,contour,suggestive,border -o "$out/together.png" -q
echo "wrote one picture per line type into $out"
