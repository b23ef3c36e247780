#!/usr/bin/env bash
# scripts/sanitize.sh [CTEST ARGS...]
# The sanitizer suite: builds the algorithm, error-metric and gstile tests and gsresample with
# AddressSanitizer + UndefinedBehaviorSanitizer (GAUSSPHERE_SANITIZE=ON, gcc, -O1 with
# assertions on, plugins off) in $SANITIZE_BUILD_DIR (default build-sanitize/), runs the tests,
# then gsresample on sample_data/fandisk.ply in its three output-size modes. Any sanitizer
# report fails the run. One summary line at the end. Debug information is line tables only
# (-g1): reports keep their files and lines, and the build is much shorter than with -g.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${SANITIZE_BUILD_DIR:-$here/build-sanitize}"
jobs="${JOBS:-$(nproc)}"
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=0:strict_string_checks=1:detect_stack_use_after_return=1}"
export LSAN_OPTIONS="${LSAN_OPTIONS:-suppressions=$here/tests/lsan_suppressions.txt:print_suppressions=0}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"

start=$SECONDS
cmake -S "$here" -B "$build" -DCMAKE_BUILD_TYPE=Debug "-DCMAKE_C_FLAGS_DEBUG=-O1 -g1" "-DCMAKE_CXX_FLAGS_DEBUG=-O1 -g1" \
  -DGAUSSPHERE_SANITIZE=ON -DGAUSSPHERE_BUILD_PLUGINS=OFF -DGAUSSPHERE_BUILD_TESTS=ON \
  -DGAUSSPHERE_BUILD_BENCH=OFF >/dev/null
cmake --build "$build" -j "$jobs" --target test_gaussphere_algorithm test_surfel_error gstile_test gsresample
built=$((SECONDS - start))

# gstile's GoogleTest cases; its command-line runs (tiled_vs_whole, the Dask cluster) need the
# Release tools and run in the release stage.
(cd "$build" && ctest --output-on-failure -j "$jobs" -L 'algorithm|error|tile' -E 'tiled_vs_whole|dask_cluster' "$@" |
  tee ctest.log)
summary=$(grep -E 'tests passed, [0-9]+ tests failed out of' "$build/ctest.log" | tail -1)

runs="$build/gsresample-runs"
mkdir -p "$runs"
for mode in "" "--target 1000" "--max-error 0.002"; do
  # shellcheck disable=SC2086  # $mode is an option and its value
  "$build/tools/gsresample/gsresample" "$here/sample_data/fandisk.ply" "$runs/fandisk.surfel" $mode >"$runs/log" 2>&1 ||
    { cat "$runs/log" >&2; echo "[sanitize] FAILED: gsresample fandisk.ply ${mode:-(defaults)}"; exit 1; }
done
echo "[sanitize] ok: ${summary}; gsresample 3 runs; build ${built} s, total $((SECONDS - start)) s"
