#!/usr/bin/env bash
# Splat sizes of a raw 5-million-point cloud: the project's grid (splat::nearestNeighbourRadii)
# against vcglib's kd-tree, measured in one run by splat_frames_bench (frames_bench.cpp).
# Usage: bench/render/frames_bench.sh [BUILD_DIR] [splat_frames_bench options]
#   BUILD_DIR defaults to build/; it is configured with the plugins and benchmarks on and only
#   the target splat_frames_bench is built. Options go to the program (--points N, --ply FILE,
#   --k K, --repeat R; default 5,000,000 generated points, k = 8, 1 repetition).
# Prints the program's CSV rows and writes them to bench/render/frames_results.csv.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/../.." && pwd)"
build="${1:-$root/build}"
[ $# -gt 0 ] && shift
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DGAUSSPHERE_BUILD_PLUGINS=ON -DGAUSSPHERE_BUILD_BENCH=ON >/dev/null
cmake --build "$build" -j2 --target splat_frames_bench >/dev/null
"$build/bench/render/splat_frames_bench" "$@" | tee "$here/frames_results.csv"
