#!/usr/bin/env bash
# Installs every Debian 12 package sketchsurf needs, then configures and builds it.
# Idempotent and non-interactive; run as root (or with sudo available).
#   tools/setup.sh [--no-build] [--build-dir DIR] [--build-type TYPE] [-- extra cmake args]
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build_dir="$here/build"
build_type=Release
do_build=1
extra=()
while [ $# -gt 0 ]; do
  case "$1" in
    --no-build) do_build=0 ;;
    --build-dir) build_dir="$2"; shift ;;
    --build-type) build_type="$2"; shift ;;
    --) shift; extra=("$@"); break ;;
    -h|--help) sed -n '2,4p' "$0"; exit 0 ;;
    *) echo "setup.sh: unknown option '$1'" >&2; exit 2 ;;
  esac
  shift
done

packages=(
  build-essential cmake ninja-build pkg-config git
  libeigen3-dev libceres-dev libsuitesparse-dev libopenmesh-dev libspectra-dev libboost-graph-dev
  libzip-dev zlib1g-dev nlohmann-json3-dev libcli11-dev libstb-dev libmetis-dev libtinygltf-dev
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers glslang-tools libglfw3-dev libglm-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  python3-dev pybind11-dev python3-numpy python3-pytest python3-distributed  # python/ and its tests
  libimgui-dev xvfb xauth xdotool
  libopenxr-dev libopenxr-loader1 openxr-layer-corevalidation  # the headset (sketchsurf-studio --xr)
  clang-14 libclang-rt-14-dev  # the reader fuzzers (tools/fuzz): Clang and its libFuzzer runtime
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  echo "setup: installing ${missing[*]}" >&2
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
else
  echo "setup: all packages present" >&2
fi

if [ "$do_build" -eq 1 ]; then
  cmake -S "$here" -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE="$build_type" "${extra[@]}" >/dev/null
  cmake --build "$build_dir" -j "$(nproc)"
fi
