#!/usr/bin/env bash
# A line-art data set of the bundled characters in two commands of inkgraph: every character of characters.txt from
# 16 sampled views (seeded, so the same on any machine and in any shard split), each still with its picture, every
# line type's mask (visible and hidden), the labels (depth, normals, object, mesh, material and triangle ids,
# barycentrics: --dump), the strokes with their 3-D points (--strokes), the SVG, the camera, the index and the card;
# then Godette alone with sampled expressions and poses. Each set is checked by `inkgraph check-dataset`, and the time
# and the disk per still are printed. README.md in this folder says more; slurm-array.sbatch runs the first set as
# an array job. INKGRAPH, OUT, SIZE, VIEWS and RESUME (any value: add --resume) override the defaults.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
inkgraph=${INKGRAPH:-$root/build/inkgraph}
out=${OUT:-$root/out/examples/line-art-dataset}
size=${SIZE:-512x512}
views=${VIEWS:-16}
resume=(${RESUME:+--resume})
cd "$root" # the list's paths, and the model keys the views are drawn from, are relative to the repository root

# The look and labels of both sets: comic shading; outline, contours, suggestive contours, creases and material
# boundaries, with the hidden creases and silhouettes as solid masks of their own (--hidden-dash none), light grey in
# the picture; the label
# fields computed (--request) and dumped with every line mask.
look=(--size "$size" --shading comic --lines outline,contour,suggestive,crease,material-boundary
    --hidden-lines crease,mesh-silhouette --hidden-dash none
    --hidden-crease-color 0.75,0.75,0.75 --hidden-mesh-silhouette-color 0.75,0.75,0.75
    --request gbuffer.depth,gbuffer.normal,gbuffer.objectId,gbuffer.materialId,gbuffer.meshId,gbuffer.triangleId,gbuffer.barycentric)

render_set() { # FOLDER, then the arguments that choose the models and views
    local set=$1
    shift
    local start end stills bytes
    start=$(date +%s.%N)
    "$inkgraph" render "$@" "${look[@]}" "${resume[@]}" -q --dataset "$set" -o "$set/{name}/{view}.png" \
        --dump "$set/{name}/{view}-labels" --strokes "$set/{name}/{view}-strokes.json" --svg "$set/{name}/{view}.svg"
    end=$(date +%s.%N)
    "$inkgraph" check-dataset "$set"
    stills=$(wc -l < "$set/index.jsonl")
    bytes=$(du -sb "$set" | cut -f1)
    awk -v s="$stills" -v t0="$start" -v t1="$end" -v b="$bytes" -v d="$set" 'BEGIN {
        printf "line-art-dataset: %s: %d stills in %.1f s: %.0f ms and %.2f MB per still\n", d, s, t1 - t0,
            1000 * (t1 - t0) / s, b / s / 1e6 }'
}

# The characters from 16 views each: azimuth uniform, elevation normal about 10 degrees (SD 10, clamped to -20..45),
# the auto-framing distance jittered by up to 10%.
render_set "$out/characters" --list examples/line-art-dataset/characters.txt --views "$views" --seed 37 \
    --view-elevation 10,10,-20,45 --view-distance-jitter 0.1
# Godette with a sampled expression and pose per view, and the light jittered within 30 degrees of the upper left.
render_set "$out/godette-expressions" models/characters/godette.vrm --views "$views" --seed 38 \
    --view-elevation 5,8,-15,30 --expressions 'none;happy=1;angry=1;sad=1;relaxed=1;blink=1' --poses rest,a-pose \
    --light -0.5,0.8,0.6 --light-jitter 30

# An overview for the README: the first two views of each character, and of Godette's expressions, side by side.
pictures=()
for folder in "$out/characters/godette" "$out/characters/fox" "$out/characters/duck" \
    "$out/godette-expressions/godette"; do
    mapfile -t first < <(find "$folder" -maxdepth 1 -name '*.png' | sort | head -n 2)
    pictures+=("${first[@]}")
done
oiiotool "${pictures[@]}" --mosaic 4x2 -o "$out/overview.png"
