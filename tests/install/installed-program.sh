#!/usr/bin/env bash
# The installed program, as a user gets it (docs/install.md), run from an unrelated folder with no INKGRAPH_*
# variable set, against the build tree's program rendering the same command:
#   installed-program.sh prefix BUILD_DIR SOURCE_DIR LIBDIR
#       `cmake --install BUILD_DIR --prefix` into a scratch folder, which is then moved (the tree must be relocatable)
#   installed-program.sh deb BUILD_DIR SOURCE_DIR LIBDIR
#       `cpack -G DEB` makes inkgraph_<version>_amd64.deb; its control data and Depends are checked, and it is
#       unpacked with `dpkg -x` into a scratch root (no root rights needed)
# Each run works in its own temporary folder, removed at the end. Needs a complete build (the program, the OpenImageIO
# module, the man page and completion), oiiotool and idiff (openimageio-tools), groff, readelf, and for `deb` cpack,
# dpkg-shlibdeps (dpkg-dev) and dpkg-deb. Registered in tests/install/CMakeLists.txt with the label `install`.
set -euo pipefail

mode=$1 build=$2 source=$3 libdir=$4
model=bunny_c3d_70k.obj # the bundled default model (scripts/render-default.sh)
render_flags=(--size 192x192 --lines outline -q)

scratch=$(mktemp -d "${TMPDIR:-/tmp}/inkgraph-install-$mode.XXXXXX")
trap 'rm -rf "$scratch"' EXIT
scratch=$(cd "$scratch" && pwd -P) # as the program names its own folder: links resolved
unset INKGRAPH_SHADER_DIR INKGRAPH_IMAGEIO_MODULE
export LP_NUM_THREADS=1

fail() {
    echo "installed-program.sh $mode: $*" >&2
    exit 1
}

for product in "$build/inkgraph" "$build/libinkgraph_imageio.so" "$build/share/man/man1/inkgraph.1" \
    "$build/share/bash-completion/completions/inkgraph"; do
    [ -e "$product" ] || fail "'$product' is missing: build everything first (cmake --build $build)"
done

# Every ELF file under $1: its RPATH and RUNPATH must not name the build tree (installed files carry none of it), and
# every library it needs is found (Debian's on the system's paths, ours through an $ORIGIN RUNPATH).
check_installed_elf_files() {
    local file found=0 unresolved
    while IFS= read -r -d '' file; do
        if head -c 4 "$file" | grep -q $'^\x7fELF'; then
            found=$((found + 1))
            unresolved=$(env -u LD_LIBRARY_PATH ldd "$file" | grep 'not found' || true)
            [ -z "$unresolved" ] || fail "'$file' needs libraries that cannot be found:"$'\n'"$unresolved"
            local paths
            paths=$(readelf -d "$file" | sed -n 's/.*(\(RPATH\|RUNPATH\)).*\[\(.*\)\]/\2/p')
            if grep -qF "$build" <<<"$paths"; then fail "'$file' has an RPATH into the build tree: $paths"; fi
        fi
    done < <(find "$1" -type f -print0)
    [ "$found" -ge 3 ] || fail "only $found ELF files under '$1' (expected the program and its two libraries)"
}

# Renders the model with program $1 in folder $2 to picture.png and picture.exr there.
render_both() {
    mkdir -p "$2"
    cp "$source/models/$model" "$2/"
    (cd "$2" && "$1" render "$model" -o picture.png "${render_flags[@]}" &&
        "$1" render "$model" -o picture.exr "${render_flags[@]}") || fail "'$1' could not render in '$2'"
}

# The installed program with prefix $1 (its binary $1/bin/inkgraph) renders what the build tree's program renders,
# finds its own shaders and module, and never the source tree's.
check_installed_program() {
    local prefix=$1 program=$1/bin/inkgraph
    render_both "$build/inkgraph" "$scratch/expected"
    render_both "$program" "$scratch/work"
    local statistics
    statistics=$(oiiotool "$scratch/work/picture.png" --printstats)
    grep -q 'Constant: No' <<<"$statistics" || fail "the installed program's picture is all one colour: $statistics"
    cmp "$scratch/expected/picture.png" "$scratch/work/picture.png" ||
        fail "the installed program's PNG differs from the build tree's"
    idiff -fail 0 -warn 0 "$scratch/expected/picture.exr" "$scratch/work/picture.exr" >/dev/null ||
        fail "the installed program's EXR differs from the build tree's"

    local report
    report=$(cd "$scratch/work" && "$program" --version --verbose) || fail "'$program --version --verbose' failed"
    grep -qxF "shaders:       $prefix/share/inkgraph/shaders (installed)" <<<"$report" ||
        fail "--version --verbose does not name the installed shaders:"$'\n'"$report"
    grep -qF "(module '$prefix/$libdir/inkgraph/libinkgraph_imageio.so')" <<<"$report" ||
        fail "--version --verbose does not name the installed OpenImageIO module:"$'\n'"$report"
    grep -qE '^inkgraph [0-9]+\.[0-9]+\.[0-9]+ \(git ([0-9a-f]+|unknown)\)$' <<<"$report" ||
        fail "no version line in:"$'\n'"$report"

    # Started through the dynamic loader (as bench/device-kit.sh starts it), whose file /proc/self/exe then names, the
    # program still finds its own files.
    local loader
    loader=$(readelf -l "$program" | sed -n 's/.*Requesting program interpreter: \(.*\)\]/\1/p')
    report=$(cd "$scratch/work" && "$loader" "$program" --version --verbose) || fail "'$loader $program' failed"
    grep -qxF "shaders:       $prefix/share/inkgraph/shaders (installed)" <<<"$report" ||
        fail "started through $loader, the program does not find its shaders:"$'\n'"$report"

    # INKGRAPH_SHADER_DIR still wins over the installed folder.
    local output status=0
    output=$(cd "$scratch/work" && INKGRAPH_SHADER_DIR="$scratch/nowhere" "$program" render "$model" -o x.png \
        "${render_flags[@]}" 2>&1) || status=$?
    [ "$status" = 4 ] && grep -qF "INKGRAPH_SHADER_DIR is '$scratch/nowhere'" <<<"$output" ||
        fail "INKGRAPH_SHADER_DIR did not override the installed shaders (exit $status): $output"

    # Without its shaders the installed program says where it looked, and never falls back to the source tree.
    mv "$prefix/share/inkgraph/shaders" "$scratch/shaders-away"
    status=0
    output=$(cd "$scratch/work" && "$program" render "$model" -o x.png "${render_flags[@]}" 2>&1) || status=$?
    mv "$scratch/shaders-away" "$prefix/share/inkgraph/shaders"
    [ "$status" = 4 ] || fail "without its shaders the installed program exited $status, not 4: $output"
    grep -qF "no shader folder found (searched '$prefix/share/inkgraph/shaders'" <<<"$output" ||
        fail "the error does not name the folders searched: $output"
    if grep -qF "$source" <<<"$output"; then fail "the installed program looked in the source tree: $output"; fi
    [ ! -e "$scratch/work/x.png" ] || fail "a failed run left x.png"

    # The man page and the completion, at their places.
    groff -ww -z -man "$prefix/share/man/man1/inkgraph.1" 2>"$scratch/groff.txt" ||
        fail "groff cannot read the man page"
    [ ! -s "$scratch/groff.txt" ] || fail "groff warns about the man page: $(cat "$scratch/groff.txt")"
    output=$(bash -c 'source "$1" && COMP_WORDS=(inkgraph render --shad) COMP_CWORD=2 && _inkgraph &&
        echo "${COMPREPLY[*]}"' completion "$prefix/share/bash-completion/completions/inkgraph")
    [ "$output" = "--shading --shademap" ] || fail "the installed completion offers '$output' for --shad"
    check_installed_elf_files "$prefix"
}

# libinkgraph.so, installed in prefix $1, finds the shaders and the module relative to itself, not to the program
# that loaded it (a consumer compiled here, in the scratch folder), and never falls back to the source tree.
check_installed_library() {
    local prefix=$1 output status=0
    cat >"$scratch/consumer.cpp" <<'END'
#include <inkgraph/inkgraph.h>
#include <iostream>
int main(int argc, char** argv) {
    namespace ig = inkgraph::api;
    try {
        ig::Renderer renderer;
        ig::Frame frame;
        frame.width = frame.height = 96;
        const ig::Still still = renderer.render(ig::Scene::load(argv[1]), ig::Look::fromArguments({}), frame, {});
        still.write("library.png");
        still.write("library.exr");
    } catch (const ig::Error& error) {
        std::cerr << error.what() << "\n";
        return error.exitCode();
    }
}
END
    "${CXX:-c++}" -std=c++17 "$scratch/consumer.cpp" -I "$prefix/include" -L "$prefix/$libdir" -linkgraph \
        -Wl,-rpath,"$prefix/$libdir" -o "$scratch/consumer" || fail "cannot build a program against libinkgraph"
    (cd "$scratch/work" && "$scratch/consumer" "$model") || fail "the program linking libinkgraph cannot render"
    local statistics
    statistics=$(oiiotool "$scratch/work/library.exr" --printstats)
    grep -q 'Constant: No' <<<"$statistics" || fail "libinkgraph's picture is all one colour: $statistics"
    mv "$prefix/share/inkgraph/shaders" "$scratch/shaders-away"
    output=$(cd "$scratch/work" && "$scratch/consumer" "$model" 2>&1) || status=$?
    mv "$scratch/shaders-away" "$prefix/share/inkgraph/shaders"
    [ "$status" = 4 ] || fail "without its shaders libinkgraph's program exited $status, not 4: $output"
    # The library sits in $prefix/$libdir: its shaders are looked for from there.
    grep -qF "no shader folder found (searched '$(cd "$prefix/$libdir/.." && pwd -P)/share/inkgraph/shaders'" \
        <<<"$output" || fail "libinkgraph does not look for its shaders beside itself: $output"
    if grep -qF "$source" <<<"$output"; then fail "libinkgraph looked in the source tree: $output"; fi
}

version=$(sed -n 's/^CMAKE_PROJECT_VERSION:[A-Z]*=//p' "$build/CMakeCache.txt")
[ -n "$version" ] || fail "no CMAKE_PROJECT_VERSION in '$build/CMakeCache.txt'"

case $mode in
prefix)
    cmake --install "$build" --prefix "$scratch/first" >"$scratch/install.log" ||
        fail "cmake --install failed: $(cat "$scratch/install.log")"
    mv "$scratch/first" "$scratch/moved" # the tree must work wherever it is
    prefix=$scratch/moved
    for file in bin/inkgraph "$libdir/inkgraph/libinkgraph_imageio.so" share/man/man1/inkgraph.1 \
        share/bash-completion/completions/inkgraph share/inkgraph/shaders/common/color.glsl \
        share/inkgraph/shademaps/README.md; do
        [ -f "$prefix/$file" ] || fail "'$file' is not installed"
    done
    [ ! -e "$prefix/share/inkgraph/shaders/_template" ] || fail "the template shaders are installed"
    expected_maps=$(cd "$source/shademaps" && ls ./*.png | wc -l)
    installed_maps=$(cd "$prefix/share/inkgraph/shademaps" && ls ./*.png | wc -l)
    [ "$expected_maps" = "$installed_maps" ] || fail "$installed_maps shade maps installed, not $expected_maps"
    # Every shader the source tree's ShaderLibrary would read is installed, byte for byte.
    (cd "$source/shaders" && find . -type f ! -name '*.md' ! -path './_template/*') | while read -r shader; do
        cmp -s "$source/shaders/$shader" "$prefix/share/inkgraph/shaders/$shader" || fail "shader '$shader' differs"
    done
    check_installed_program "$prefix"
    check_installed_library "$prefix"
    ;;
deb)
    (cd "$scratch" && cpack -G DEB --config "$build/CPackConfig.cmake" -B "$scratch/package") >"$scratch/cpack.log" ||
        fail "cpack failed: $(cat "$scratch/cpack.log")"
    deb=$scratch/package/inkgraph_${version}_amd64.deb
    [ -f "$deb" ] || fail "no '$(basename "$deb")' made: $(ls "$scratch/package")"
    [ "$(dpkg-deb -f "$deb" Package)" = inkgraph ] || fail "the package is not named inkgraph"
    [ "$(dpkg-deb -f "$deb" Version)" = "$version" ] || fail "the package's version is not $version"
    [ "$(dpkg-deb -f "$deb" Architecture)" = amd64 ] || fail "the package is not for amd64"
    [ "$(dpkg-deb -f "$deb" Section)" = graphics ] || fail "the package's section is not graphics"
    [ -n "$(dpkg-deb -f "$deb" Maintainer)" ] || fail "the package has no maintainer"
    depends=$(dpkg-deb -f "$deb" Depends)
    depend_names=$(tr ',|' '\n\n' <<<"$depends" | sed -E 's/\(.*\)//; s/ //g' | grep -v '^$')
    # Each dependency (every alternative) is a Debian package this system knows.
    for name in $depend_names; do
        dpkg-query -W "$name" >/dev/null 2>&1 || fail "Depends names '$name', which is not a package here"
    done
    for name in libegl1 libgl1 libegl-mesa0 libgl1-mesa-dri; do # opened with dlopen: dpkg-shlibdeps cannot see them
        grep -qxF "$name" <<<"$depend_names" || fail "Depends lacks $name: $depends"
    done
    listing=$(dpkg-deb -c "$deb")
    for file in ./usr/bin/inkgraph "./usr/$libdir/inkgraph/libinkgraph_imageio.so" \
        ./usr/share/man/man1/inkgraph.1 ./usr/share/bash-completion/completions/inkgraph \
        ./usr/share/inkgraph/shaders/common/color.glsl ./usr/share/inkgraph/shademaps/README.md; do
        grep -qF " $file" <<<"$listing" || fail "the package lacks '$file'"
    done
    dpkg -x "$deb" "$scratch/root"
    # dpkg-shlibdeps at work: every library an ELF file of the package needs, and the package does not hold, comes
    # from a package that Depends names.
    while IFS= read -r -d '' file; do
        head -c 4 "$file" | grep -q $'^\x7fELF' || continue
        for soname in $(readelf -d "$file" | sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p'); do
            [ -n "$(find "$scratch/root" -name "$soname")" ] && continue
            library=$(ldconfig -p | awk -v name="$soname" '$1 == name && /x86-64/ && !found {print $NF; found = 1}')
            [ -n "$library" ] || fail "'$file' needs '$soname', which this system lacks"
            owner=$(dpkg -S "$(readlink -f "$library")" 2>/dev/null || dpkg -S "$library" 2>/dev/null) ||
                fail "no package owns '$library'"
            owner=${owner%%:*}
            grep -qxF "$owner" <<<"$depend_names" ||
                fail "'$file' needs '$soname' of $owner, which Depends lacks: $depends"
        done
    done < <(find "$scratch/root" -type f -print0)
    # Installable on a fresh Debian 12: apt resolves every dependency from the archive for a system with nothing
    # installed. Only where apt has package lists (apt-get update has run).
    policy=$(apt-cache policy libc6 2>/dev/null || true)
    if grep -qE '^ +[0-9]+ (https?|file):' <<<"$policy"; then
        : >"$scratch/empty-status"
        apt-get install --simulate -o Dir::State::status="$scratch/empty-status" -o Debug::NoLocking=1 "$deb" \
            >"$scratch/apt.log" 2>&1 || fail "apt cannot install the package on an empty system: $(tail -20 "$scratch/apt.log")"
        grep -q '^Inst inkgraph ' "$scratch/apt.log" || fail "apt's simulation does not install inkgraph"
    else
        echo "installed-program.sh deb: no apt package lists here; the apt simulation is left out"
    fi
    check_installed_program "$scratch/root/usr"
    ;;
*)
    fail "unknown mode '$mode' (prefix or deb)"
    ;;
esac
echo "installed-program.sh $mode: ok"
