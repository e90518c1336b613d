#!/usr/bin/env bash
# One command from a fresh Debian 12 machine to a passing test suite:
# installs what is missing, builds, and runs every test with ctest.
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$repo/tools/scripts/setup.sh"
build_dir=${CURVENET_BUILD_DIR:-$repo/build}
exec ctest --test-dir "$build_dir" --output-on-failure -j "$(nproc)" "$@"
