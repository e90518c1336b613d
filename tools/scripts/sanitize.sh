#!/usr/bin/env bash
# The whole test suite under AddressSanitizer + UndefinedBehaviorSanitizer,
# then under ThreadSanitizer (with the renderer and the program, whose
# tests run it), both less the sweeps of one property over every built-in
# (see below). Separate build folders; incremental after the first run.
#   bash tools/scripts/sanitize.sh            # both
#   bash tools/scripts/sanitize.sh address    # ASan + UBSan only
#   bash tools/scripts/sanitize.sh thread     # TSan only
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
which=${1:-all}
jobs=$(nproc)
# -O1 with line tables only: what the sanitizers recommend, and builds about a
# third faster than -O2 -g, which keeps both parts inside CI's time.
flags=(-DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG"
       "-DCMAKE_C_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG" -DCURVENET_BUILD_BENCH=OFF
       # Debian's python3 cannot load an instrumented module, and the shared
       # library's tests build outside programs without sanitizers.
       -DCURVENET_BUILD_PYTHON=OFF -DCURVENET_BUILD_SHARED=OFF
       # Unity builds (setup.sh): the program's commands compile in under half
       # the time, the engine in ~10 % less.
       -DCMAKE_UNITY_BUILD=ON)

# The sweeps of one property over every built-in:
# races and memory errors live in code paths, not in data, and these sweeps
# run the same code as the tests that take one network through it; they run
# whole in the Release suite (tools/test.sh). Left out under ASan they save
# ~460 of the part's ~925 s of test time, under TSan ~700 of ~1 380 s
# (measured on 2 cores). The sweeps over the public sketches stay under ASan:
# real data is where a reader or builder meets what the built-ins never ask.
builtin_sweeps='Embed.JetBatchesAgreeWithPointwiseEvaluationOnEveryBuiltin|Schemes/PlannedPositions|Builtins/PartialRebuildOf'
builtin_sweeps+='|Schemes/BatchEvaluation|MeshApproximation.G2BeatsG1OnTriangulatedBuiltins|AllBuiltins/G1Surface'
builtin_sweeps+='|Builtins/ToleranceTessellation|All/G2Builtin'
builtin_sweeps+='|PlannedTessellation.MatchesPointwiseEvaluationOnEveryBuiltinAndScheme'
builtin_sweeps+='|RibbonTable.MatchesExactRibbonsOfEveryBuiltin|Curvature.EveryBuiltin'
sketch_sweeps='RibbonTable.EverySketchSide|RobustnessCorpus.SharedSketches'

# Packages are the same as for the normal build.
CURVENET_BUILD_DIR=$repo/build bash "$repo/tools/scripts/setup.sh" --install-only

if [[ $which == all || $which == address ]]; then
  dir=$repo/build-asan
  [ -f "$dir/CMakeCache.txt" ] || cmake -S "$repo" -B "$dir" -G Ninja "${flags[@]}" \
    -DCURVENET_SANITIZE=address,undefined
  cmake --build "$dir" -j "$jobs"
  # Embree and TBB allocate thread-local pools they never free: leaks are not
  # this project's findings; every other ASan/UBSan report fails the test.
  ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    ctest --test-dir "$dir" --output-on-failure -j "$jobs" -E "$builtin_sweeps"
fi

if [[ $which == all || $which == thread ]]; then
  dir=$repo/build-tsan
  # Configured every time: a folder from before the renderer joined keeps
  # its tools switched off otherwise.
  # The SIMD kernels for the baseline instruction set only: races are between
  # the parallel loops that call them on their own parts of a buffer, the same
  # for every width; every width is checked under ASan and in the Release suite.
  cmake -S "$repo" -B "$dir" -G Ninja "${flags[@]}" -DCURVENET_SANITIZE=thread -DCURVENET_BUILD_TOOLS=ON \
    -DCMAKE_CXX_FLAGS=-DHWY_COMPILE_ONLY_STATIC=1 >/dev/null
  cmake --build "$dir" -j "$jobs"
  # TBB's own synchronization is not visible to TSan in the Debian build;
  # tests/tsan.supp lists those library frames, nothing of ours.
  # The sketch sweeps too (their parallel code is the one Sketch.* and
  # ToleranceTessellation.CreasesOfARealSketch* take one sketch through), and
  # the sweep solver's over every kernel width, compiled here for one.
  TSAN_OPTIONS="halt_on_error=1 suppressions=$repo/tests/tsan.supp" \
    ctest --test-dir "$dir" --output-on-failure -j "$jobs" -E "$builtin_sweeps|$sketch_sweeps|Kernels.SweepSolverMatches"
fi
