#!/usr/bin/env bash
# Shared set-up for tools/demo.sh and tools/test.sh: installs the Debian
# packages curvenet needs (only the missing ones, so a second run is quick),
# then configures and builds into build/ (incremental after the first run).
set -euo pipefail

repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
build_dir=${CURVENET_BUILD_DIR:-$repo/build}

packages=(
  build-essential cmake ninja-build pkg-config mold
  libtbb-dev libeigen3-dev libembree-dev libopenimageio-dev
  libbenchmark-dev libgtest-dev libgmock-dev libhwy-dev nlohmann-json3-dev libcli11-dev
  python3-dev pybind11-dev python3-numpy python3-pytest
)

# Extra packages for the sanitizer and fuzzing scripts (e.g. clang).
read -r -a extra <<< "${CURVENET_EXTRA_PACKAGES:-}"
packages+=("${extra[@]}")

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "curvenet setup: installing ${missing[*]}"
  if [ "$(id -u)" -eq 0 ]; then sudo=(); elif command -v sudo >/dev/null; then sudo=(sudo); else
    echo "curvenet setup: need root (or sudo) to install: ${missing[*]}" >&2
    exit 1
  fi
  export DEBIAN_FRONTEND=noninteractive
  "${sudo[@]}" apt-get update -qq
  "${sudo[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# --install-only: the packages, no build (used by the sanitizer and fuzz scripts).
if [ "${1:-}" = "--install-only" ]; then exit 0; fi

# A unity build (each target's sources compiled a few at a time as one file)
# builds from scratch in about three quarters of the time, mostly because the
# program's commands parse and instantiate CLI11 once per batch instead of
# once per file. For incremental work configure a folder of your own without it.
if [ ! -f "$build_dir/CMakeCache.txt" ]; then
  cmake -S "$repo" -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_UNITY_BUILD=ON
fi
cmake --build "$build_dir" -j "$(nproc)"
