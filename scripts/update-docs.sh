#!/usr/bin/env bash
# Rewrites the docs' generated sections from the code: each region between "<!-- generated: NAME -->" and
# "<!-- end generated -->" in README.md and docs/robustness.md gets what `inkgraph help --docs NAME` prints
# (app/GeneratedDocs.h: the line types from their registry, the files --dump writes from what each pass declares, the
# warning codes from their table). tests/app/GeneratedDocsTest.cpp fails when a region differs, so run this after
# changing a line type, a pass's outputs or their meanings, or a warning code.
# Usage: scripts/update-docs.sh [PROGRAM]   (default: build/inkgraph, built first with scripts/build.sh or cmake)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
program="${1:-$root/build/inkgraph}"
[[ -x "$program" ]] || { echo "update-docs.sh: no program '$program' (build it: cmake --build build --target inkgraph)" >&2; exit 2; }
exec python3 - "$program" "$root/README.md" "$root/docs/robustness.md" <<'PYTHON'
import re, subprocess, sys

program, paths = sys.argv[1], sys.argv[2:]
pattern = re.compile(r"(<!-- generated: ([a-z-]+) -->\n)(.*?)(<!-- end generated -->\n)", re.S)

def regenerate(match):
    section = match.group(2)
    generated = subprocess.run([program, "help", "--docs", section], check=True, capture_output=True,
                               text=True).stdout
    return match.group(1) + generated + match.group(4)

for path in paths:
    text = open(path, encoding="utf-8").read()
    updated, count = pattern.subn(regenerate, text)
    if count == 0:
        sys.exit(f"update-docs.sh: no generated section in {path}")
    if updated != text:
        open(path, "w", encoding="utf-8").write(updated)
    print(f"update-docs.sh: {count} section(s) of {path} {'rewritten' if updated != text else 'already up to date'}")
PYTHON
