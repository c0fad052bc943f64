#!/usr/bin/env bash
# A metallic teapot: Winnemöller & Bangay 2002's specular comic shading with the bundled 2-D metallic shade map (stripes across the
# diffuse axis, a broad highlight), Lander's outline, and the teapot's open patch borders and creases.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
inkgraph=${INKGRAPH:-$root/build/inkgraph} # INKGRAPH, OUT and SIZE override the defaults (scripts/gallery.sh, tests)
out=${OUT:-$root/out/examples/teapot-metallic}
mkdir -p "$out"
"$inkgraph" render "$root/models/teapot_c3d.obj" --size "${SIZE:-1024x768}" \
    --shading comic --shademap "$root/shademaps/metallic.png" --shininess 24 \
    --lines outline,border,crease --outline-width 3 --border-width 1.5 \
    -o "$out/teapot.png" --stats "$out/teapot-stats.json"
