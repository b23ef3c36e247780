#!/usr/bin/env bash
# scripts/fuzz.sh [SECONDS_PER_TARGET]  (default 60)
# Builds the libFuzzer targets of tests/fuzz (clang-14, ASan + UBSan, GAUSSPHERE_FUZZ=ON) in
# $FUZZ_BUILD_DIR (default build-fuzz/), replays each target's regression inputs and seed
# corpus, then fuzzes each target for SECONDS_PER_TARGET seconds, the targets side by side. New corpus entries stay in
# the build folder (the committed seeds are not touched). A failing input is copied into
# tests/fuzz/regressions/<target>/, so that it is replayed from then on; commit it.
# Exit status: 0 when no target failed. One summary line per target and one in total.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
seconds="${1:-60}"
build="${FUZZ_BUILD_DIR:-$here/build-fuzz}"
jobs="${JOBS:-$(nproc)}"
export LSAN_OPTIONS="${LSAN_OPTIONS:-suppressions=$here/tests/lsan_suppressions.txt:print_suppressions=0}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1}"

start=$SECONDS
cmake -S "$here" -B "$build" -DCMAKE_C_COMPILER=clang-14 -DCMAKE_CXX_COMPILER=clang++-14 \
  -DCMAKE_BUILD_TYPE=Debug "-DCMAKE_C_FLAGS_DEBUG=-O1 -g" "-DCMAKE_CXX_FLAGS_DEBUG=-O1 -g" \
  -DGAUSSPHERE_FUZZ=ON -DGAUSSPHERE_BUILD_PLUGINS=OFF -DGAUSSPHERE_BUILD_TESTS=OFF \
  -DGAUSSPHERE_BUILD_BENCH=OFF >/dev/null
cmake --build "$build" -j "$jobs" --target fuzz_targets
echo "[fuzz] built in $((SECONDS - start)) s"

# fuzz_one NAME PROGRAM CORPUS REGRESSIONS: replays the kept inputs, then fuzzes; prints its
# summary line and writes the number of executions into fuzz-work/NAME/runs. Status 1 on failure.
fuzz_one() {
  local name=$1 program=$2 corpus=$3 regressions=$4
  local work="$build/fuzz-work/$name"
  mkdir -p "$work/corpus" "$work/artifacts"
  local log="$work/fuzz.log"
  echo 0 >"$work/runs"

  # Every kept input once; given files, libFuzzer runs each and names it ("Running: FILE").
  if ! "$program" -artifact_prefix="$work/replay-" "$regressions"/* "$corpus"/* >"$work/replay.log" 2>&1; then
    grep -m1 -B 2 -A 30 -E '^==[0-9]+==ERROR|runtime error|deadly signal' "$work/replay.log" >&2 || tail -n 40 "$work/replay.log" >&2
    echo "[fuzz] $name: FAILED on $(sed -n 's/^Running: //p' "$work/replay.log" | tail -1) (log: $work/replay.log)"
    return 1
  fi

  rm -f "$work/artifacts/"*
  local status=0
  "$program" "$work/corpus" "$corpus" "$regressions" -max_total_time="$seconds" -timeout=30 \
    -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix="$work/artifacts/" >"$log" 2>&1 || status=$?
  local runs
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  echo "${runs:-0}" >"$work/runs"
  local found=("$work/artifacts/"*)
  if [ "$status" -ne 0 ] || [ -e "${found[0]}" ]; then
    for f in "${found[@]}"; do
      [ -e "$f" ] && cp "$f" "$regressions/" && echo "[fuzz] $name: kept $(basename "$f") in $regressions"
    done
    grep -m1 -A 30 -E '^==[0-9]+==ERROR|runtime error|^ALARM|^==[0-9]+== ERROR|deadly signal' "$log" >&2 || tail -n 40 "$log" >&2
    echo "[fuzz] $name: FAILED after ${runs:-0} executions in ${seconds} s (log: $log)"
    return 1
  fi
  echo "[fuzz] $name: ok, ${runs:-0} executions in ${seconds} s, corpus $(ls "$work/corpus" | wc -l) files"
}

# The targets fuzz side by side (libFuzzer runs one process on one core each).
pids=()
names=()
while read -r name program corpus regressions; do
  [ -n "$name" ] || continue
  fuzz_one "$name" "$program" "$corpus" "$regressions" &
  pids+=("$!")
  names+=("$name")
done <"$build/fuzz_targets.txt"
failed=0
total_runs=0
for i in "${!pids[@]}"; do
  wait "${pids[$i]}" || failed=1
  total_runs=$((total_runs + $(cat "$build/fuzz-work/${names[$i]}/runs")))
done

if [ "$failed" -ne 0 ]; then
  echo "[fuzz] FAILED: see above ($((SECONDS - start)) s)"
  exit 1
fi
echo "[fuzz] ok: $(wc -l <"$build/fuzz_targets.txt") targets, $total_runs executions, no failure ($((SECONDS - start)) s)"
