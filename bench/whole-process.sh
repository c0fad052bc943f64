#!/usr/bin/env bash
# Whole-process wall time and peak memory of the stills issue 20 sets goals for, RUNS rounds (default 7). Each round
# runs every row once, in order, so drift on a shared machine hits all rows alike; medians are of the rounds.
#   bench/whole-process.sh [RUNS] > table.md        (after scripts/build.sh; docs/performance.md quotes the table)
# Environment: INKGRAPH (the binary, default build/inkgraph), FREESTYLE=0 skips Blender (it takes ~10 s a run),
# ROWS="probe tetra bunny freestyle batch large" picks rows (also: singles, the batch's models one process each;
# unlined, the bunny's still with its cel shading and no lines, the floor under the comic still; comic36, issue 38's
# batch: the nine bundled models four times in one process, the comic look (--shading cel --lines
# silhouette,contour,suggestive) at 1024², PNGs written, with the default --jobs; comic36-serial, the same with
# --jobs 0, the baseline beside it; comic36-dN, the same in one process with --draw-threads N (N drawing threads,
# a GL context each); comic36-pN, N such processes at once, each its own 36 stills: the machine's stills per second);
# GPU_BUSY=1 samples nvidia-smi's utilization.gpu every 100 ms during the comic36 rows (when nvidia-smi is on PATH)
# and adds the mean busy share to their note;
# BEFORE=/path/to/an/older/inkgraph adds each inkgraph row again as ROW@before, run by that binary in the same rounds
# (from its own checkout's folder, so it finds its shaders): tetra, bunny, batch, large and comic36.
# EGL_PROBE and MAKE_MESH replace build/bench/inkgraph_egl_probe and build/bench/inkgraph_make_mesh, GNU_TIME
# /usr/bin/time: a machine without our build runs the device kit's (bench/device-kit.sh, bench/device-rows.sh).
# Generated inputs (the large row's mesh) go to build/bench-data/, made when missing.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
runs=${1:-7}
build="$root/build"
inkgraph=${INKGRAPH:-$build/inkgraph}
probe=${EGL_PROBE:-$build/bench/inkgraph_egl_probe}
make_mesh=${MAKE_MESH:-$build/bench/inkgraph_make_mesh}
gnu_time=${GNU_TIME:-/usr/bin/time}
work="$build/bench-data"
mkdir -p "$work/out" "$work/batch"
rows=${ROWS:-"probe tetra bunny freestyle batch large"}
for row in $rows; do # a misspelt row is refused before any round runs, not run as an empty command
    case $row in
    probe | tetra | bunny | unlined | freestyle | batch | singles | large | comic36 | comic36-serial) ;;
    comic36-d[1-9]* | comic36-p[1-9]*) [[ ${row:9} =~ ^[0-9]+$ ]] || row_unknown=$row ;;
    *) row_unknown=$row ;;
    esac
    if [ -n "${row_unknown:-}" ]; then
        echo "whole-process.sh: unknown row '$row_unknown' in ROWS (probe, tetra, bunny, unlined, freestyle, batch," \
            "singles, large, comic36, comic36-serial, comic36-dN, comic36-pN)" >&2
        exit 2
    fi
done
if [ -n "${BEFORE:-}" ]; then
    for row in tetra bunny batch large comic36; do [[ " $rows " == *" $row "* ]] && rows+=" $row@before"; done
fi
cd "$root"

for _ in 1 2 3 4; do grep -v '^#' examples/batch/models.txt; done >"$work/comic36.txt"
for row in $rows; do [[ $row == comic36* ]] && mkdir -p "$work/${row/@before/-before}"; done
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n' >"$work/tetrahedron.obj"
large="$work/armadillo-1.3m.obj"
if [[ " $rows " == *" large"* ]] && [ ! -f "$large" ]; then # written whole or not at all
    "$make_mesh" subdivide 5 models/armadillo_cgal_52k.obj "$work/armadillo-1.3m.partial.obj" >/dev/null
    mv "$work/armadillo-1.3m.partial.obj" "$large"
fi
if [[ " $rows " == *" freestyle "* ]] && { [ "${FREESTYLE:-1}" = 0 ] || ! command -v blender >/dev/null; }; then
    rows=${rows/freestyle/}
    echo "(Freestyle row skipped: FREESTYLE=0 or no blender on PATH)" >&2
fi

comic=(--shading cel --lines silhouette,contour,suggestive)
command_of() { # row -> the command, one word per line
    if [[ $1 == *@before ]]; then
        inkgraph=$BEFORE command_of "${1%@before}" | sed -e "s|/out/\(.*\)\.png$|/out/\1-before.png|" \
            -e "s|/comic36/|/comic36-before/|"
        return
    fi
    case $1 in
    probe) printf '%s\n' "$probe" ;;
    tetra) printf '%s\n' "$inkgraph" render "$work/tetrahedron.obj" -o "$work/out/tetra.png" --size 64x64 -q ;;
    bunny) printf '%s\n' "$inkgraph" render models/bunny_c3d_70k.obj -o "$work/out/bunny.png" "${comic[@]}" -q ;;
    unlined) printf '%s\n' "$inkgraph" render models/bunny_c3d_70k.obj -o "$work/out/bunny-unlined.png" --shading cel \
        --lines none -q ;;
    freestyle) printf '%s\n' blender -b --factory-startup -noaudio -P bench/freestyle_still.py -- \
        models/bunny_c3d_70k.obj "$work/out/bunny-freestyle.png" ;;
    batch) printf '%s\n' "$inkgraph" render --list examples/batch/models.txt -o "$work/batch/{name}.png" -q ;;
    singles) # one line: the command is read back one word per line
        printf '%s\n' bash -c 'grep -v "^#" examples/batch/models.txt | while read -r m; do "$0" render "$m" -o "$1/$(basename "$m" .obj).png" -q || exit 1; done' "$inkgraph" "$work/batch" ;;
    comic36 | comic36-serial | comic36-d*)
        jobs=()
        [ "$1" = comic36-serial ] && jobs=(--jobs 0)
        [[ $1 == comic36-d* ]] && jobs=(--draw-threads "${1#comic36-d}")
        printf '%s\n' "$inkgraph" render --list "$work/comic36.txt" -o "$work/$1/{index}.png" "${comic[@]}" \
            "${jobs[@]}" -q ;;
    comic36-p*) # one line: the command is read back one word per line
        printf '%s\n' bash -c 'pids=(); for p in $(seq "$1"); do mkdir -p "$3/p$p"; "$0" render --list "$2" -o "$3/p$p/{index}.png" --shading cel --lines silhouette,contour,suggestive -q & pids+=($!); done; status=0; for pid in "${pids[@]}"; do wait "$pid" || { status=$?; echo "a process of the row exited with status $status" >&2; }; done; exit $status' \
            "$inkgraph" "${1#comic36-p}" "$work/comic36.txt" "$work/$1" ;;
    large) printf '%s\n' "$inkgraph" render "$large" -o "$work/out/large.png" --shading comic \
        --lines silhouette,contour,suggestive,crease -q ;;
    esac
}

sample_gpu=0
[ "${GPU_BUSY:-0}" = 1 ] && command -v nvidia-smi >/dev/null && sample_gpu=1
declare -A times=() memory=() busy=() failures=()
for _ in $(seq "$runs"); do
    for row in $rows; do
        [ -z "${failures[$row]:-}" ] || continue
        mapfile -t command < <(command_of "$row")
        folder=$root
        [[ $row == *@before ]] && folder=$(cd "$(dirname "$BEFORE")/.." && pwd)
        sampler=""
        if [ "$sample_gpu" = 1 ] && [[ $row == comic36* ]]; then
            nvidia-smi --query-gpu=utilization.gpu --format=csv,noheader,nounits -lms 100 >"$work/busy" 2>/dev/null &
            sampler=$!
        fi
        start=$(date +%s%N)
        (cd "$folder" && "$gnu_time" -f %M -o "$work/rss" "${command[@]}" >/dev/null 2>"$work/stderr") &&
            status=0 || status=$?
        end=$(date +%s%N)
        if [ "$status" != 0 ]; then # the row is dropped from the later rounds; the others still run
            [ -z "$sampler" ] || { kill "$sampler" 2>/dev/null || true; wait "$sampler" 2>/dev/null || true; }
            echo "$row failed (exit $status):" >&2
            cat "$work/stderr" "$work/rss" >&2 # GNU time says how the command ended (a signal, a status)
            failures[$row]="exit $status: $(cat "$work/stderr" "$work/rss" | grep -v '^[[:space:]]*$' | head -1 || true)"
            continue
        fi
        if [ -n "$sampler" ]; then
            kill "$sampler" 2>/dev/null || true
            wait "$sampler" 2>/dev/null || true
            busy[$row]+="$(awk '$1 ~ /^[0-9]+$/ {s += $1; n++} END {if (n) printf "%.0f", s / n; else print 0}' \
                "$work/busy") "
        fi
        times[$row]+="$(( (end - start) / 1000000 )) "
        memory[$row]+="$(tail -1 "$work/rss") "
    done
done

median() { tr ' ' '\n' | grep . | sort -n | awk '{v[NR]=$1} END {print v[int((NR+1)/2)]}'; }
range() { tr ' ' '\n' | grep . | sort -n | awk 'NR==1{lo=$1} {hi=$1} END {print lo "–" hi}'; }
declare -A medians
echo "| row | median ms | range ms | peak RSS MiB (median) | note |"
echo "|---|---|---|---|---|"
for row in $rows; do # notes compare rows
    if [ -n "${times[$row]:-}" ]; then medians[$row]=$(echo "${times[$row]}" | median); fi
done
for row in $rows; do
    if [ -n "${failures[$row]:-}" ]; then
        echo "| $row | failed | | | ${failures[$row]//|/\\|} |"
        continue
    fi
    rss=$(( $(echo "${memory[$row]}" | median) / 1024 ))
    note=""
    case $row in
    tetra | tetra@before) note="$(awk -v a="${medians[$row]}" -v b="${medians[probe]:-0}" \
        'BEGIN { if (b > 0) printf "%.2fx the probe", a / b }')" ;;
    comic36 | comic36-serial | comic36@before) note="$(awk -v t="${medians[$row]}" -v row="$row" \
        -v s="${medians[comic36-serial]:-0}" -v b="${medians[comic36@before]:-0}" 'BEGIN {
            printf "36 stills: %.1f stills/s", 36000 / t
            if (row == "comic36" && s > 0) printf "; %.2fx the serial row", s / t
            if (row != "comic36@before" && b > 0) printf "; %.2fx the before row", b / t }')" ;;
    comic36-d*) note="$(awk -v t="${medians[$row]}" -v d="${row#comic36-d}" -v c="${medians[comic36]:-0}" 'BEGIN {
            printf "36 stills, %d drawing threads: %.1f stills/s", d, 36000 / t
            if (c > 0) printf "; %.2fx the comic36 row", c / t }')" ;;
    comic36-p*) note="$(awk -v t="${medians[$row]}" -v p="${row#comic36-p}" \
        'BEGIN { printf "%d processes x 36 stills: %.1f stills/s", p, 36000 * p / t }')" ;;
    batch | batch@before | singles) note="$(awk -v t="${medians[$row]}" 'BEGIN { printf "9 stills: %.1f stills/s", 9000 / t }')" ;;
    freestyle) note="$(awk -v a="${medians[freestyle]}" -v b="${medians[bunny]:-0}" \
        'BEGIN { if (b > 0) printf "%.1fx the inkgraph bunny; ", a / b; printf "40x: a still of <= %.0f ms", a / 40 }')" ;;
    unlined) note="$(awk -v a="${medians[unlined]}" -v b="${medians[bunny]:-0}" \
        'BEGIN { if (b > 0) printf "%.0f%% of the bunny with its three line types", 100 * a / b }')" ;;
    esac
    [ -n "${busy[$row]:-}" ] && note+="; GPU busy $(echo "${busy[$row]}" | median)% (median of rounds)"
    echo "| $row | ${medians[$row]} | $(echo "${times[$row]}" | range) | $rss | $note |"
done
echo
echo "$runs rounds; $(nproc) cores; $(date -u +%Y-%m-%d); LP_NUM_THREADS=${LP_NUM_THREADS:-unset}"
[ "${#failures[@]}" = 0 ] || exit 1
