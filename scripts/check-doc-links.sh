#!/usr/bin/env bash
# Fails when a Markdown file of the repo links to a file the repo does not hold: every relative link target
# ([text](path), ![alt](path), [label]: path, <img src="path">, <a href="path">) in every tracked *.md must name an
# existing file or folder inside the repository. Web links (scheme:...) and in-page anchors (#...) are not checked;
# a "#anchor" after a path is ignored. Fenced code blocks and inline code are skipped.
# Usage: scripts/check-doc-links.sh [REPO_ROOT]   (default: the repo this script is in). Prints each broken link as
# FILE:LINE: TARGET (why) and exits 1 if there is any.
set -euo pipefail
root="$(cd "${1:-$(dirname "$0")/..}" && pwd)"
exec python3 - "$root" <<'PYTHON'
import os, re, subprocess, sys

root = os.path.realpath(sys.argv[1])
try:
    listed = subprocess.run(["git", "-C", root, "ls-files", "-z", "--cached", "--others", "--exclude-standard",
                             "*.md"], check=True, capture_output=True).stdout.decode().split("\0")
    files = sorted(f for f in listed if f and os.path.isfile(os.path.join(root, f)))
except (OSError, subprocess.CalledProcessError):  # not a git checkout: every *.md outside hidden and build folders
    files = []
    for folder, folders, names in os.walk(root):
        folders[:] = sorted(f for f in folders if not f.startswith((".", "build")))
        files += [os.path.relpath(os.path.join(folder, n), root) for n in sorted(names) if n.endswith(".md")]

INLINE = re.compile(r"!?\[(?:[^\[\]]|\[[^\]]*\])*\]\(\s*(<[^>]*>|[^)\s]+)(?:\s+\"[^\"]*\")?\s*\)")
REFERENCE = re.compile(r"^\s{0,3}\[[^\]]+\]:\s*(<[^>]*>|\S+)")
HTML = re.compile(r"<(?:img|a|source)\b[^>]*?\b(?:src|href)\s*=\s*[\"']([^\"']+)[\"']", re.IGNORECASE)
SCHEME = re.compile(r"^[A-Za-z][A-Za-z0-9+.-]*:")

broken = []
for name in files:
    path = os.path.join(root, name)
    with open(path, encoding="utf-8", errors="replace") as handle:
        lines = handle.read().split("\n")
    fence = None
    for number, line in enumerate(lines, 1):
        stripped = line.lstrip()
        marker = re.match(r"(`{3,}|~{3,})", stripped)
        if marker:
            if fence is None:
                fence = marker.group(1)[0] * len(marker.group(1))
            elif stripped.startswith(fence):
                fence = None
            continue
        if fence is not None:
            continue
        text = re.sub(r"(`+)(?:(?!\1).)+?\1", "", line)  # inline code
        targets = [m.group(1) for m in INLINE.finditer(text)] + [m.group(1) for m in HTML.finditer(text)]
        reference = REFERENCE.match(text)
        if reference:
            targets.append(reference.group(1))
        for target in targets:
            target = target.strip("<>")
            if not target or target.startswith("#") or SCHEME.match(target):
                continue
            relative = target.split("#", 1)[0].split("?", 1)[0]
            if not relative:
                continue
            base = root if relative.startswith("/") else os.path.dirname(path)
            resolved = os.path.realpath(os.path.join(base, relative.lstrip("/")))
            if resolved != root and not resolved.startswith(root + os.sep):
                broken.append(f"{name}:{number}: {target} (outside the repository)")
            elif not os.path.exists(resolved):
                broken.append(f"{name}:{number}: {target} (no such file)")

for line in broken:
    print(line)
print(f"check-doc-links: {len(files)} Markdown files, {len(broken)} broken links", file=sys.stderr)
sys.exit(1 if broken else 0)
PYTHON
