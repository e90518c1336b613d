#!/usr/bin/env bash
# One command from a fresh Debian 12 machine to the demo: installs what is
# missing, builds, and runs `curvenet demo` on the built-in default network.
# Output goes to demo-output/ (or the folder given as the first argument).
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$repo/tools/scripts/setup.sh"
build_dir=${CURVENET_BUILD_DIR:-$repo/build}
exec "$build_dir/tools/curvenet" demo --out "${1:-$repo/demo-output}"
