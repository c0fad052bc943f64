#!/usr/bin/env bash
# The line-cleanliness table of issues 19 and 39 (bench/README.md): inkgraph_line_cleanliness over every bundled model
# and character (the nine models/*.obj and the seven glTF and VRM files of models/characters/) in two looks, one
# markdown table with the machine and date at the top. The inkgraph binary is an argument, so the same sweep measures
# a build before a change and one after; its environment (LD_LIBRARY_PATH, INKGRAPH_SHADER_DIR, LP_NUM_THREADS) is the
# caller's. Models run one after another, nine renders each (512, 1024 and 2048 px, and turns of +-1, +-5 and +-0.1
# degrees); about 7 minutes on the 2-core CPU machine for the two default looks (measured 2026-12-01).
#   bench/line-cleanliness.sh INKGRAPH_BINARY OUT.md [WORK_DIR]
# TOOL=path/to/inkgraph_line_cleanliness overrides the default build/bench/inkgraph_line_cleanliness.
# LOOKS="comic default comic-merge" picks the rows (default "comic default"); comic-merge is the comic look with
# --overlapping-lines merge (issue 19's binaries and later); pro-lines the types of issue 36 (intersection,
# object-boundary, hidden mesh silhouettes and intersections, solid so the F1 columns compare lines, not dash phases)
# over outline and contour; comic-object the comic look with the object-space suggestive contours (suggestive-object)
# in place of the image-space ones, to measure both (issue 39).
# MODELS="models/a.obj ..." measures those models instead of the sixteen; COLUMNS=TYPE,... names the types given an F1
# column (inkgraph_line_cleanliness --columns; pro-lines defaults to its own types).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
if [ $# -lt 2 ] || [ $# -gt 3 ]; then
    echo "usage: bench/line-cleanliness.sh INKGRAPH_BINARY OUT.md [WORK_DIR]" >&2
    exit 2
fi
binary=$1
out=$2
work=${3:-$(mktemp -d /tmp/line-cleanliness.XXXXXX)}
tool=${TOOL:-$root/build/bench/inkgraph_line_cleanliness}
[ -x "$binary" ] || { echo "line-cleanliness.sh: '$binary' is not an executable" >&2; exit 2; }
[ -x "$tool" ] || { echo "line-cleanliness.sh: '$tool' is not built (cmake --build build --target inkgraph_line_cleanliness)" >&2; exit 2; }

# Every model inkgraph renders in models/ (models/characters/three-vrm-test.vrma is an animation, not a model).
default_models=(
    models/bunny_c3d_70k.obj
    models/armadillo_cgal_52k.obj
    models/lucy_blendify_15k.obj
    models/suzanne_npm_4k.obj
    models/cow_c3d.obj
    models/fandisk_c3d.obj
    models/spot_c3d.obj
    models/teapot_c3d.obj
    models/torusknot_open3d.obj
    models/characters/fox.glb
    models/characters/box-textured.glb
    models/characters/duck.glb
    models/characters/godette.vrm
    models/characters/mtoon-uv-animation-test.vrm
    models/characters/expressions-binary-overrides.vrm
    models/characters/expressions-binary-overridden.vrm
)
if [ -n "${MODELS:-}" ]; then read -r -a models <<<"$MODELS"; else models=("${default_models[@]}"); fi
comic_flags=(--shading comic --lines outline,contour,suggestive,crease)
pro_flags=(--lines outline,contour,intersection,object-boundary --hidden-lines mesh-silhouette,intersection --hidden-dash none)
pro_columns=intersection,object-boundary,hidden-mesh-silhouette,hidden-intersection,contour
looks=(${LOOKS:-comic default})

table=$(mktemp)
trap 'rm -f "$table"' EXIT
cpu=$(grep -m1 'model name' /proc/cpuinfo | sed 's/.*: //' || echo "unknown CPU")
{
    echo "Measured $(date -u '+%Y-%m-%d %H:%M UTC') on $(hostname): $cpu, $(nproc) cores, llvmpipe (no GPU);"
    echo "binary \`$binary\`; bench/line-cleanliness.sh (bench/README.md defines each column)."
    echo
} > "$table"
header=--header
for model in "${models[@]}"; do
    name=$(basename "$model")
    name=${name%.*}
    for look in "${looks[@]}"; do
        case $look in
        comic) flags=("${comic_flags[@]}") ;;
        comic-merge) flags=("${comic_flags[@]}" --overlapping-lines merge) ;;
        comic-object) flags=(--shading comic --lines outline,contour,suggestive-object,crease) ;;
        default) flags=() ;;
        pro-lines) flags=("${pro_flags[@]}") ;;
        *) echo "line-cleanliness.sh: unknown look '$look' (comic, default, comic-merge, comic-object, pro-lines)" >&2; exit 2 ;;
        esac
        columns=${COLUMNS:-}
        [ -z "$columns" ] && [ "$look" = pro-lines ] && columns=$pro_columns
        [ -z "$columns" ] && [ "$look" = comic-object ] && columns=outline,contour,suggestive-object,crease
        column_flags=()
        [ -n "$columns" ] && column_flags=(--columns "$columns")
        echo "line-cleanliness.sh: $name, $look" >&2
        "$tool" --inkgraph "$binary" --model "$root/$model" --work "$work/$name-$look" --look "$look" $header "${column_flags[@]}" \
            -- "${flags[@]}" >> "$table"
        header=
    done
done
mkdir -p "$(dirname "$out")"
mv "$table" "$out"
trap - EXIT
echo "line-cleanliness.sh: wrote $out (renders and per-run JSON in $work)" >&2
