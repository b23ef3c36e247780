# Shared by the benchmark scripts that drive gsbench (bench.sh, bench_control.sh): arguments,
# build, inputs, header. Sourced,
# with `root`, `build` and `jobs` set by the caller.

# Every measured process, ours and the peers, runs with transparent huge pages for its heap
# (README: Install): the setting is the host's, and the same for each.
export GLIBC_TUNABLES=glibc.malloc.hugetlb=1

# bench_parse_args SCRIPT_NAME HELP_LINES ARGS...: sets `quick` (0/1) and `models` (names).
bench_parse_args() {
  local name=$1 help_lines=$2
  shift 2
  quick=0
  models=()
  for arg in "$@"; do
    case "$arg" in
      --quick) quick=1 ;;
      -h|--help) sed -n "2,${help_lines}p" "$0"; exit 0 ;;
      -*) echo "$name: unknown option $arg" >&2; exit 2 ;;
      *) models+=("$arg") ;;
    esac
  done
}

# bench_build_then_run_in_xvfb CMAKE_OPTIONS... -- ARGS...: builds gsbench and the staged
# MeshLab (and the targets in `bench_extra_targets`, if the caller sets it), then re-runs the
# calling script inside one virtual display (meshlabserver needs one); a build error stays
# visible, outside xvfb-run.
bench_build_then_run_in_xvfb() {
  local options=()
  while [ $# -gt 0 ] && [ "$1" != -- ]; do options+=("$1"); shift; done
  shift
  [ -n "${GSBENCH_IN_XVFB:-}" ] && return 0
  if [ ! -f "$build/CMakeCache.txt" ]; then
    cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release "${options[@]}"
  fi
  cmake --build "$build" --target gsbench stage ${bench_extra_targets[@]+"${bench_extra_targets[@]}"} -j "$jobs"
  GSBENCH_IN_XVFB=1 exec xvfb-run -a -s "-screen 0 1280x1024x24" "$0" "$@"
}

# bench_all_models DATA_DIR: every point set in DATA_DIR, the paper's models first.
bench_all_models() {
  local data=$1 name
  models=(dragon igea bunny horse armadillo_43k maxplanck_25k buddha_res3 dragon_res2 fandisk rocker_arm)
  for f in "$data"/*.ply; do
    name="$(basename "$f" .ply)"
    case "$name" in *_mesh) continue ;; esac
    [[ " ${models[*]} " == *" $name "* ]] || models+=("$name")
  done
}

# bench_choose_inputs: sets `data`, `runs` and, unless given, `models` for the quick run
# (shipped samples, one timed run) or the full one (../shared/data, RUNS or 3 timed runs).
bench_choose_inputs() {
  if [ "$quick" = 1 ]; then
    data="$root/sample_data"
    runs="${RUNS:-1}"
    [ ${#models[@]} -gt 0 ] || models=(bunny fandisk)
  else
    data="$root/../shared/data"
    runs="${RUNS:-3}"
    [ ${#models[@]} -gt 0 ] || bench_all_models "$data"
  fi
}

# bench_present_models TAG: sets `present` to the `models` found in `data` as point sets,
# saying why each other one is skipped; stops when none is left.
bench_present_models() {
  local tag=$1 name
  present=()
  for name in "${models[@]}"; do
    case "$name" in *_mesh) echo "[$tag] skip $name: a mesh file, not a point set"; continue ;; esac
    if [ -f "$data/$name.ply" ]; then present+=("$name")
    else echo "[$tag] skip $name: $data/$name.ply not found"; fi
  done
  [ ${#present[@]} -gt 0 ] || { echo "[$tag] no model found in $data" >&2; exit 1; }
}

# bench_header RUNS_NOTE: the lines naming the run, the machine and the code measured.
bench_header() {
  echo "Run $(date -u '+%Y-%m-%d %H:%M UTC') at commit $(git -C "$root" rev-parse --short HEAD)"
  echo "on $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//'), $(nproc) cores,"
  echo "load average at start: $(cut -d' ' -f1-3 /proc/loadavg) (the machine is shared: times are indicative)."
  echo "Timed runs per figure: $runs (median)$1."
  # The build uses the working tree: say so when the measured code is not the commit's.
  local dirty
  dirty="$(git -C "$root" status --porcelain -- vcg_ext | awk '{print $2}' | tr '\n' ' ')"
  [ -z "$dirty" ] || echo "Built with uncommitted changes in: $dirty"
}
