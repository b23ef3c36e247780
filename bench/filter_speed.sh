#!/usr/bin/env bash
# The whole resampling filter through meshlabserver against CGAL's hierarchy clustering at the
# same count, measured side by side in one run: dragon and igea at level 8.
#   bash bench/filter_speed.sh [BUILD_DIR] [ROUNDS]      (default build/, 5 rounds)
# Per model: the filter's own figure for its whole run and for the part around the algorithm
# (its log line "the whole filter took"), the algorithm's neighbour search (its stage time),
# nanoflann's kd-tree finding the same 16 nearest neighbours of every point (gsbench knn: the
# paper's first step by a standard library) and CGAL's hierarchy at our count (gsbench compare,
# in process, matched to ours' count), each the median over the rounds, alternating.
# Prints a markdown table with the ratios and the absolute times, stamped with the commit, and
# writes it to bench/results/filter_speed.md (docs/results.md quotes it).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="$(realpath "${1:-$here/build}")"
rounds="${2:-5}"
# Huge pages for both processes' heaps (README: Install): the same host setting for each.
export GLIBC_TUNABLES=glibc.malloc.hugetlb=1
data="${SHARED_DATA_DIR:-$here/../shared/data}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
server="$build/stage/bin/meshlabserver"
gsbench="$build/bench/gsbench"
[ -x "$server" ] && [ -x "$gsbench" ] || { echo "build the stage and gsbench targets in $build first" >&2; exit 1; }
median() { sort -g | awk '{v[NR]=$1} END {print (NR % 2) ? v[(NR+1)/2] : (v[NR/2] + v[NR/2+1]) / 2}'; }
{
echo "| model | surfels | whole filter (s) | around the algorithm (s, % of it) | its neighbour search (s) | nanoflann 16 nearest (s) | CGAL hierarchy (s) | filter / hierarchy |"
echo "|---|---|---|---|---|---|---|---|"
for model in dragon igea; do
  input="$data/$model.ply"
  : > "$work/filter.txt"; : > "$work/around.txt"; : > "$work/neighbours.txt"; : > "$work/nanoflann.txt"
  : > "$work/hierarchy.txt"
  for round in $(seq "$rounds"); do
    OMP_NUM_THREADS=2 xvfb-run -a -s "-screen 0 1280x1024x24" "$server" -i "$input" \
      -s "$here/sample_data/resample_level8.mlx" -o "$work/out.ply" > "$work/run.log" 2>&1
    count=$(sed -n 's/.*points -> \([0-9]*\) surfels.*/\1/p' "$work/run.log" | head -1)
    sed -n 's/.*the whole filter took \([0-9.]*\) s, \([0-9.]*\) s of it around.*/\1 \2/p' "$work/run.log" |
      head -1 > "$work/line.txt"
    read -r whole around < "$work/line.txt"
    echo "$whole" >> "$work/filter.txt"
    echo "$around" >> "$work/around.txt"
    sed -n 's/.*(neighbours \([0-9.]*\),.*/\1/p' "$work/run.log" | head -1 >> "$work/neighbours.txt"
    "$gsbench" knn "$input" --k 16 --threads 2 --runs 1 >> "$work/nanoflann.txt"
    # Ours in process at level 8, CGAL's hierarchy matched to its count.
    rm -f "$work/hierarchy.csv"
    "$gsbench" compare "$input" --name "$model" --methods ours,cgal-hierarchy --threads 2 --runs 1 \
      --csv "$work/hierarchy.csv" --work "$work/gsbench" > /dev/null 2>&1
    awk -F, '$4 == "cgal-hierarchy" {print $11}' "$work/hierarchy.csv" >> "$work/hierarchy.txt"
  done
  whole=$(median < "$work/filter.txt"); around=$(median < "$work/around.txt")
  neighbours=$(median < "$work/neighbours.txt"); nanoflann=$(median < "$work/nanoflann.txt")
  hierarchy=$(median < "$work/hierarchy.txt")
  awk -v m="$model" -v c="$count" -v w="$whole" -v a="$around" -v n="$neighbours" -v f="$nanoflann" \
      -v h="$hierarchy" 'BEGIN {
    printf "| %s | %d | %.3f | %.3f (%.1f %%) | %.3f | %.3f | %.3f | %.2f |\n", m, c, w, a, 100 * a / (w - a), n, f, h, w / h }'
done
echo
echo "commit $(git -C "$here" rev-parse --short HEAD), $rounds rounds, $(nproc) CPUs, load $(cut -d' ' -f1-3 /proc/loadavg), $(date -u +%F)"
} | tee "$here/bench/results/filter_speed.md"
