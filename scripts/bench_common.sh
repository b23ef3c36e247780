# Shared by the benchmark scripts that drive gsbench (bench.sh, bench_control.sh); sourced,
# with `root`, `build` and `jobs` set by the caller.

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
# MeshLab, then re-runs the calling script inside one virtual display (meshlabserver needs
# one); a build error stays visible, outside xvfb-run.
bench_build_then_run_in_xvfb() {
  local options=()
  while [ $# -gt 0 ] && [ "$1" != -- ]; do options+=("$1"); shift; done
  shift
  [ -n "${GSBENCH_IN_XVFB:-}" ] && return 0
  if [ ! -f "$build/CMakeCache.txt" ]; then
    cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release "${options[@]}"
  fi
  cmake --build "$build" --target gsbench stage -j "$jobs"
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
