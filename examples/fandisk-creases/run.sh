#!/usr/bin/env bash
# Hoppe's fandisk, a CAD part: its sharp creases (blue) and mesh silhouette from the mesh's own edges, in object
# space. The fandisk is closed, so its border pass finds nothing (--stats: edges_drawn 0); the teapot's open
# patches show the border type at work.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
inkgraph=${INKGRAPH:-$root/build/inkgraph} # INKGRAPH, OUT and SIZE override the defaults (scripts/gallery.sh, tests)
out=${OUT:-$root/out/examples/fandisk-creases}
mkdir -p "$out"
"$inkgraph" render "$root/models/fandisk_c3d.obj" --size "${SIZE:-1024x1024}" \
    --eye 12,22,-10 --target 2.4,15.2,-1.3 --fov 30 \
    --shading cel --lines mesh-silhouette,crease,border \
    --mesh-silhouette-width 3 --crease-color 0.1,0.25,0.7 --crease-angle 30 --border-color 0.8,0.1,0.1 \
    -o "$out/fandisk.png" --svg "$out/fandisk-lines.svg" --stats "$out/fandisk-stats.json"
"$inkgraph" render "$root/models/teapot_c3d.obj" --size "${SIZE:-1024x1024}" --eye 5,8.5,8 --target 0.2,1.2,0 \
    --shading cel --lines border,mesh-silhouette --border-color 0.8,0.1,0.1 --border-width 2.5 \
    -o "$out/teapot-borders.png" --stats "$out/teapot-borders-stats.json"
