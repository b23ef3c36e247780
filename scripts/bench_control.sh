#!/usr/bin/env bash
# "Beyond the paper", parts 1 and 2: our resampler driven by an output size or by an error
# bound instead of the Gaussian sphere level, against CGAL's hierarchy and grid simplification
# and MeshLab's Poisson-disk simplification matched to the count ours gives (gsbench compare
# --target-percent / --max-error; bench/report.py --control-*).
#
#   scripts/bench_control.sh [--quick] [models...]
#
# models: names of ../shared/data/NAME.ply (default: every point set there, *_mesh.ply
# excluded). Absent ones are skipped with a reason.
#   (a) targets 5, 10, 20, 30 % of the input (ours: ResamplingParams::targetCount, level search
#       from n = 8) -> bench/results/control_targets.md/.csv
#   (b) error bounds 0.025, 0.01 and 0.002 x bbox diagonal at n = 8 (maxErrorFraction), plus the
#       metric's floor S' = S -> bench/results/control_error_bound.md/.csv
#   raw gsbench rows in bench/results/raw/control_{targets,error_bound}.csv, the machine and
#   its load in bench/results/raw/control_header.txt
#   --quick: sample_data bunny + fandisk, one timing run, into ${TMPDIR:-/tmp}/gsbench-control-quick
#
# Environment: BUILD_DIR (default <repo>/build-control), JOBS (default 2), RUNS (timed runs per
# figure, median; default 3), TARGETS (default "5 10 20 30"), POISSON_TARGETS (targets at which
# MeshLab Poisson runs; default: all of TARGETS), ERRORS (default "0.025 0.01 0.002").
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${BUILD_DIR:-$root/build-control}"
jobs="${JOBS:-2}"
targets="${TARGETS:-5 10 20 30}"
poisson_targets="${POISSON_TARGETS:-$targets}"
errors="${ERRORS:-0.025 0.01 0.002}"

source "$root/scripts/bench_common.sh"
bench_parse_args bench_control.sh 23 "$@"
bench_build_then_run_in_xvfb -DGAUSSPHERE_BUILD_TESTS=OFF -- "$@"

gsbench="$build/bench/gsbench"
meshlabserver="$build/stage/bin/meshlabserver"
bench_choose_inputs
bench_present_models control
if [ "$quick" = 1 ]; then out="${TMPDIR:-/tmp}/gsbench-control-quick"; else out="$root/bench/results"; fi

raw="$out/raw"
work="${TMPDIR:-/tmp}/gsbench-control-work"
mkdir -p "$raw" "$work"
rm -f "$raw/control_targets.csv" "$raw/control_error_bound.csv"
header="$raw/control_header.txt"
loads="$work/loads.txt"
: > "$loads"


bench_header "; ours with 1 thread (the metric uses every core)" > "$header"

compare() { # model, csv, methods, extra gsbench arguments...
  local name="$1" csv="$2" methods="$3"
  shift 3
  cut -d' ' -f1 /proc/loadavg >> "$loads"
  "$gsbench" compare "$data/$name.ply" --name "$name" --level 8 --threads 1 --runs "$runs" \
    --csv "$csv" --work "$work" --meshlabserver "$meshlabserver" --methods "$methods" "$@"
}

started=$SECONDS
for name in "${present[@]}"; do
  for t in $targets; do
    methods=ours,cgal-hierarchy,cgal-grid
    [[ " $poisson_targets " == *" $t "* ]] && methods+=",meshlab-poisson"
    echo "[control] (a) $name: target $t % at $((SECONDS - started)) s"
    compare "$name" "$raw/control_targets.csv" "$methods" --target-percent "$t"
  done
  for e in $errors; do
    echo "[control] (b) $name: error bound $e x diagonal at $((SECONDS - started)) s"
    compare "$name" "$raw/control_error_bound.csv" ours,cgal-hierarchy,cgal-grid,meshlab-poisson,floor --max-error "$e"
  done
done

{
  echo "Load average at end: $(cut -d' ' -f1-3 /proc/loadavg); 1-minute load sampled before each of the $(wc -l < "$loads") gsbench runs: min $(sort -g "$loads" | head -1), median $(sort -g "$loads" | awk '{v[NR]=$1} END {print v[int((NR+1)/2)]}'), max $(sort -g "$loads" | tail -1)."
  echo "Benchmark time $((SECONDS - started)) s. MeshLab Poisson at targets: $poisson_targets %."
} >> "$header"

python=python3
"$python" "$root/bench/report.py" --control-targets "$raw/control_targets.csv" \
  --control-error-bound "$raw/control_error_bound.csv" --out "$out" --header "$header"
echo "[control] done in $((SECONDS - started)) s: $out/control_targets.md, $out/control_error_bound.md"
