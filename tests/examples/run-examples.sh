#!/usr/bin/env bash
# Runs every example script, small, with the given inkgraph executable, and checks that each writes the files its
# README names (pictures non-empty PNGs, SVGs with paths), then runs the Slurm array script once per share with the
# Slurm variables set by hand and checks the shares are disjoint and cover the list. Usage: run-examples.sh INKGRAPH
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
export INKGRAPH=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*" >&2; failures=$((failures + 1)); }

expect_png() { # a PNG file: its 8-byte signature
    [ -s "$1" ] || { fail "missing or empty: $1"; return; }
    [ "$(head -c 8 "$1" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ] || fail "not a PNG: $1"
}
expect_svg() { # an SVG with at least one path, closed properly
    [ -s "$1" ] || { fail "missing or empty: $1"; return; }
    grep -q '<path d="M' "$1" || fail "no path in $1"
    tail -c 16 "$1" | grep -q '</svg>' || fail "SVG not closed: $1"
}
run_example() { # name, then the files it must write
    local name=$1; shift
    if ! OUT="$work/$name" SIZE=96x96 "$root/examples/$name/run.sh" > "$work/$name.log" 2>&1; then
        fail "examples/$name/run.sh exited non-zero:"; cat "$work/$name.log" >&2; return
    fi
    for file in "$@"; do
        case $file in
            *.png) expect_png "$work/$name/$file" ;;
            *.svg) expect_svg "$work/$name/$file" ;;
            *) [ -s "$work/$name/$file" ] || fail "missing or empty: $work/$name/$file" ;;
        esac
    done
}

run_example default-bunny bunny.png stats.json dump/normal.exr dump/manifest.json
run_example bunny-cel-lines bunny.png bunny-sheet.png bunny-lines.svg bunny-stats.json
run_example teapot-metallic teapot.png teapot-stats.json
run_example fandisk-creases fandisk.png fandisk-lines.svg teapot-borders.png
run_example intersections-hidden-lines godette-face.png godette-face.svg godette-objects.png fandisk-hidden.png \
    fandisk-hidden.svg
run_example armadillo-suggestive armadillo-object.png armadillo-image.png
run_example line-types outline.png silhouette.png contour.png suggestive.png suggestive-object.png depth-edge.png \
    normal-edge.png mesh-silhouette.png crease.png border.png together.png
run_example still-life still-life.png
run_example clean-strokes bunny.png armadillo.png lucy.png suzanne.png fox.png godette.png bunny-weight.png \
    bunny.svg
grep -q 'stroke="none" d="M' "$work/clean-strokes/bunny-weight.svg" 2>/dev/null ||
    fail "clean-strokes: bunny-weight.svg has no weighted (filled outline) path"
run_example characters fox-default.png godette-mtoon.png godette-face.png godette-orbit.png fox-walk.png \
    expressions-binary-overrides-default.png godette-happy.png godette-a-pose.png
VIEWS=2 run_example line-art-dataset characters/index.jsonl characters/README.md characters/godette/0.png \
    characters/fox/1-strokes.json characters/duck/1.svg characters/godette/1-labels/triangleid.exr \
    godette-expressions/index.jsonl godette-expressions/godette/1.png
run_example batch 1-bunny_c3d_70k.png 5-spot_c3d.png 9-suzanne_npm_4k.png 9-suzanne_npm_4k.json

# The Slurm script, as tasks 1..3 of --array=1-3.
models=$(grep -cv '^#' "$root/examples/batch/models.txt")
for task in 1 2 3; do
    if ! (cd "$root" && OUT="$work/slurm" SIZE=64x64 SLURM_ARRAY_TASK_ID=$task SLURM_ARRAY_TASK_MIN=1 \
          SLURM_ARRAY_TASK_COUNT=3 bash examples/batch/slurm-array.sbatch > "$work/slurm-$task.log" 2>&1); then
        fail "slurm-array.sbatch task $task exited non-zero:"; cat "$work/slurm-$task.log" >&2
    fi
    grep -q "rendered 3 of 3 models (shard $((task - 1))/3 of $models)" "$work/slurm-$task.log" ||
        fail "task $task did not render its share of 3: $(cat "$work/slurm-$task.log")"
done
pictures=$(find "$work/slurm" -name '*.png' | wc -l)
[ "$pictures" -eq "$models" ] || fail "the shares wrote $pictures pictures for $models models"

# The data set's Slurm script, as tasks 0..2 of --array=0-2: one data set, an index and card per task, whole for
# check-dataset; a task run again resumes and renders nothing.
for task in 0 1 2; do
    if ! (cd "$root" && OUT="$work/dataset-slurm" SIZE=64x64 VIEWS=2 SLURM_ARRAY_TASK_ID=$task SLURM_ARRAY_TASK_MIN=0 \
          SLURM_ARRAY_TASK_COUNT=3 bash examples/line-art-dataset/slurm-array.sbatch > "$work/dataset-$task.log" 2>&1); then
        fail "line-art-dataset/slurm-array.sbatch task $task exited non-zero:"; cat "$work/dataset-$task.log" >&2
    fi
done
"$INKGRAPH" check-dataset "$work/dataset-slurm" > "$work/dataset-check.log" 2>&1 ||
    fail "check-dataset of the Slurm data set: $(cat "$work/dataset-check.log")"
grep -q "6 stills, 0 failed" "$work/dataset-check.log" || fail "the Slurm data set: $(cat "$work/dataset-check.log")"
(cd "$root" && OUT="$work/dataset-slurm" SIZE=64x64 VIEWS=2 SLURM_ARRAY_TASK_ID=1 SLURM_ARRAY_TASK_MIN=0 \
    SLURM_ARRAY_TASK_COUNT=3 bash examples/line-art-dataset/slurm-array.sbatch > "$work/dataset-rerun.log" 2>&1) ||
    fail "line-art-dataset/slurm-array.sbatch rerun exited non-zero: $(cat "$work/dataset-rerun.log")"
grep -q "resumed: 2 stills complete, 0 rendered" "$work/dataset-rerun.log" ||
    fail "the rerun of task 1 did not resume: $(cat "$work/dataset-rerun.log")"

[ "$failures" -eq 0 ] || { echo "$failures failures" >&2; exit 1; }
echo "every example ran and wrote its files"
