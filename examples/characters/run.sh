#!/usr/bin/env bash
# Real textured characters and props (models/characters/: glTF, GLB, VRM 0.x and 1.0): each file in the default look
# and with --shading mtoon (the file's MToon materials and outline widths), then a few showcase renders: a close-up
# framed by node, an orbited view with silhouette and contour lines, the fox posed by its Walk animation.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
inkgraph=${INKGRAPH:-$root/build/inkgraph} # INKGRAPH, OUT and SIZE override the defaults (scripts/gallery.sh, tests)
out=${OUT:-$root/out/examples/characters}
size=${SIZE:-512x512}
models="$root/models/characters"
mkdir -p "$out"

for file in fox.glb box-textured.glb duck.glb mtoon-uv-animation-test.vrm godette.vrm \
    expressions-binary-overrides.vrm; do
    name=${file%.*}
    "$inkgraph" render "$models/$file" --size "$size" -o "$out/$name-default.png"
    case $file in # the two flat VRM 1.0 samples are white panels: on dark paper, as their viewer shows them
        mtoon-uv-animation-test.vrm | expressions-binary-overrides.vrm) paper=(--background 0.03,0.03,0.03) ;;
        *) paper=() ;;
    esac
    "$inkgraph" render "$models/$file" --size "$size" --shading mtoon "${paper[@]}" -o "$out/$name-mtoon.png"
done

# Godette in the comic look: her MToon materials are lit by every look (their KHR_materials_unlit is the exporter's
# fallback), so Winnemöller & Bangay's 2-D shade map shades her too.
"$inkgraph" render "$models/godette.vrm" --size "$size" --shading comic -o "$out/godette-comic.png"
# Godette's face: --frame fits the camera to the meshes under the node 'Face'.
"$inkgraph" render "$models/godette.vrm" --size "$size" --frame Face --shading mtoon -o "$out/godette-face.png"
# Turned 35 degrees to her left, 10 above the horizontal, with the inflated-hull silhouette and the contours.
"$inkgraph" render "$models/godette.vrm" --size "$size" --orbit 35,10 --shading mtoon \
    --lines silhouette,contour -o "$out/godette-orbit.png"
# The fox half a second into its Walk animation, seen from its right side.
"$inkgraph" render "$models/fox.glb" --size "$size" --animation Walk --time 0.5 --orbit 90,10 \
    --lines contour -o "$out/fox-walk.png"
# Godette posed and expressive, her head framed by its humanoid bone (--frame head: the vertices the head bone and
# its children weight), in the default look: three VRM expressions, then the A-pose seen whole.
for expression in happy angry blink; do
    "$inkgraph" render "$models/godette.vrm" --size "$size" --frame head --expression "$expression=1" \
        -o "$out/godette-$expression.png"
done
"$inkgraph" render "$models/godette.vrm" --size "$size" --pose a-pose -o "$out/godette-a-pose.png"
