#!/usr/bin/env bash
# scripts/test.sh [CTEST ARGS...]
# Sets up (Debian packages, MeshLab source), then runs every stage and prints one line each:
#   release   builds everything (Release) and runs every test, including the end-to-end runs
#             of meshlabserver and the GUI under Xvfb; CTEST ARGS go to this ctest
#   sanitize  scripts/sanitize.sh: the algorithm tests, the error-metric tests and gsresample as
#             a Debug build (assertions on, -O1) under ASan + UBSan
#   fuzz      scripts/fuzz.sh: each fuzz target for $FUZZ_SECONDS seconds (default 60)
#   hosts     the plugins in MeshLab 2022.02 (Debian 13, in a trixie root made once by
#             scripts/hosts/trixie_root.sh): the filter, the .surfel round trip and the surfel error
#             filter through MeshLab's own plugin loader, Ellipse Splatting in its GUI under Xvfb;
#             the .deb packages for Debian 12 and 13 built, installed into clean roots, used and
#             removed (scripts/package.sh, scripts/hosts/deb_test.sh); the same checks in
#             MeshLab 2025.07, built once per machine from ../shared's source
#             (scripts/hosts/meshlab2025.sh; HOSTS_2025=0 leaves 2025.07 out). The roots and the
#             2025.07 build it needs are made (once per machine) while the stages before it run.
#   debug     (not in the default: sanitize builds the same targets as Debug) compiles them at -O0
# STAGES="release sanitize fuzz hosts" (the default) picks stages. Every stage runs even when
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

# What the hosts stage needs from outside the project is made once per machine, in the background
# from the start, while the other stages run, as three jobs: the Debian 13 root (network and
# disk), then MeshLab 2025.07 in it (its build runs at nice 15, in the CPU the other stages leave
# idle); and the two clean roots for the package checks, side by side with them. The stage uses
# each as soon as it is there: MeshLab 2022.02's checks and the packages first, 2025.07's last.
start_host_deps() {
  local hosts="$here/scripts/hosts"
  mkdir -p "$build"
  "$hosts/trixie_root.sh" > "$build/hosts-root.log" 2>&1 &
  root_job=$!
  { "$hosts/clean_root.sh" bookworm && "$hosts/clean_root.sh" trixie; } > "$build/hosts-clean-roots.log" 2>&1 &
  clean_roots_job=$!
  if [ "${HOSTS_2025:-1}" != 0 ]; then
    "$hosts/meshlab2025.sh" > "$build/hosts-meshlab2025.log" 2>&1 &
    meshlab2025_job=$!
  fi
}

# host_dep_ready JOB LOG: waits for a background job of start_host_deps; prints its log if it failed.
host_dep_ready() { wait "$1" || { cat "$2"; return 1; }; }

host_checks() { # VERSION: every end-to-end check in that MeshLab
  local check
  for check in filter_e2e io_e2e render_e2e gui_e2e; do "$here/scripts/hosts/$check.sh" "$1" || return 1; done
}

stage_hosts() {
  local hosts="$here/scripts/hosts"
  host_dep_ready "$root_job" "$build/hosts-root.log" && host_checks 2022.02 &&
    host_dep_ready "$clean_roots_job" "$build/hosts-clean-roots.log" &&
    BUILD_DIR="$build" bash "$here/scripts/package.sh" bookworm trixie &&
    "$hosts/deb_test.sh" bookworm && "$hosts/deb_test.sh" trixie || return 1
  [ "${HOSTS_2025:-1}" = 0 ] ||
    { host_dep_ready "$meshlab2025_job" "$build/hosts-meshlab2025.log" && host_checks 2025.07; }
}

stage_sanitize() { bash "$here/scripts/sanitize.sh"; }

stage_fuzz() { bash "$here/scripts/fuzz.sh" "${FUZZ_SECONDS:-60}"; }

bash "$here/scripts/setup.sh" || exit 1
case " ${STAGES:-release sanitize fuzz hosts} " in *" hosts "*) start_host_deps ;; esac
summary=()
failed=0
for stage in ${STAGES:-release sanitize fuzz hosts}; do
  start=$SECONDS
  if [ "$stage" = release ]; then stage_release "$@"; else "stage_$stage"; fi
  status=$?
  result=ok
  if [ "$status" -ne 0 ]; then result="FAILED (status $status)"; failed=1; fi
  summary+=("[test] $stage: $result in $((SECONDS - start)) s")
  echo "${summary[-1]}"
done
# A stage that failed early can leave background jobs of start_host_deps running: they stop with
# the run (an interrupted MeshLab 2025.07 build resumes where it stopped next time).
for job in $(jobs -pr); do pkill -TERM -P "$job" 2>/dev/null; kill "$job" 2>/dev/null; done
echo "[test] summary:"
printf '%s\n' "${summary[@]}"
exit "$failed"
