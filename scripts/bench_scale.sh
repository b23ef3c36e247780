#!/usr/bin/env bash
# Scaling benchmark of the resampler: builds bench/scale's gsscale in build-scale/ and runs
# it at 1, 5 and 20 million points (dragon densified in memory, default parameters), each
# size with 2 and 1 OpenMP threads, every measurement in a fresh process, then at an exact
# output size of 10 % (2 threads). Writes bench/scale/results.md and results.csv, and
# results_target.md and results_target.csv.
#
#   scripts/bench_scale.sh            full run (~8 minutes on 2 cores, peak RSS ~4.6 GB)
#   scripts/bench_scale.sh --quick    1 million points only (~15 s)
set -euo pipefail

root="$(cd "$(dirname "$0")/.." && pwd)"
build="$root/build-scale"
sizes=1000000,5000000,20000000
case "${1:-}" in
  --quick) sizes=1000000 ;;
  "") ;;
  *) echo "usage: $0 [--quick]" >&2; exit 2 ;;
esac

cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release \
      -DGAUSSPHERE_BUILD_PLUGINS=OFF -DGAUSSPHERE_BUILD_TESTS=OFF >/dev/null
cmake --build "$build" --target gsscale -j2

# The results describe the working tree that was built: say so when vcg_ext differs from HEAD.
commit="$(git -C "$root" rev-parse --short HEAD)"
git -C "$root" diff --quiet HEAD -- vcg_ext || commit="$commit + uncommitted vcg_ext changes"

"$build/bench/scale/gsscale" bench --sizes "$sizes" --threads 2,1 --commit "$commit" \
    --csv "$root/bench/scale/results.csv" --md "$root/bench/scale/results.md"
echo "wrote bench/scale/results.md and results.csv"

# An exact output size (TargetPercentage 10) at the same sizes, 2 threads: its merges and
# exchanges come on top of the level path (peak RSS ~4.6 GB at 20 million points).
"$build/bench/scale/gsscale" bench --sizes "$sizes" --threads 2 --target-percent 10 --commit "$commit" \
    --csv "$root/bench/scale/results_target.csv" --md "$root/bench/scale/results_target.md"
echo "wrote bench/scale/results_target.md and results_target.csv"
