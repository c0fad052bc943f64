#!/usr/bin/env bash
# The lines Pencil+ and Blender's Line Art draw that the other examples do not: where surfaces cross (intersection),
# what the model hides (--hidden-lines, dashed) and where one object meets another (object-boundary), on a VRM
# character and on a CAD part.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
inkgraph=${INKGRAPH:-$root/build/inkgraph} # INKGRAPH, OUT and SIZE override the defaults (scripts/gallery.sh, tests)
out=${OUT:-$root/out/examples/intersections-hidden-lines}
size=${SIZE:-1024x1024}
mkdir -p "$out"
# Godette's face: red where her hair and head cross (the hair is its own mesh and crosses itself), pink dashes where
# those crossings run on behind the hair, grey dashes for the silhouette edges the model hides.
"$inkgraph" render "$root/models/characters/godette.vrm" --size "$size" --frame head \
    --lines outline,contour,intersection --intersection-color 0.85,0.1,0.1 \
    --hidden-lines intersection,mesh-silhouette --hidden-dash 6,4 \
    --hidden-intersection-color 0.9,0.5,0.5 --hidden-intersection-width 1.2 \
    --hidden-mesh-silhouette-color 0.6,0.6,0.6 --hidden-mesh-silhouette-width 1.2 \
    -o "$out/godette-face.png" --svg "$out/godette-face.svg" --stats "$out/godette-face-stats.json"
# The whole character with its object boundaries (blue: where one node's mesh meets another's in the picture).
"$inkgraph" render "$root/models/characters/godette.vrm" --size "$size" \
    --lines outline,contour,intersection,object-boundary --intersection-color 0.85,0.1,0.1 \
    --object-boundary-color 0.1,0.3,0.8 -o "$out/godette-objects.png"
# Fandisk as a technical drawing: visible edges solid, hidden ones thin grey dashes, no shading.
"$inkgraph" render "$root/models/fandisk_c3d.obj" --size "$size" \
    --eye 12,22,-10 --target 2.4,15.2,-1.3 --fov 30 --shading none \
    --lines mesh-silhouette,crease --mesh-silhouette-width 2.5 --crease-width 2 \
    --hidden-lines mesh-silhouette,crease --hidden-dash 8,5 \
    --hidden-crease-color 0.45,0.45,0.45 --hidden-mesh-silhouette-color 0.45,0.45,0.45 \
    --hidden-crease-width 1.2 --hidden-mesh-silhouette-width 1.2 \
    -o "$out/fandisk-hidden.png" --svg "$out/fandisk-hidden.svg" --stats "$out/fandisk-hidden-stats.json"
