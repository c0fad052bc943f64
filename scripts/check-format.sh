#!/usr/bin/env bash
# Fails when a tracked C++ source (*.h, *.cpp; not shaders/, never a build folder) is not formatted as the repo's
# .clang-format says. Runs, from the repo root:
#   git ls-files -z -- '*.h' '*.cpp' ':!:shaders/' | xargs -0 clang-format --dry-run --Werror --style=file
# and prints the offending files (clang-format -i FILE fixes one; clang-format --dry-run FILE shows what it would
# change). clang-format is Debian 12's (scripts/install-deps.sh installs it); without it the check fails, it is not
# skipped. Usage: scripts/check-format.sh [REPO_ROOT]   (default: the repo this script is in)
set -euo pipefail
root="$(cd "${1:-$(dirname "$0")/..}" && pwd)"
cd "$root"
if ! command -v clang-format >/dev/null 2>&1; then
    echo "check-format: clang-format is not installed (scripts/install-deps.sh installs Debian's clang-format)" >&2
    exit 1
fi
if ! git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
    echo "check-format: $root is not a git checkout; the check formats the tracked files only" >&2
    exit 1
fi
mapfile -d '' files < <(git ls-files -z -- '*.h' '*.cpp' ':!:shaders/')
if [ ${#files[@]} -eq 0 ]; then
    echo "check-format: no C++ sources found in $root" >&2
    exit 1
fi
report=$(mktemp)
trap 'rm -f "$report"' EXIT
status=0
printf '%s\0' "${files[@]}" | xargs -0 clang-format --dry-run --Werror --style=file 2>"$report" || status=$?
# Each finding starts "FILE:LINE:COL: error: code should be clang-formatted".
mapfile -t offending < <(sed -n 's/^\(.*\):[0-9][0-9]*:[0-9][0-9]*: error: .*clang-format.*/\1/p' "$report" | sort -u)
if [ "$status" -ne 0 ] || [ ${#offending[@]} -ne 0 ]; then
    if [ ${#offending[@]} -eq 0 ]; then
        cat "$report" >&2 # clang-format failed for another reason (bad .clang-format, unreadable file)
    else
        printf '%s\n' "${offending[@]}"
    fi
    echo "check-format: ${#offending[@]} of ${#files[@]} files not formatted ($(clang-format --version))" >&2
    exit 1
fi
echo "check-format: all ${#files[@]} files formatted ($(clang-format --version))"
