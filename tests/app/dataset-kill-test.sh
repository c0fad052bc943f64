#!/usr/bin/env bash
# --dataset and --resume through the executable (app/Dataset.h, docs/datasets.md): a kill -9 at any moment, followed
# by --resume until the run exits 0, gives exactly the files of one uninterrupted run, and check-dataset passes.
#   A: one uninterrupted run.
#   B: killed by the test hooks at chosen places: inside a commit (INKGRAPH_TEST_COMMIT_KILL), between a commit and its
#      journal line (INKGRAPH_TEST_JOURNAL_KILL), in the middle of a journal line (INKGRAPH_TEST_JOURNAL_TEAR).
#   C: killed with SIGKILL after random short sleeps (the outcome must not depend on where they land, nor on how many
#      land: the count is reported, never asserted).
# A, B and C are compared file by file, every byte, except each --dump's manifest.json (timings; the index's checksums
# of those are masked); the dump's EXR files carry a fixed time stamp, so they are compared as they are.
# F: a run refused at once while another holds the folder's lock; two runs at once: the set is A's.
# Then: a truncated file, or a dump's deleted file, is rendered again, a changed flag renders every still again, --resume needs --dataset, and a
# data set is not written over without --resume.
# Usage: dataset-kill-test.sh INKGRAPH SOURCE_ROOT
set -euo pipefail
inkgraph=$1
root=$2
work=$(mktemp -d "${TMPDIR:-/tmp}/inkgraph-dataset-kill.XXXXXX")
trap 'rm -rf "$work"' EXIT
export LP_NUM_THREADS=1

# Six stills: three models, two sampled views each (a run long enough for random kills to land inside it).
models=("$root/models/spot_c3d.obj" "$root/models/teapot_c3d.obj" "$root/models/suzanne_npm_4k.obj")
# Every output but --stats, whose files hold timings (docs/datasets.md); --dump with its EXR labels, whose
# manifest.json holds timings too (its other files are byte-deterministic).
flags=(--size 64x64 --views 2 --seed 5 --dataset . -o '{name}-{view}.png' --svg 'svg/{name}-{view}.svg'
    --graphviz 'plan/{name}-{view}.dot' --dump 'dump/{name}-{view}' --request gbuffer.depth,gbuffer.normal)

fail() {
    echo "FAIL: $*" >&2
    exit 1
}

# render FOLDER [--resume] [more flags]: a run inside FOLDER (so that the card's command is the same in each folder).
# Its exit code is returned, its stderr kept in FOLDER.log.
render() {
    local folder=$1
    shift
    mkdir -p "$folder/svg" "$folder/plan"
    (cd "$folder" && exec "$inkgraph" render "${models[@]}" "${flags[@]}" "$@" 2> "$work/$(basename "$folder").log")
}

# resume_until_done FOLDER: --resume until the run exits 0 (at most 5 times: each run without a kill finishes).
resume_until_done() {
    local folder=$1
    for _ in 1 2 3 4 5; do
        if render "$folder" --resume; then return 0; fi
    done
    fail "--resume into $folder did not finish: $(cat "$work/$(basename "$folder").log")"
}

# An index with each dump manifest's checksum masked (the manifest holds timings).
masked_index() { sed -E 's/("dump\/[^"]*\/manifest\.json":)\{[^}]*\}/\1{}/g' "$1"; }

# same_as_A FOLDER WHAT: every file of FOLDER as A's, byte for byte, but the dumps' manifest.json (present in both) and
# the index's checksums of them.
same_as_A() {
    local folder=$1 what=$2
    diff <(cd "$work/A" && find . | sort) <(cd "$folder" && find . | sort) || fail "$what: other files than A's"
    diff -r -x manifest.json -x index.jsonl "$work/A" "$folder" || fail "$what differs from A"
    diff <(masked_index "$work/A/index.jsonl") <(masked_index "$folder/index.jsonl") || fail "$what: the index differs"
}

killed_by_hook() { # FOLDER VARIABLE=N [--resume]: the run must die of SIGKILL
    local folder=$1 hook=$2
    shift 2
    local status=0
    (export "${hook?}" && render "$folder" "$@") || status=$?
    [ "$status" -eq 137 ] || fail "$hook: expected the run to be killed (137), got $status: $(cat "$work/$(basename "$folder").log")"
    grep -q "test hook: killed" "$work/$(basename "$folder").log" || fail "$hook: the hook did not say where it killed"
}

# A: uninterrupted.
render "$work/A" || fail "the uninterrupted run: $(cat "$work/A.log")"
[ "$(wc -l < "$work/A/index.jsonl")" -eq 6 ] || fail "A's index has $(wc -l < "$work/A/index.jsonl") lines, not 6"
[ ! -e "$work/A/.inkgraph" ] || fail "A's journal folder is left after the run"
"$inkgraph" check-dataset "$work/A" > "$work/check.txt" || fail "check-dataset A: $(cat "$work/check.txt")"
grep -q "6 stills, 0 failed, [0-9]* files verified; 0 errors, 0 warnings: whole" "$work/check.txt" ||
    fail "check-dataset A: $(cat "$work/check.txt")"

# E: two drawing threads (--draw-threads, each with its own GL context): the same files as A, every still journaled
# and indexed in the same order.
render "$work/E" --draw-threads 2 || fail "the run with two drawing threads: $(cat "$work/E.log")"
grep -q -- "--request gbuffer.depth,gbuffer.normal --draw-threads 2$" "$work/E/README.md" ||
    fail "E's card does not give its command: $(cat "$work/E/README.md")"
sed -i 's/ --draw-threads 2$//' "$work/E/README.md" # the card's command, the one line that may differ
same_as_A "$work/E" "E (two drawing threads)"
# B: at each hooked place in turn; each resume starts where the last one was killed.
killed_by_hook "$work/B" INKGRAPH_TEST_COMMIT_KILL=2                   # still 1: -o moved into place, not --svg
killed_by_hook "$work/B" INKGRAPH_TEST_COMMIT_KILL=4 --resume          # still 1 again, old files kept as backups
killed_by_hook "$work/B" INKGRAPH_TEST_JOURNAL_KILL=2 --resume         # still 1 journaled; still 2 committed, not
killed_by_hook "$work/B" INKGRAPH_TEST_JOURNAL_TEAR=1 --resume         # still 2 again: half its line written
[ -n "$(tail -c 1 "$work/B/.inkgraph/journal.jsonl")" ] || fail "the torn journal line ends in a newline"
killed_by_hook "$work/B" INKGRAPH_TEST_JOURNAL_KILL=2 --resume         # the torn line cut off; still 3 committed
resume_until_done "$work/B"
grep -q "inkgraph: resumed: 2 stills complete, 4 rendered" "$work/B.log" || fail "B's last resume: $(cat "$work/B.log")"
same_as_A "$work/B" "B (killed by the hooks, resumed)"
"$inkgraph" check-dataset "$work/B" > "$work/check.txt" || fail "check-dataset B: $(cat "$work/check.txt")"

# C: killed at random moments (from before the GL context to after the index), then resumed to the end. The first
# run is a new one; the others resume whatever the kills left (a folder without a journal is a new data set).
mkdir -p "$work/C/svg" "$work/C/plan"
killed=0
for attempt in 1 2 3 4 5 6; do
    [ "$attempt" -eq 1 ] && resume=() || resume=(--resume)
    (cd "$work/C" && exec "$inkgraph" render "${models[@]}" "${flags[@]}" "${resume[@]}" 2>> "$work/C-killed.log") &
    sleep "$(printf '0.%03d' $((RANDOM % 150)))" # a whole run takes some 0.2 s on llvmpipe
    kill -9 $! 2> /dev/null || true
    status=0
    wait $! 2> /dev/null || status=$?
    [ "$status" -ne 137 ] || killed=$((killed + 1))
done
resume_until_done "$work/C"
same_as_A "$work/C" "C (killed at random moments, resumed)"
"$inkgraph" check-dataset "$work/C" > "$work/check.txt" || fail "check-dataset C: $(cat "$work/check.txt")"

# F: two runs of the same split into one folder at once (a requeued array task beside the one it replaces). While one
# run holds the split's lock (here flock(1) holds it, as a run does from its checks to its index), another is refused
# at once, exit 5, and changes nothing; then two runs started together, twice: one is refused or finds every still
# complete, and the set is A's. Without the lock both ran, their journals, commits and indexes interleaved.
cp -r "$work/A" "$work/F"
mkdir -p "$work/F/.inkgraph"
status=0
flock "$work/F/.inkgraph/lock" bash -c "cd '$work/F' && exec \"\$0\" render \"\$@\" --resume 2> '$work/F.log'" \
    "$inkgraph" "${models[@]}" "${flags[@]}" || status=$?
[ "$status" -eq 5 ] && grep -q "is being written by another inkgraph run; wait until it has finished, then --resume" \
    "$work/F.log" || fail "F: a run while another holds the lock exited $status: $(cat "$work/F.log")"
rm "$work/F/.inkgraph/lock"
rmdir "$work/F/.inkgraph"
diff -r "$work/A" "$work/F" || fail "F: the refused run changed the data set"
for attempt in 1 2; do
    rm -rf "$work/F"
    mkdir -p "$work/F/svg" "$work/F/plan"
    pids=()
    for run in first second; do
        (cd "$work/F" && exec "$inkgraph" render "${models[@]}" "${flags[@]}" --resume 2> "$work/F-$run.log") &
        pids+=($!)
    done
    finished=0
    for index in 0 1; do
        run=$([ "$index" -eq 0 ] && echo first || echo second)
        status=0
        wait "${pids[$index]}" || status=$?
        if [ "$status" -eq 0 ]; then
            finished=$((finished + 1))
        elif [ "$status" -ne 5 ] || ! grep -q "is being written by another inkgraph run; wait until it has finished," \
            "$work/F-$run.log"; then
            fail "F: the $run run exited $status: $(cat "$work/F-$run.log")"
        fi
    done
    [ "$finished" -ge 1 ] || fail "F: neither run finished: $(cat "$work"/F-*.log)"
    same_as_A "$work/F" "F (two runs at once, attempt $attempt)"
    "$inkgraph" check-dataset "$work/F" > "$work/check.txt" || fail "check-dataset F: $(cat "$work/check.txt")"
done

# D: a copy of A with one file cut short: only that still is rendered again.
cp -r "$work/A" "$work/D"
truncate -s 100 "$work/D/teapot_c3d-1.png"
"$inkgraph" check-dataset "$work/D" > "$work/check.txt" && fail "check-dataset passes a truncated PNG"
grep -q "'teapot_c3d-1.png' is a PNG cut short" "$work/check.txt" || fail "check-dataset D: $(cat "$work/check.txt")"
render "$work/D" --resume || fail "resume D: $(cat "$work/D.log")"
grep -q "inkgraph: resumed: 5 stills complete, 1 rendered" "$work/D.log" || fail "resume D: $(cat "$work/D.log")"
same_as_A "$work/D" "D (a truncated file, resumed)"

# A file of a still's --dump deleted: the damaged dump is still a dump, replaced; only that still is rendered again
# (the whole run was refused, the folder taken for one that is not a dump).
rm "$work/D/dump/teapot_c3d-1/depth.exr"
"$inkgraph" check-dataset "$work/D" > "$work/check.txt" && fail "check-dataset passes a dump that lost a file"
render "$work/D" --resume || fail "resume D after a dump lost a file: $(cat "$work/D.log")"
grep -q "inkgraph: resumed: 5 stills complete, 1 rendered" "$work/D.log" || fail "lost dump file: $(cat "$work/D.log")"
same_as_A "$work/D" "D (a dump's file deleted, resumed)"

# A changed flag: every still rendered again, and the index records the new settings.
render "$work/D" --resume --svg-tolerance 1 || fail "resume D with a new flag: $(cat "$work/D.log")"
grep -q "inkgraph: resumed: 0 stills complete, 6 rendered" "$work/D.log" || fail "new flag: $(cat "$work/D.log")"
cmp -s "$work/A/index.jsonl" "$work/D/index.jsonl" && fail "the index did not change with --svg-tolerance 1"
# The same flags in another order: the same settings, nothing to render.
flags=(--svg-tolerance 1 -o '{name}-{view}.png' --seed 5 --graphviz 'plan/{name}-{view}.dot' --dataset .
    --request gbuffer.depth,gbuffer.normal --svg 'svg/{name}-{view}.svg' --views 2 --dump 'dump/{name}-{view}'
    --size 64x64)
render "$work/D" --resume || fail "resume D, flags reordered: $(cat "$work/D.log")"
grep -q "inkgraph: resumed: 6 stills complete, 0 rendered" "$work/D.log" || fail "reordered: $(cat "$work/D.log")"

# Another seed: other views, every still rendered again.
flags[5]=6 # after --seed
render "$work/D" --resume || fail "resume D with another seed: $(cat "$work/D.log")"
grep -q "inkgraph: resumed: 0 stills complete, 6 rendered" "$work/D.log" || fail "another seed: $(cat "$work/D.log")"
grep -q '"seed":6' "$work/D/index.jsonl" || fail "the index does not record --seed 6"

# Refusals: --resume without --dataset; a data set without --resume (nothing changed).
status=0
(cd "$work/A" && "$inkgraph" render "${models[0]}" -o x.png --resume) 2> "$work/refused.log" || status=$?
[ "$status" -eq 2 ] && grep -q "\-\-resume: needs --dataset" "$work/refused.log" || fail "--resume alone: $status"
cp -r "$work/A" "$work/A-before"
status=0
render "$work/A" || status=$?
[ "$status" -eq 2 ] && grep -q "already holds a data set ('index.jsonl'); add --resume" "$work/A.log" ||
    fail "a data set without --resume: $status $(cat "$work/A.log")"
diff -r "$work/A-before" "$work/A" || fail "a refused run changed the data set"
echo "dataset kill test: A, B (5 hooked kills), C ($killed of 6 runs killed at random), D (truncated file, lost" \
    "dump file, changed flag), F (a run refused while the lock is held, two at once twice) agree"
