#!/usr/bin/env bash
# Every commit builds and passes: each commit of BASE..HEAD, oldest first, checked out in one throw-away git worktree,
# configured (Release, ccache), built (every target) and its fast tests run (ctest -L 'unit|lint': no GL, no install,
# no Python, no Slurm). One line per commit, "ok" or "FAILS: <what>"; exit 1 when any commit fails.
#
#   scripts/check-commits.sh BASE [HEAD]        e.g. scripts/check-commits.sh main    (before you stop)
#
# The worktree (and the build folder inside it, reused from commit to commit: `git checkout` touches only the files a
# commit changes, so each build after the first is incremental) is removed at the end; the logs stay in
# CHECK_COMMITS_DIR/logs. Both lie under the repo (ignored as /build*/), so ccache's base_dir (/work here) makes the
# compile lines relative and the first build hits what the repo's own build/ left in the cache.
# Environment: CHECK_COMMITS_DIR (default <repo>/build-check-commits), CHECK_COMMITS_JOBS (default: the cores),
# CHECK_COMMITS_LABELS (ctest -L regex, default 'unit|lint').
set -euo pipefail
root=$(git -C "$(dirname "$0")/.." rev-parse --show-toplevel)
if [ $# -lt 1 ] || [ $# -gt 2 ]; then
    echo "usage: scripts/check-commits.sh BASE [HEAD]" >&2
    exit 2
fi
base=$1
head=${2:-HEAD}
mapfile -t commits < <(git -C "$root" rev-list --reverse "$base..$head")
if [ ${#commits[@]} -eq 0 ]; then
    echo "check-commits: no commits in $base..$head"
    exit 0
fi
work=${CHECK_COMMITS_DIR:-$root/build-check-commits}
src=$work/src
build=$src/build # inside the worktree: the same relative paths as <repo>/build, for ccache
logs=$work/logs
jobs=${CHECK_COMMITS_JOBS:-$(nproc 2>/dev/null || echo 2)}
labels=${CHECK_COMMITS_LABELS:-unit|lint}

if [ -e "$src" ]; then
    echo "check-commits: $src exists (another run, or one that was killed): remove it with" >&2
    echo "  git -C '$root' worktree remove --force '$src'" >&2
    exit 2
fi
mkdir -p "$logs"
cleanup() {
    git -C "$root" worktree remove --force "$src" >/dev/null 2>&1 || rm -rf "$src"
    git -C "$root" worktree prune
}
trap cleanup EXIT
git -C "$root" worktree add --quiet --detach "$src" "${commits[0]}"

echo "check-commits: ${#commits[@]} commits of $base..$head; logs in $logs"
failed=0
for commit in "${commits[@]}"; do
    short=$(git -C "$root" rev-parse --short "$commit")
    subject=$(git -C "$root" log -1 --format=%s "$commit" | cut -c1-60)
    log=$logs/$short.log
    git -C "$src" checkout --quiet --detach "$commit"
    what=""
    if ! cmake -S "$src" -B "$build" -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER_LAUNCHER=ccache \
        -DCMAKE_C_COMPILER_LAUNCHER=ccache >"$log" 2>&1; then
        what="configure"
    elif ! cmake --build "$build" -j"$jobs" >>"$log" 2>&1; then
        what="build: $(grep -m1 -E 'error|Error' "$log" | cut -c1-160)"
    elif ! (cd "$build" && LP_NUM_THREADS=1 ctest -L "$labels" --output-on-failure --timeout 600 -j"$jobs") \
        >>"$log" 2>&1; then
        # ctest lists them after "The following tests FAILED:", as "  12 - name (Failed)".
        tests=$(sed -n '/The following tests FAILED:/,$s/^[[:space:]]*[0-9]* - \([^ ]*\).*/\1/p' "$log" | head -5 |
            paste -sd' ' -)
        what="tests (ctest -L '$labels'): ${tests:-see the log}"
    fi
    if [ -z "$what" ]; then
        echo "$short ok            $subject"
    else
        echo "$short FAILS: $what   ($subject; log: $log)"
        failed=1
    fi
done
exit "$failed"
