#!/usr/bin/env bash
# scripts/test.sh [CTEST ARGS...]
# Sets up (Debian packages, MeshLab source), then runs every stage and prints one line each:
#   release   builds everything (Release) and runs every test, including the end-to-end runs
#             of meshlabserver and the GUI under Xvfb; CTEST ARGS go to this ctest
#   debug     compiles the algorithm tests, the error-metric tests and gsresample as Debug (-O0)
#   sanitize  scripts/sanitize.sh: those tests and gsresample under ASan + UBSan
#   fuzz      scripts/fuzz.sh: each fuzz target for $FUZZ_SECONDS seconds (default 60)
# STAGES="release debug sanitize fuzz" (the default) picks stages. Every stage runs even when
# one before it failed; the exit status is 0 only when all passed.
set -uo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${BUILD_DIR:-$here/build}"

stage_release() {
  cmake -S "$here" -B "$build" -DCMAKE_BUILD_TYPE=Release -DGAUSSPHERE_BUILD_PLUGINS=ON \
    -DGAUSSPHERE_BUILD_TESTS=ON >/dev/null &&
    cmake --build "$build" -j "$(nproc)" &&
    (cd "$build" && ctest --output-on-failure -j 2 "$@")
}

# Debug builds catch what optimisation hides: missing definitions of odr-used constants,
# assertions that do not compile.
stage_debug() {
  local debug="${DEBUG_BUILD_DIR:-$here/build-debug}"
  cmake -S "$here" -B "$debug" -DCMAKE_BUILD_TYPE=Debug -DGAUSSPHERE_BUILD_PLUGINS=OFF \
    -DGAUSSPHERE_BUILD_TESTS=ON -DGAUSSPHERE_BUILD_BENCH=OFF >/dev/null &&
    cmake --build "$debug" -j "$(nproc)" --target test_gaussphere_algorithm test_surfel_error gsresample
}

stage_sanitize() { bash "$here/scripts/sanitize.sh"; }

stage_fuzz() { bash "$here/scripts/fuzz.sh" "${FUZZ_SECONDS:-60}"; }

bash "$here/scripts/setup.sh" || exit 1
summary=()
failed=0
for stage in ${STAGES:-release debug sanitize fuzz}; do
  start=$SECONDS
  if [ "$stage" = release ]; then stage_release "$@"; else "stage_$stage"; fi
  status=$?
  result=ok
  if [ "$status" -ne 0 ]; then result="FAILED (status $status)"; failed=1; fi
  summary+=("[test] $stage: $result in $((SECONDS - start)) s")
  echo "${summary[-1]}"
done
echo "[test] summary:"
printf '%s\n' "${summary[@]}"
exit "$failed"
