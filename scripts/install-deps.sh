#!/usr/bin/env bash
# Installs what inkgraph needs from Debian 12's packages, only what is missing. Safe to run again.
set -euo pipefail

packages=(
    build-essential cmake pkg-config
    libegl-dev libgl-dev libopengl-dev libegl1 libegl-mesa0 libgl1-mesa-dri libepoxy-dev
    libglm-dev libopencv-dev libtbb-dev libtinygltf-dev libdraco-dev libmeshoptimizer-dev nlohmann-json3-dev libstb-dev libpng-dev libjpeg-dev libwebp-dev
    libopenimageio-dev openimageio-tools
    libgtest-dev libgmock-dev libbenchmark-dev
    pybind11-dev python3-dev python3-numpy python3-pytest python3-mypy python3-jsonschema
    slurm-wlm munge
    groff-base
    clang-format
)

missing=()
for package in "${packages[@]}"; do
    if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
        missing+=("$package")
    fi
done

if [ ${#missing[@]} -eq 0 ]; then
    echo "install-deps: all ${#packages[@]} packages present"
    exit 0
fi

sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then
    if command -v sudo >/dev/null 2>&1; then
        sudo_cmd=(sudo)
    else
        echo "install-deps: missing packages (${missing[*]}) and not root, and no sudo to install them" >&2
        exit 1
    fi
fi

echo "install-deps: installing ${missing[*]}"
# Through env, because sudo resets the environment: without it tzdata (pulled in by OpenCV) can stop at a prompt.
"${sudo_cmd[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update -qq
"${sudo_cmd[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}"
