#!/usr/bin/env bash
# Prints every deterministic table of README.md and docs/*.md (continuity,
# deviation, counts) as the build computes it; --check compares them with the
# documents (what the test docs.figures runs), --update rewrites them there.
#   bash tools/scripts/figures.sh [--check | --update] [--only NAME,...]
# Builds the curvenet_figures program into build/ (CURVENET_BUILD_DIR) first.
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
build_dir=${CURVENET_BUILD_DIR:-$repo/build}
if [ ! -f "$build_dir/CMakeCache.txt" ]; then
  cmake -S "$repo" -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
fi
cmake --build "$build_dir" --target curvenet_figures >/dev/null
exec "$build_dir/tools/figures/curvenet_figures" --repo "$repo" "$@"
