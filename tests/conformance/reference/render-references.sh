#!/bin/bash
# Regenerates the MToon conformance references: every case of ../generate-cases.py rendered by three-vrm in
# headless Chromium (SwiftShader), into pictures/ (<case>-<view>.png, VERSIONS, cases.sha256).
#
#   tests/conformance/reference/render-references.sh SCRATCH_DIR
#
# SCRATCH_DIR (outside the repository; made if missing) gets node_modules from package-lock.json (npm ci) and the
# generated cases. Needs node and npm (npm's registry), python3 and Chromium (Debian: apt-get install chromium;
# CHROMIUM=path overrides). None of this is a build or test dependency: the PNGs are committed, and ctest only reads
# them.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
if [ $# -ne 1 ]; then
    echo "usage: $0 SCRATCH_DIR" >&2
    exit 2
fi
scratch="$1"
mkdir -p "$scratch"
scratch="$(cd "$scratch" && pwd)"
case "$scratch/" in
    "$(cd "$here/../../.." && pwd)"/*) echo "$0: SCRATCH_DIR must lie outside the repository" >&2; exit 2 ;;
esac

chromium="${CHROMIUM:-}"
if [ -z "$chromium" ]; then
    # Debian's /usr/bin/chromium is a wrapper script; Playwright wants the browser itself.
    for candidate in /usr/lib/chromium/chromium /usr/bin/chromium /usr/bin/chromium-browser; do
        if [ -x "$candidate" ]; then chromium="$candidate"; break; fi
    done
fi
if [ -z "$chromium" ]; then
    echo "$0: no Chromium found (apt-get install chromium, or set CHROMIUM)" >&2
    exit 1
fi

# The driver runs from the scratch folder, where node finds playwright-core.
cp "$here/package.json" "$here/package-lock.json" "$here/render-references.mjs" "$scratch/"
(cd "$scratch" && npm ci --no-audit --no-fund --loglevel=error)

rm -rf "$scratch/cases"
python3 "$here/../generate-cases.py" "$scratch/cases"

mkdir -p "$here/pictures"
rm -f "$here/pictures"/*.png
node "$scratch/render-references.mjs" "$here" "$scratch/node_modules" "$scratch/cases" "$here/pictures" "$chromium"
