#!/usr/bin/env bash
# Regenerates the pictures of the README and of examples/*/README.md: runs every example that has pictures at the
# gallery's size and copies its .png and .svg files into docs/gallery/<example>/. Run after scripts/build.sh (Release):
#     bash scripts/gallery.sh            # or: INKGRAPH=/path/to/inkgraph bash scripts/gallery.sh
# Deterministic on one machine: llvmpipe renders the same bytes each run (GPU drivers may differ in the last bit).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
export INKGRAPH=${INKGRAPH:-$root/build/inkgraph}
[ -x "$INKGRAPH" ] || { echo "gallery.sh: no executable '$INKGRAPH' (run scripts/build.sh first)" >&2; exit 1; }
gallery="$root/docs/gallery"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# example folder, then the size its pictures have in the gallery (small enough to keep the repository light)
examples=(
    "bunny-cel-lines 640x640"
    "teapot-metallic 640x480"
    "fandisk-creases 480x480"
    "intersections-hidden-lines 480x480"
    "armadillo-suggestive 480x480"
    "still-life 800x500"
    "line-types 256x256"
    "characters 384x384"
    "clean-strokes 512x512"
    "line-art-dataset 256x256"
)
for entry in "${examples[@]}"; do
    read -r name size <<<"$entry"
    echo "gallery.sh: $name at $size"
    OUT="$work/$name" SIZE="$size" "$root/examples/$name/run.sh" >/dev/null
    rm -rf "$gallery/$name.tmp"
    mkdir -p "$gallery/$name.tmp"
    find "$work/$name" -maxdepth 1 \( -name '*.png' -o -name '*.svg' \) -exec cp {} "$gallery/$name.tmp/" \;
    # Replaced whole, so pictures an example no longer makes do not linger.
    rm -rf "$gallery/$name"
    mv "$gallery/$name.tmp" "$gallery/$name"
done
echo "gallery.sh: wrote $(find "$gallery" -type f | wc -l) files into $gallery"
