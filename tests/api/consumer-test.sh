#!/usr/bin/env bash
# examples/cpp-consumer built against the installed package, as a user builds it: the build installed into a scratch
# prefix (`cmake --install`), the example configured there with CMAKE_PREFIX_PATH alone, built, and run on a bundled
# model; it must link the installed libinkgraph.so and write the files its README names, of the right sizes, with ink.
# Usage: consumer-test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$(realpath "$1")
source=$(realpath "$2")
work=$(mktemp -d "${TMPDIR:-/tmp}/inkgraph-consumer.XXXXXX")
fail() {
    echo "consumer-test: $*" >&2
    echo "consumer-test: kept $work" >&2
    trap - EXIT
    exit 1
}
trap 'rm -rf "$work"' EXIT

prefix=$work/prefix
cmake --install "$build" --prefix "$prefix" > "$work/install.log" || fail "cmake --install failed: $(cat "$work/install.log")"
cmake -S "$source/examples/cpp-consumer" -B "$work/build" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release \
    > "$work/configure.log" 2>&1 || fail "configuring the consumer failed: $(cat "$work/configure.log")"
cmake --build "$work/build" > "$work/build.log" 2>&1 || fail "building the consumer failed: $(cat "$work/build.log")"
consumer=$work/build/inkgraph-consumer

# The library it runs with is the installed one.
library=$(ldd "$consumer" | awk '$1 == "libinkgraph.so.0.2" { print $3 }')
[[ "$library" == "$prefix"/* ]] || fail "the consumer links '$library', not the installed library under $prefix"

(cd "$work" && "$consumer" "$source/models/suzanne_npm_4k.obj" out > stdout.txt 2> stderr.txt) ||
    fail "the consumer failed: $(cat "$work/stderr.txt")"
for file in picture.png contour.png normal.exr; do
    [ -s "$work/out/$file" ] || fail "no $file"
done

# PNG: the IHDR chunk's width and height, big-endian, at bytes 16 to 23.
pngSize() { od -An -tu1 -j16 -N8 "$1" | awk '{ printf "%dx%d", $1*16777216+$2*65536+$3*256+$4, $5*16777216+$6*65536+$7*256+$8 }'; }
[ "$(pngSize "$work/out/picture.png")" = 512x384 ] || fail "picture.png is $(pngSize "$work/out/picture.png")"
[ "$(pngSize "$work/out/contour.png")" = 512x384 ] || fail "contour.png is $(pngSize "$work/out/contour.png")"

# Every buffer at the frame's size; the contour has ink and the normals cover a good share of the frame.
pixelsSet() { sed -n "s/^$1: $2, \([0-9]*\) pixels set$/\1/p" "$work/stdout.txt"; }
contour=$(pixelsSet lines.contour "512x384x1 uint8")
covered=$(pixelsSet normal "512x384x4 float32")
[ -n "$contour" ] && [ "$contour" -gt 200 ] || fail "the contour layer: $(cat "$work/stdout.txt")"
[ -n "$covered" ] && [ "$covered" -gt $((512 * 384 / 8)) ] || fail "the normals: $(cat "$work/stdout.txt")"
grep -q "^inkgraph 0.2.0 (git " "$work/stdout.txt" || fail "no version line: $(cat "$work/stdout.txt")"
echo "consumer-test: built against $prefix, rendered: $(tr '\n' ';' < "$work/stdout.txt")"
