#!/usr/bin/env bash
# Tiled resampling at scale (bench/tile/README.md):
#   bench/tile/bench_tile.sh WORK_DIR compare   # whole vs tiled at 5 and 20 million points
#   bench/tile/bench_tile.sh WORK_DIR big       # 200 million points from disk, 1 and 2 Dask workers
#   bench/tile/bench_tile.sh WORK_DIR target    # the dragon at five target counts, whole vs tiled
#   bench/tile/bench_tile.sh WORK_DIR bound     # the dragon at two error bounds, whole vs tiled
#   bench/tile/bench_tile.sh WORK_DIR flat      # whole vs tiled on flat faces: the drilled box at 5
#                                               # and 20 million points
#   bench/tile/bench_tile.sh WORK_DIR halo      # the dragon in 13 tiles at halo widths 1-32 spacings
#                                               # (PARTS=n: n x 20 million instead of 10)
# Inputs: the dragon densified by gsscale (bench/scale); 200 million = ten samplings of 20 million
# (seeds 1-10) concatenated. Every tile's run goes through a wrapper that caps its address space
# (MEMORY_CAP_KIB, default 4 GiB) and records its peak RSS. Writes key=value lines into
# WORK_DIR/*.txt and prints them. Needs a Release build in build/ (gsresample, gstile,
# gstile_compare, gsscale) and about 20 GB of disk for `big`. The lines, after a stamp (commit, date,
# machine, load), also go to bench/tile/results/STAGE.txt, which bench/results_doc.py reads.
set -euo pipefail
here=$(cd "$(dirname "$0")/../.." && pwd)
work=$(mkdir -p "$1" && cd "$1" && pwd)
stage=$2
bin=$here/build
gsscale=$bin/bench/scale/gsscale gstile=$bin/tools/gstile/gstile
cap=${MEMORY_CAP_KIB:-4194304}
cd "$work"

measure() { # NAME COMMAND...: wall seconds and peak RSS (MiB) of COMMAND into NAME.time
  /usr/bin/time -f "wall_s=%e peak_mib=%M" -o "$1.time" nice "${@:2}" > "$1.log" 2>&1
  awk '{ split($2, m, "="); printf "%s %s peak_mib=%.0f\n", "'"$1"'", $1, m[2] / 1024 }' "$1.time"
}

generate() { # POINTS SEED [SHAPE]
  local shape=${3:-dragon}
  local out=${shape}_$1_s$2.ply
  [ -f "$out" ] || nice "$gsscale" generate --points "$1" --seed "$2" --shape "$shape" --out "$out" > /dev/null
  echo "$out"
}

capped_gstile() { # a wrapper for gstile_dask.py --gstile: the cap, and each run's peak RSS
  cat > capped_gstile <<WRAP
#!/bin/sh
ulimit -v $cap
exec /usr/bin/time -a -o "$work/tile_runs.rss" -f "%M" "$gstile" "\$@"
WRAP
  chmod +x capped_gstile
}

compare() { # POINTS TILE_POINTS [SHAPE]: the dragon's lines tagged POINTS, another shape's SHAPE_POINTS
  local input tag=${3:+$3_}$1; input=$(generate "$1" 1 "${3:-dragon}")
  measure "whole_$tag" "$bin/tools/gsresample/gsresample" "$input" "whole_$tag.surfel"
  measure "tiled_$tag" "$gstile" all "$input" "tiled_$tag.surfel" --tile-points "$2" --tile-dir "tiles_$tag"
  echo "tiled_$tag tiles=$(grep -c '^\[run\]' "tiled_$tag.log")"
  nice "$bin/tools/gstile/gstile_compare" "tiles_$tag" "whole_$tag.surfel" "tiled_$tag.surfel" > "compare_$tag.txt"
  sed "s/^/compare_$tag /" "compare_$tag.txt"
  rm -rf "tiles_$tag"
}

# whole_and_tiled NAME GSRESAMPLE_OPTIONS...: the dragon (437,645 points) whole and in 13 tiles of
# at most 150,000 points with their halo, compared; lines prefixed NAME.
whole_and_tiled() {
  local name=$1 dragon=$here/../shared/data/dragon.ply
  shift
  measure "whole_$name" "$bin/tools/gsresample/gsresample" "$dragon" "whole_$name.surfel" "$@"
  measure "tiled_$name" "$gstile" all "$dragon" "tiled_$name.surfel" "$@" --tile-points 150000 --tile-dir "tiles_$name"
  nice "$bin/tools/gstile/gstile_compare" "tiles_$name" "whole_$name.surfel" "tiled_$name.surfel" > "compare_$name.txt"
  sed "s/^/$name /" "compare_$name.txt"
  rm -rf "tiles_$name"
}

target() { local count; for count in 4000 8000 10000 40000 100000; do whole_and_tiled "target_$count" --target "$count"; done; }
# 0.002 of the diagonal: level 8 meets it on the dragon; 0.0005: clusters split in every tile.
bound() { local bound; for bound in 0.002 0.0005; do whole_and_tiled "bound_$bound" --max-error "$bound"; done; }

halo() { # the dragon in 13 tiles of at most 150,000 points with their halo, at each halo width
  local dragon=$here/../shared/data/dragon.ply width
  nice "$bin/tools/gsresample/gsresample" "$dragon" whole_dragon.surfel > /dev/null
  for width in 1 2 4 6 8 12 16 24 32; do
    nice "$gstile" all "$dragon" "halo_$width.surfel" --tile-points 150000 --halo-spacings "$width" \
      --tile-dir "tiles_halo_$width" > /dev/null
    nice "$bin/tools/gstile/gstile_compare" "tiles_halo_$width" whole_dragon.surfel "halo_$width.surfel" |
      sed "s/^/halo_$width /"
    rm -rf "tiles_halo_$width"
  done
}

big() {
  local count=${PARTS:-10} parts=() input
  if [ "$count" -gt 1 ]; then
    input=dragon_$((count * 20))M.ply
    if [ ! -f "$input" ]; then
      for seed in $(seq "$count"); do parts+=("$(generate 20000000 "$seed")"); done
      nice /usr/bin/python3 "$here/bench/tile/concat_ply.py" "$input" "${parts[@]}"
      rm -f "${parts[@]}"
    fi
  else
    input=$(generate 20000000 1)
  fi
  echo "big_parameters points=$((count * 20000000)) tile_points=${TILE_POINTS:-8000000} cap_mib=$((cap / 1024))"
  measure split_big "$gstile" split "$input" tiles_big --tile-points "${TILE_POINTS:-8000000}"
  grep "tiles with points" split_big.log
  capped_gstile
  for workers in 1 2; do
    rm -f tiles_big/tile_*.surfel tile_runs.rss
    measure "dask_${workers}_workers" /usr/bin/python3 "$here/scripts/gstile_dask.py" tiles_big \
      "out_big_$workers.surfel" --workers "$workers" --gstile "$work/capped_gstile"
    sort -n tile_runs.rss | tail -1 | awk '{ printf "dask_'"$workers"'_workers largest_tile_peak_mib=%.0f\n", $1 / 1024 }'
  done
  cmp out_big_1.surfel out_big_2.surfel && echo "outputs_1_and_2_workers=identical"
  tail -1 dask_2_workers.log
}

stamp() {
  local dirty
  # Result files other stages wrote do not make the code differ from the commit.
  dirty=$(git -C "$here" status --porcelain --untracked-files=no | awk '{print $2}' |
    { grep -v '^bench/tile/results/' || true; } | paste -sd' ' -)
  echo "# commit $(git -C "$here" rev-parse --short HEAD)${dirty:+ (uncommitted changes in: $dirty)}"
  echo "# date $(date -u +%Y-%m-%d)"
  echo "# machine $(sed -n 's/^model name\s*: //p' /proc/cpuinfo | head -1 | awk '{print $1, $2}'), $(nproc) cores"
  echo "# load average at start $(cut -d' ' -f1-3 /proc/loadavg)"
}

case $stage in
  compare) run() { compare 5000000 1000000; compare 20000000 4000000; } ;;
  big) run() { big; } ;;
  target) run() { target; } ;;
  bound) run() { bound; } ;;
  flat) run() { compare 5000000 1000000 drilled-box; compare 20000000 4000000 drilled-box; } ;;
  halo) run() { halo; } ;;
  *) echo "usage: $0 WORK_DIR compare|big|target|bound|flat|halo" >&2; exit 2 ;;
esac
mkdir -p "$here/bench/tile/results"
{ stamp; run; echo "# load average at end $(cut -d' ' -f1-3 /proc/loadavg)"; } | tee "$stage.txt"
cp "$stage.txt" "$here/bench/tile/results/$stage.txt"
