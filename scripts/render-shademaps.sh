#!/usr/bin/env bash
# Regenerates shademaps/*.png (the maps) and shademaps/renders/*.png (a render made with each) from a Release build
# in build/. Usage: scripts/render-shademaps.sh [MODEL]   (default: models/spot_c3d.obj)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
model=${1:-"$root/models/spot_c3d.obj"}
"$root/build/shademaps/inkgraph_make_shademaps" "$root/shademaps"
mkdir -p "$root/shademaps/renders"
view=(--size 320x320 --eye 3.1,1.2,2.6 --target 0,-0.08,0 --fov 30 --light 0.3,0.9,0.6 --lines outline -q)
for map in "$root"/shademaps/*.png; do
    name=$(basename "$map" .png)
    if [ "$(head -c 24 "$map" | tail -c 4 | od -An -tu1 | tr -s ' ')" = " 0 0 0 1" ]; then
        shading=(--shading cel)   # one-row maps (PNG height 1) are cel maps
    else
        shading=(--shading comic --shininess 24)
    fi
    "$root/build/inkgraph" render "$model" -o "$root/shademaps/renders/$name.png" "${shading[@]}" \
        --shademap "$map" "${view[@]}"
    echo "shademaps/renders/$name.png"
done
