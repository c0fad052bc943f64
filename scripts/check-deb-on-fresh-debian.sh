#!/usr/bin/env bash
# Proves that the Debian packages install and work on a fresh Debian 12: builds a minimal Debian 12 root with
# debootstrap, installs the packages there with apt (which fetches their dependencies from the archive, so this needs
# the network and root), and renders from the installed program and the installed Python module:
#   bash scripts/check-deb-on-fresh-debian.sh [BUILD_DIR]      (default build/; after scripts/build.sh)
# About 3 minutes and 1 GiB in a temporary folder, removed at the end. Not part of the test suite, which must run
# without the network; tests/install checks the same packages unpacked with dpkg -x.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "${1:-$root/build}" && pwd)
[ "$(id -u)" -eq 0 ] || { echo "check-deb-on-fresh-debian: needs root (debootstrap, chroot)" >&2; exit 1; }
command -v debootstrap >/dev/null ||
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends debootstrap >/dev/null
work=$(mktemp -d /tmp/inkgraph-fresh-debian.XXXXXX)
chroot_dir=$work/root
cleanup() {
    umount "$chroot_dir/proc" 2>/dev/null || true
    rm -rf "$work"
}
trap cleanup EXIT

echo "check-deb-on-fresh-debian: packages from $build"
(cd "$work" && cpack --config "$build/CPackConfig.cmake" -G DEB >/dev/null)
echo "check-deb-on-fresh-debian: debootstrap --variant=minbase bookworm"
debootstrap --variant=minbase bookworm "$chroot_dir" http://deb.debian.org/debian >"$work/debootstrap.log" 2>&1 ||
    { tail -20 "$work/debootstrap.log" >&2; exit 1; }
cp "$work"/inkgraph_*.deb "$work"/python3-inkgraph_*.deb "$root/models/bunny_c3d_70k.obj" "$chroot_dir/root/"
cp /etc/resolv.conf "$chroot_dir/etc/resolv.conf"
mount -t proc proc "$chroot_dir/proc"
inside() { chroot "$chroot_dir" /usr/bin/env -i PATH=/usr/bin:/bin HOME=/root LP_NUM_THREADS=1 bash -c "$1"; }
echo "check-deb-on-fresh-debian: apt install ./inkgraph_*.deb ./python3-inkgraph_*.deb"
inside 'apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq /root/*.deb' \
    >"$work/apt.log" 2>&1 || { tail -20 "$work/apt.log" >&2; exit 1; }
inside 'cd /tmp && inkgraph --version --verbose | head -6 &&
    inkgraph render /root/bunny_c3d_70k.obj -o /tmp/bunny.png --shading cel --lines silhouette,contour,suggestive -q &&
    inkgraph render /root/bunny_c3d_70k.obj -o /tmp/bunny.exr -q &&
    python3 -c "import inkgraph
r = inkgraph.render(\"/root/bunny_c3d_70k.obj\", size=256, buffers=[\"normal\"])
assert r.picture.shape == (256, 256, 4) and r.buffers[\"normal\"].shape == (256, 256, 4)
print(\"python:\", inkgraph.__version__)"'
"$build/inkgraph" render "$root/models/bunny_c3d_70k.obj" -o "$work/build-bunny.png" --shading cel \
    --lines silhouette,contour,suggestive -q
cmp "$work/build-bunny.png" "$chroot_dir/tmp/bunny.png"
echo "check-deb-on-fresh-debian: the packaged program's picture is identical to the build's; done"
