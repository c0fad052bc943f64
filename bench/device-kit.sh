#!/usr/bin/env bash
# The bench's programs with every library they load, for a machine where none of our Debian 12 libraries are
# installed (a GPU machine's image with only its NVIDIA driver): bench/device-rows.sh runs them there.
#   bench/device-kit.sh [BUILD_DIR] [KIT_DIR]      (defaults build/ and .devicekit/; after scripts/build.sh)
# KIT_DIR/bin holds inkgraph, inkgraph_egl_probe, inkgraph_make_mesh, GNU time (whole-process.sh's peak RSS; images
# often lack /usr/bin/time) and, each left out when the kit would pass KIT_LIMIT_MB, inkgraph_bench and the GL tests
# named in KIT_TESTS (default tests/passes/passes_post_stage_gl_tests: the GPU post stage against the CPU's).
# KIT_ARCHIVE=1 also writes KIT_DIR.tar.xz, about a third of the kit, for a device tool that carries at most 64 MiB
# with the tree (then KIT_LIMIT_MB defaults to 120, not 40); device-rows.sh unpacks it when KIT_DIR is absent. KIT_DIR/lib
# holds what `ldd` lists for them, under the names it lists (the sonames), glibc and its loader included, plus what is
# opened at run time and so not listed: glvnd's libEGL.so.1, libOpenGL.so.0 and libGL.so.1 (libepoxy), libtbbmalloc.so.2
# (libtbb), glibc's small libraries a driver links (libpthread, librt, ...). No GL driver is carried (Mesa's
# libEGL_mesa, swrast, libLLVM): glvnd loads the machine's vendor library, NVIDIA's on a GPU machine. KIT_DIR/run/NAME
# starts bin/NAME through the carried loader with --library-path KIT_DIR/lib (then $LD_LIBRARY_PATH), so the Debian
# userland runs whatever the image's glibc is, from any folder; it sets INKGRAPH_SHADER_DIR to this tree's shaders/
# unless the environment does. KIT_DIR/MANIFEST says what was copied from where.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "${1:-$root/build}" && pwd)
kit=${2:-$root/.devicekit}
archive=${KIT_ARCHIVE:-0}
limit_mb=${KIT_LIMIT_MB:-$([ "$archive" = 1 ] && echo 120 || echo 40)}
read -r -a tests <<<"${KIT_TESTS-tests/passes/passes_post_stage_gl_tests}"

programs=(inkgraph bench/inkgraph_egl_probe bench/inkgraph_make_mesh)
for program in "${programs[@]}"; do
    [ -x "$build/$program" ] || { echo "device-kit.sh: $build/$program is missing (build it first)" >&2; exit 1; }
done
# Never a folder that is not an earlier kit.
if [ -e "$kit" ] && [ -n "$(ls -A "$kit")" ] && [ ! -f "$kit/MANIFEST" ]; then
    echo "device-kit.sh: $kit exists and is not a kit (no MANIFEST): not replaced" >&2
    exit 1
fi
rm -rf "$kit"
mkdir -p "$kit/bin" "$kit/lib" "$kit/run"
kit=$(cd "$kit" && pwd)

# What the kit must never hold: a GL driver of this machine would stand in for the GPU machine's.
forbidden='^(libEGL_mesa|libGLX_mesa|libglapi|libgallium|libLLVM|libdrm|libgbm|.*swrast|.*_dri)'

copy_library() { # soname path: the file behind path, named soname
    if [[ $1 =~ $forbidden ]]; then
        echo "device-kit.sh: $1 ($2) belongs to a GL driver: not carried" >&2
        exit 1
    fi
    if [ ! -e "$kit/lib/$1" ]; then cp -L "$2" "$kit/lib/$1"; fi
}

add_dependencies() { # file: every library ldd lists for it, and the loader
    local listing
    listing=$(ldd "$1") || { echo "device-kit.sh: ldd $1 failed" >&2; exit 1; }
    if grep -q "not found" <<<"$listing"; then
        echo "device-kit.sh: $1 has unresolved libraries:" >&2
        grep "not found" <<<"$listing" >&2
        exit 1
    fi
    while read -r name arrow path _; do
        if [ "$arrow" = "=>" ] && [ -f "$path" ]; then
            copy_library "$name" "$path"
        elif [[ $name == /*/ld-linux-x86-64.so.2 ]]; then
            copy_library ld-linux-x86-64.so.2 "$name"
        fi
    done <<<"$listing"
}

add_program() { # path in the build, name in the kit
    cp -L "$1" "$kit/bin/$2"
    add_dependencies "$1"
}

for program in "${programs[@]}"; do add_program "$build/$program" "$(basename "$program")"; done
if [ -x /usr/bin/time ]; then add_program /usr/bin/time time; fi

# Opened with dlopen (libepoxy: libEGL.so.1, then libOpenGL.so.0 or libGL.so.1; libtbb: libtbbmalloc.so.2), and
# glibc's libraries that the GPU machine's driver libraries may link: from the image they would not match our libc.
libc_folder=$(dirname "$(ldd "$build/inkgraph" | awk '$1 == "libc.so.6" {print $3}')")
for name in libEGL.so.1 libOpenGL.so.0 libGL.so.1 libGLdispatch.so.0 libGLX.so.0 libtbbmalloc.so.2 \
    libc.so.6 libm.so.6 libdl.so.2 libpthread.so.0 librt.so.1 libresolv.so.2 libutil.so.1 libanl.so.1 \
    libnss_files.so.2 libnss_dns.so.2; do
    found=""
    for folder in "$libc_folder" /usr/lib/x86_64-linux-gnu /lib/x86_64-linux-gnu; do
        if [ -e "$folder/$name" ]; then
            found=$folder/$name
            break
        fi
    done
    if [ -z "$found" ]; then
        echo "device-kit.sh: $name not found on this machine (skipped)" >&2
        continue
    fi
    copy_library "$name" "$found"
    add_dependencies "$found"
done
# Once more over everything carried: a library's own dependencies (those of dlopened ones especially).
for library in "$kit"/lib/*; do
    if [ "$(basename "$library")" != ld-linux-x86-64.so.2 ]; then add_dependencies "$library"; fi
done

size_of() { du -sb "$@" | awk '{s += $1} END {print s}'; }
add_optional_program() { # path in the build, name in the kit: only while the kit stays under the limit
    [ -x "$1" ] || { echo "device-kit.sh: $1 is missing: left out" >&2; return 0; }
    local extra name arrow path _ total
    extra=$(size_of "$1")
    while read -r name arrow path _; do
        if [ "$arrow" = "=>" ] && [ -f "$path" ] && [ ! -e "$kit/lib/$name" ]; then
            extra=$((extra + $(size_of "$(readlink -f "$path")")))
        fi
    done < <(ldd "$1")
    total=$(($(size_of "$kit") + extra))
    if ((total > limit_mb * 1024 * 1024)); then
        echo "device-kit.sh: $2 left out: the kit would be $((total / 1048576)) MiB," \
            "over $limit_mb MiB (KIT_LIMIT_MB)" >&2
    else
        add_program "$1" "$2"
    fi
}
if [ -x "$build/bench/inkgraph_bench" ]; then add_optional_program "$build/bench/inkgraph_bench" inkgraph_bench; fi
for test in "${tests[@]}"; do add_optional_program "$build/$test" "$(basename "$test")"; done

# The wrappers: POSIX sh (dash where /bin/sh is dash), no subprocess, so a whole-process row pays ~1 ms for them.
shaders=$(realpath -m --relative-to="$kit" "$root/shaders")
# inkgraph starts itself again with its malloc tunables (app/main.cpp), but not when the dynamic loader started it, as
# the wrapper does: the wrapper sets them instead, as inkgraph would (GLIBC_TUNABLES set by the caller, even empty,
# is kept), so the GPU rows measure what an installed inkgraph runs with.
tunables=$(sed -n 's/.*kMallocTunables = "\([^"]*\)";.*/\1/p' "$root/app/main.cpp")
[ -n "$tunables" ] || { echo "device-kit.sh: no kMallocTunables in $root/app/main.cpp" >&2; exit 1; }
for program in "$kit"/bin/*; do
    name=$(basename "$program")
    malloc_tunables=""
    [ "$name" = inkgraph ] && malloc_tunables="GLIBC_TUNABLES=\${GLIBC_TUNABLES-$tunables}
export GLIBC_TUNABLES"
    cat >"$kit/run/$name" <<EOF
#!/bin/sh
# bin/$name of the device kit (bench/device-kit.sh), through the kit's loader and libraries: Debian's glibc and
# userland whatever the machine's are; the GL vendor library is the machine's (glvnd: __EGL_VENDOR_LIBRARY_FILENAMES).
case \$0 in */*) kit=\${0%/*}/.. ;; *) kit=.. ;; esac
case \$kit in /*) ;; *) kit=\$PWD/\$kit ;; esac
INKGRAPH_SHADER_DIR=\${INKGRAPH_SHADER_DIR:-\$kit/$shaders}
export INKGRAPH_SHADER_DIR
$malloc_tunables
exec "\$kit/lib/ld-linux-x86-64.so.2" --library-path "\$kit/lib\${LD_LIBRARY_PATH:+:\$LD_LIBRARY_PATH}" --argv0 "\$0" \\
    "\$kit/bin/$name" "\$@"
EOF
    chmod 755 "$kit/run/$name"
done

# The tree the build was made from (inkgraph_bench reads its models/ and bench/shaders/ there), and how far it is
# from this one, whose shaders/ the kit's programs read.
source_root=$(sed -n 's/^CMAKE_HOME_DIRECTORY:INTERNAL=//p' "$build/CMakeCache.txt" 2>/dev/null || true)
source_commit="" changed=""
if [ -n "$source_root" ] && git -C "$source_root" rev-parse HEAD >/dev/null 2>&1; then
    source_commit=$(git -C "$source_root" rev-parse HEAD)
    changed=$(GIT_OPTIONAL_LOCKS=0 git -C "$source_root" status --porcelain --untracked-files=no | wc -l)
    # Scripts and documents aside, this tree's commit should be the build's, and the build's tree unchanged.
    if ! git -C "$root" diff --quiet "$source_commit" HEAD -- ':(exclude)*.sh' ':(exclude)*.md' 2>/dev/null ||
        [ "$changed" != 0 ]; then
        echo "device-kit.sh: warning: the build's tree $source_root is at ${source_commit:0:7} with $changed" \
            "changed files, this tree at $(git -C "$root" rev-parse --short HEAD): the binaries may not be this" \
            "tree's" >&2
    fi
    if [ "$(cd "$source_root" && pwd -P)" != "$(cd "$root" && pwd -P)" ]; then
        for folder in shaders bench/shaders; do
            if ! diff -rq "$source_root/$folder" "$root/$folder" >/dev/null 2>&1; then
                echo "device-kit.sh: warning: $folder/ differs between $source_root and $root:" >&2
                diff -rq "$source_root/$folder" "$root/$folder" >&2 || true
            fi
        done
    fi
fi
{
    echo "# bench/device-kit.sh $(date -u +%Y-%m-%dT%H:%M:%SZ) on $(uname -n)"
    echo "build=$build"
    echo "source_root=$source_root"
    echo "source_commit=$source_commit"
    echo "source_changed_files=$changed"
    echo "shaders=$shaders"
    (cd "$kit" && for file in bin/* lib/*; do
        printf '%s %s %s\n' "$(sha256sum "$file" | cut -c1-16)" "$(stat -c %s "$file")" "$file"
    done)
} >"$kit/MANIFEST"

echo "device kit: $kit: $(ls "$kit/bin" | tr '\n' ' ')+ $(ls "$kit/lib" | wc -l) libraries," \
    "$(awk -v b="$(size_of "$kit")" 'BEGIN { printf "%.1f MiB (%.1f MB)", b / 1048576, b / 1e6 }')"
if [ "$archive" = 1 ]; then
    rm -f "$kit.tar.xz"
    tar -C "$(dirname "$kit")" -cf - "$(basename "$kit")" | xz -T0 -6 >"$kit.tar.xz.tmp"
    mv "$kit.tar.xz.tmp" "$kit.tar.xz"
    echo "device kit archive: $kit.tar.xz, $(awk -v b="$(size_of "$kit.tar.xz")" 'BEGIN { printf "%.1f MiB", b / 1048576 }')"
fi
