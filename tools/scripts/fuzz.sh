#!/usr/bin/env bash
# Bounded fuzzing of every reader (networks and meshes), of the network
# builder, of model edits and of the C interface (libFuzzer, clang, ASan +
# UBSan), seeded from the built-ins and ../shared/data.
#   bash tools/scripts/fuzz.sh [SECONDS_PER_HARNESS]   # default 60
# Long runs: pass e.g. 3600; the corpora grow in build-fuzz/corpus/ and are
# reused by the next run. A finding stops the script with a non-zero exit and
# leaves crash-*/timeout-* files in build-fuzz/findings/; add each to
# tests/fuzz/regressions/<harness>/ once fixed (see tests/fuzz/README.md).
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
seconds=${1:-60}
dir=$repo/build-fuzz

CURVENET_EXTRA_PACKAGES="clang-14 libclang-rt-14-dev" bash "$repo/tools/scripts/setup.sh" --install-only
# -O1 with line tables: libFuzzer's recommendation, and a quicker build for CI.
# HWY_COMPILE_ONLY_STATIC and kernels/CMakeLists.txt: the harnesses drive the
# readers and the builder, not the SIMD kernels (tests/kernels_test.cpp checks
# every width, under ASan + UBSan in sanitize.sh), so the kernels are compiled
# for the baseline target only and without instrumentation; instrumented for
# every target they alone took four minutes to compile.
[ -f "$dir/CMakeCache.txt" ] || CC=clang-14 CXX=clang++-14 cmake -S "$repo" -B "$dir" -G Ninja \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG -DHWY_COMPILE_ONLY_STATIC=1" \
  -DCURVENET_BUILD_FUZZERS=ON -DCURVENET_BUILD_TOOLS=OFF -DCURVENET_BUILD_TESTS=OFF -DCURVENET_BUILD_BENCH=OFF \
  -DCURVENET_BUILD_PYTHON=OFF -DCURVENET_BUILD_SHARED=OFF -DCMAKE_UNITY_BUILD=ON
cmake --build "$dir" -j "$(nproc)"

corpus=$dir/corpus findings=$dir/findings
harnesses=(fuzz_network_json fuzz_lop fuzz_mesh fuzz_network_builder fuzz_model_edit fuzz_c_api fuzz_curve_graph)
for harness in "${harnesses[@]}"; do mkdir -p "$corpus/$harness"; done
mkdir -p "$findings"
"$dir/tests/fuzz/fuzz_seed_corpus" "$corpus/fuzz_network_json" "$corpus/fuzz_mesh"
shared=$repo/../shared/data/transfinite-models
if [ -d "$shared" ]; then cp -f "$shared"/*.lop "$corpus/fuzz_lop/"; fi
# Curve graphs: a cube's twelve edges as OBJ polylines, and the public sketches.
{
  printf 'v %s\n' "0 0 0" "1 0 0" "1 1 0" "0 1 0" "0 0 1" "1 0 1" "1 1 1" "0 1 1"
  printf 'l %s\n' "1 2" "2 3" "3 4" "4 1" "5 6" "6 7" "7 8" "8 5" "1 5" "2 6" "3 7" "4 8"
} >"$corpus/fuzz_curve_graph/cube.obj"
sketches=$repo/../shared/data/sketches
if [ -d "$sketches" ]; then cp -f "$sketches"/*.obj "$corpus/fuzz_curve_graph/"; fi

export ASAN_OPTIONS=detect_leaks=0
for harness in "${harnesses[@]}"; do
  regressions=$repo/tests/fuzz/regressions/$harness
  # Past findings first: they must all pass now.
  if [ -d "$regressions" ] && [ -n "$(ls -A "$regressions")" ]; then
    "$dir/tests/fuzz/$harness" -runs=0 "$regressions"/* >/dev/null 2>&1 ||
      { echo "fuzz: $harness fails on a recorded regression input" >&2; exit 1; }
  fi
done

# The harnesses are single-threaded: run them side by side, each for the given
# wall time, so the run takes SECONDS rather than seven times as long. The
# slowest inputs take ~15 s on a whole core: 90 s per input leaves room for
# sharing two cores seven ways and still stops a real hang.
echo "fuzz: ${harnesses[*]} side by side for ${seconds}s each"
pids=()
for harness in "${harnesses[@]}"; do
  "$dir/tests/fuzz/$harness" "$corpus/$harness" -max_total_time="$seconds" -timeout=90 -rss_limit_mb=4096 \
    -max_len=65536 -artifact_prefix="$findings/$harness-" -print_final_stats=1 2>"$findings/$harness.log" &
  pids+=($!)
done
failed=0
for i in "${!harnesses[@]}"; do
  harness=${harnesses[$i]}
  if wait "${pids[$i]}"; then
    echo "fuzz: $harness"
    grep -E "^(Done|stat::number_of_executed_units)" "$findings/$harness.log" || true
  else
    echo "fuzz: $harness found a fault; see $findings/$harness.log" >&2
    tail -30 "$findings/$harness.log" >&2
    failed=1
  fi
done
exit $failed
