#!/usr/bin/env bash
# examples/cpp-consumer built against the installed package, as a user builds it: the build installed into a scratch
# prefix (`cmake --install`), the example configured there with CMAKE_PREFIX_PATH alone, built, and run on a bundled
# character at 128x128 (llvmpipe draws its 8 views in seconds). It must link the installed library under the soname of
# its minor (libinkgraph.so.MAJOR.MINOR, from the installed header's INKGRAPH_VERSION_*), use typed calls only (no
# flag strings), and write the files its README names: 8 pictures of the size with ink, and 8 cameras whose K has its
# centre at (width/2 - 0.5, height/2 - 0.5) and whose [R|t] has an orthonormal R and agrees with the view matrix.
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

# Typed calls only: the example is the API's showcase, so no command-line words (flags, the string adapter).
main=$source/examples/cpp-consumer/main.cpp
if grep -n -e '"--' -e 'fromArguments' -e 'fromStyleFile' -e '\.set(' "$main" > "$work/flags.txt"; then
    fail "main.cpp uses flag strings: $(cat "$work/flags.txt")"
fi

prefix=$work/prefix
cmake --install "$build" --prefix "$prefix" > "$work/install.log" || fail "cmake --install failed: $(cat "$work/install.log")"
cmake -S "$source/examples/cpp-consumer" -B "$work/build" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release \
    > "$work/configure.log" 2>&1 || fail "configuring the consumer failed: $(cat "$work/configure.log")"
cmake --build "$work/build" > "$work/build.log" 2>&1 || fail "building the consumer failed: $(cat "$work/build.log")"
consumer=$work/build/inkgraph-consumer

# The version the installed header declares; the library it runs with is the installed one, under its minor's soname.
versionPart() { sed -n "s/^#define INKGRAPH_VERSION_$1 \([0-9]*\)$/\1/p" "$prefix/include/inkgraph/inkgraph.h"; }
major=$(versionPart MAJOR)
minor=$(versionPart MINOR)
patch=$(versionPart PATCH)
[ -n "$major" ] && [ -n "$minor" ] && [ -n "$patch" ] || fail "no INKGRAPH_VERSION_* in the installed header"
soname=libinkgraph.so.$major.$minor
library=$(ldd "$consumer" | awk -v soname="$soname" '$1 == soname { print $3 }')
[[ "$library" == "$prefix"/* ]] ||
    fail "the consumer links '$library' as $soname, not the installed library under $prefix: $(ldd "$consumer")"

(cd "$work" && "$consumer" "$source/models/characters/godette.vrm" out 128 > stdout.txt 2> stderr.txt) ||
    fail "the consumer failed: $(cat "$work/stderr.txt")"
version=$major.$minor.$patch
grep -q "^inkgraph $version (git .*), built against $version$" "$work/stdout.txt" ||
    fail "no version line for $version: $(cat "$work/stdout.txt")"

# PNG: the IHDR chunk's width and height, big-endian, at bytes 16 to 23.
pngSize() { od -An -tu1 -j16 -N8 "$1" | awk '{ printf "%dx%d", $1*16777216+$2*65536+$3*256+$4, $5*16777216+$6*65536+$7*256+$8 }'; }
for view in 00 01 02 03 04 05 06 07; do
    picture=picture-$view.png
    [ -s "$work/out/$picture" ] || fail "no $picture"
    [ -s "$work/out/camera-$view.json" ] || fail "no camera-$view.json"
    [ "$(pngSize "$work/out/$picture")" = 128x128 ] || fail "$picture is $(pngSize "$work/out/$picture")"
    # Each view has a contour and the model covers a share of the frame (the program counts them).
    line=$(grep "^$picture, camera-$view.json: " "$work/stdout.txt") || fail "no line for view $view: $(cat "$work/stdout.txt")"
    contour=$(sed -n 's/.*, contour \([0-9]*\) pixels, .*/\1/p' <<< "$line")
    covered=$(sed -n 's/.*, covered \([0-9]*\) pixels$/\1/p' <<< "$line")
    [ -n "$contour" ] && [ "$contour" -gt 20 ] || fail "view $view's contour: $line"
    [ -n "$covered" ] && [ "$covered" -gt $((128 * 128 / 20)) ] || fail "view $view's coverage: $line"
done
! cmp -s "$work/out/picture-00.png" "$work/out/picture-02.png" || fail "the front and the side view are the same picture"

# The cameras: K in OpenCV's convention at the picture's size, [R|t] a rotation and the view matrix with its y and z
# rows negated, its camera centre -R^T t at the eye, the eyes on one circle around the target, 45 degrees apart.
python3 - "$work/out" > "$work/cameras.txt" 2>&1 <<'PYTHON' || fail "the cameras: $(cat "$work/cameras.txt")"
import json, math, sys

def close(a, b, scale=1.0):
    return abs(a - b) <= 1e-9 * max(1.0, scale)

eyes = []
for view in range(8):
    name = f"{sys.argv[1]}/camera-{view:02d}.json"
    with open(name) as handle:
        camera = json.load(handle)
    def check(condition, what):
        if not condition:
            sys.exit(f"{name}: {what}: {json.dumps(camera)}")
    width, height = camera["width"], camera["height"]
    check((width, height) == (128, 128), "the size")
    check(camera["source"] == "orbit" and camera["picture"] == f"picture-{view:02d}.png", "source and picture")
    check(camera["azimuth_degrees"] == 45 * view, "the azimuth")
    K = camera["intrinsics"]
    focal = (height / 2) / math.tan(math.radians(camera["fov_y_degrees"]) / 2)
    check(close(K[0][0], focal, focal) and close(K[1][1], focal, focal), "fx = fy = (height / 2) / tan(fovY / 2)")
    check(K[0][2] == width / 2 - 0.5 and K[1][2] == height / 2 - 0.5, "cx = width/2 - 0.5, cy = height/2 - 0.5")
    check(K[0][1] == 0 and K[1][0] == 0 and K[2] == [0, 0, 1], "K's zeros and its last row")
    Rt = camera["extrinsics"]
    check(len(Rt) == 3 and all(len(row) == 4 for row in Rt), "[R|t] is 3 x 4")
    R = [row[:3] for row in Rt]
    t = [row[3] for row in Rt]
    for i in range(3):
        for j in range(3):
            dot = sum(R[i][k] * R[j][k] for k in range(3))
            check(close(dot, 1.0 if i == j else 0.0), "R R^T = I")
    det = (R[0][0] * (R[1][1] * R[2][2] - R[1][2] * R[2][1]) - R[0][1] * (R[1][0] * R[2][2] - R[1][2] * R[2][0]) +
           R[0][2] * (R[1][0] * R[2][1] - R[1][1] * R[2][0]))
    check(close(det, 1.0), "det R = 1")
    view_matrix = camera["view_matrix"]
    check(len(view_matrix) == 4 and len(camera["projection_matrix"]) == 4, "4 x 4 view and projection")
    for i, sign in enumerate((1, -1, -1)):
        for j in range(4):
            check(close(Rt[i][j], sign * view_matrix[i][j], abs(view_matrix[i][j])), "[R|t] = the view's rows x, -y, -z")
    centre = [-sum(R[k][i] * t[k] for k in range(3)) for i in range(3)]
    scale = max(abs(v) for v in camera["eye"])
    check(all(close(centre[i], camera["eye"][i], 1e3 * scale) for i in range(3)), "-R^T t is the eye")
    eyes.append([camera["eye"][i] - camera["target"][i] for i in range(3)])

radius = math.dist(eyes[0], [0, 0, 0])
for view, eye in enumerate(eyes):
    if abs(math.dist(eye, [0, 0, 0]) - radius) > 1e-6 * radius:
        sys.exit(f"view {view}'s eye is not as far from the target as view 0's")
    following = eyes[(view + 1) % 8]
    angle = math.degrees(math.acos(sum(a * b for a, b in zip(eye, following)) / radius ** 2))
    horizontal = math.degrees(math.acos(math.cos(math.radians(45)) * math.cos(math.radians(10)) ** 2 +
                                        math.sin(math.radians(10)) ** 2))
    if abs(angle - horizontal) > 1e-6:
        sys.exit(f"views {view} and {(view + 1) % 8}: {angle} degrees apart, not {horizontal} (45 on the circle at 10 up)")
PYTHON
echo "consumer-test: built against $prefix ($soname), rendered: $(tr '\n' ';' < "$work/stdout.txt")"
