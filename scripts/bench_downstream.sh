#!/usr/bin/env bash
# The downstream benchmark: how well MeshLab's Screened Poisson reconstructs each model from our
# surfels and from every peer's points at the same count, measured against the original mesh.
#
#   scripts/bench_downstream.sh [--quick] [models...]
#
# models: names of ../shared/data/NAME.ply that have a NAME_mesh.ply beside them (default: every
# point set there). Absent ones are skipped with a reason.
#   full run  -> bench/results/: downstream.md, downstream.csv, downstream.png,
#                raw/downstream_header.txt; then docs/results.md (bench/results_doc.py)
#   --quick   -> bench/results/quick/: the shipped sample_data bunny and fandisk, 200,000 distance
#                samples per mesh; a smoke run of about a minute
#
# Per model: ours is `gsresample` at its defaults (level 8; its PLY carries quality = the points
# each surfel represents); `gsbench export` matches CGAL's hierarchy, CGAL's grid and MeshLab's
# Poisson disk to our count (+-2 %) and writes their points; the input itself is the floor.
# Each is reconstructed by meshlabserver's "Surface Reconstruction: Screened Poisson" at one depth
# for all (9 for the dragon, 8 for the others), ours weighted as the shipped
# sample_data/resample_and_reconstruct.mlx says (its confidence flag), the others unweighted;
# `gsmeshdist` measures each reconstruction against NAME_mesh.ply (bench/README.md).
#
# Environment: BUILD_DIR (default <repo>/build-bench), JOBS (default 2), SAMPLES (area samples
# per mesh for the distance, default 1,000,000), OURS_WEIGHTS (more weightings of ours to
# reconstruct, each a row ours-WEIGHT, space-separated among quality, none, area, sqrt (the square
# root of the points represented), nofit, even; default quality; nofit is ours with --fit-offsets 0, unweighted: the surfels on the sampled surface, not
# fitted to the blend; even is ours at
# level 8 with --spread-evenly 1 (the same count, surfels spread evenly for reconstruction), unweighted), PEERS (default "cgal-hierarchy cgal-grid meshlab-poisson"),
# FLOOR (0: no reconstruction from the input itself), WORK (default ${TMPDIR:-/tmp}/gsbench-downstream: the
# point sets and reconstructions, kept for viewing), OUT (the results' folder instead of the
# two above; docs/results.md is then left alone).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${BUILD_DIR:-$root/build-bench}"
jobs="${JOBS:-2}"

source "$root/scripts/bench_common.sh"
# Screened Poisson's OpenMP threads sleep while they wait: spinning, they slowed a reconstruction
# tenfold beside other work on the machine. The figures measured are distances, not times.
export OMP_WAIT_POLICY=passive
bench_parse_args bench_downstream.sh 26 "$@"
bench_extra_targets=(gsresample gsmeshdist)
bench_build_then_run_in_xvfb -DGAUSSPHERE_BUILD_BENCH=ON -- "$@"

gsbench="$build/bench/gsbench"
gsmeshdist="$build/bench/gsmeshdist"
gsresample="$build/tools/gsresample/gsresample"
meshlabserver="$build/stage/bin/meshlabserver"
meshes="$root/../shared/data"
bench_choose_inputs
runs=1
bench_present_models downstream
if [ "$quick" = 1 ]; then
  out="${OUT:-$root/bench/results/quick}"
  samples="${SAMPLES:-200000}"
else
  out="${OUT:-$root/bench/results}"
  samples="${SAMPLES:-1000000}"
fi
read -r -a ours_weights <<< "${OURS_WEIGHTS-quality}"
# The weighting users get: the confidence flag of the shipped script.
shipped_weight=none
grep -q 'value="true" name="confidence"' "$root/sample_data/resample_and_reconstruct.mlx" && shipped_weight=quality
read -r -a peers <<< "${PEERS-cgal-hierarchy cgal-grid meshlab-poisson}"
work="${WORK:-${TMPDIR:-/tmp}/gsbench-downstream}"
mkdir -p "$out/raw" "$work"
# Rows and header are written in the work folder and move into $out when the run is complete.
csv="$work/downstream.csv"
header="$work/downstream_header.txt"

# Screened Poisson's depth: the dragon has 437,645 points and details depth 8 cannot hold.
poisson_depth() { if [ "$1" = dragon ]; then echo 9; else echo 8; fi; }

# poisson_script DEPTH CONFIDENCE(true|false) > FILE.mlx: the Screened Poisson step of the shipped
# sample_data/resample_and_reconstruct.mlx (every parameter listed, as meshlabserver 2020.09
# needs; MeshLab's defaults), with the depth and the confidence flag (per-vertex quality scales
# each sample's weight) set: the benchmark reconstructs as users do.
poisson_script() {
  echo "<!DOCTYPE FilterScript>"
  echo "<FilterScript>"
  sed -n '/<filter name="Surface Reconstruction: Screened Poisson">/,/<\/filter>/p' \
    "$root/sample_data/resample_and_reconstruct.mlx" |
    sed -e "s/value=\"[^\"]*\" name=\"depth\"/value=\"$1\" name=\"depth\"/" \
        -e "s/value=\"[^\"]*\" name=\"confidence\"/value=\"$2\" name=\"confidence\"/"
  echo "</FilterScript>"
}

ply_vertex_count() { grep -a -m1 '^element vertex' "$1" | awk '{print $3}'; }

# reconstruct_and_measure NAME METHOD POINTS.ply WEIGHT PARAMETERS MATCHED: one CSV row.
reconstruct_and_measure() {
  local name=$1 method=$2 points=$3 weight=$4 parameters=$5 matched=$6
  local depth confidence=false mesh="$work/$name/${method}_reconstruction.ply" started distance
  depth="$(poisson_depth "$name")"
  [ "$weight" = none ] || confidence=true
  poisson_script "$depth" "$confidence" > "$work/$name/poisson_d${depth}_$confidence.mlx"
  started=$(date +%s.%N)
  nice "$meshlabserver" -i "$points" -s "$work/$name/poisson_d${depth}_$confidence.mlx" -o "$mesh" \
    > "$work/$name/${method}_reconstruction.log" 2>&1 ||
    { echo "[downstream] meshlabserver failed on $name/$method: $work/$name/${method}_reconstruction.log" >&2; exit 1; }
  local reconstruction_s ended
  ended=$(date +%s.%N)
  reconstruction_s=$(awk -v a="$started" -v b="$ended" 'BEGIN { printf "%.2f", b - a }')
  started=$ended
  distance="$(nice "$gsmeshdist" "$mesh" "$meshes/${name}_mesh.ply" --samples "$samples")"
  ended=$(date +%s.%N)
  echo "$name,$input_points,$method,$(ply_vertex_count "$points"),$weight,$depth,$parameters,$matched,$reconstruction_s,$(awk -v a="$started" -v b="$ended" 'BEGIN { printf "%.2f", b - a }'),$distance" >> "$csv"
  echo "[downstream]   $method: $(tail -1 "$csv" | cut -d, -f4) points, reconstruction ${reconstruction_s} s, distance $distance"
}

echo "model,input_points,method,points,weight,depth,parameters,matched,reconstruction_s,distance_s,$("$gsmeshdist" --csv-header)" > "$csv"
bench_header ", one reconstruction per method: times are indicative" > "$header"
echo "Distance samples per mesh: $samples; ours weighted as shipped ($shipped_weight); more weightings of ours: ${ours_weights[*]:-none}." >> "$header"

started=$SECONDS
for name in "${present[@]}"; do
  if [ ! -f "$meshes/${name}_mesh.ply" ]; then echo "[downstream] skip $name: $meshes/${name}_mesh.ply not found"; continue; fi
  echo "[downstream] $name at $((SECONDS - started)) s"
  mkdir -p "$work/$name"
  input="$data/$name.ply"
  input_points="$(ply_vertex_count "$input")"

  nice "$gsresample" "$input" "$work/$name/ours.ply" --level 8 > "$work/$name/ours.log"
  count="$(ply_vertex_count "$work/$name/ours.ply")"
  reconstruct_and_measure "$name" ours "$work/$name/ours.ply" "$shipped_weight" "n=8" yes
  for weight in "${ours_weights[@]}"; do
    [ "$weight" != "$shipped_weight" ] || continue
    case "$weight" in
      quality|none) reconstruct_and_measure "$name" "ours-$weight" "$work/$name/ours.ply" "$weight" "n=8" yes ;;
      area|sqrt)
        nice "$gsresample" "$input" "$work/$name/ours.surfel" --level 8 > /dev/null
        /usr/bin/python3 "$root/bench/surfel_weights.py" "$work/$name/ours.surfel" "$work/$name/ours_$weight.ply" "$weight"
        reconstruct_and_measure "$name" "ours-$weight" "$work/$name/ours_$weight.ply" "$weight" "n=8" yes ;;
      nofit)
        nice "$gsresample" "$input" "$work/$name/ours_nofit.ply" --level 8 --fit-offsets 0 > /dev/null
        reconstruct_and_measure "$name" ours-nofit "$work/$name/ours_nofit.ply" none "n=8" yes ;;
      even)
        nice "$gsresample" "$input" "$work/$name/ours_even.ply" --level 8 --spread-evenly 1 > /dev/null
        reconstruct_and_measure "$name" ours-even "$work/$name/ours_even.ply" none "n=8 spread-evenly" yes ;;
      *) echo "[downstream] unknown weight $weight in OURS_WEIGHTS" >&2; exit 2 ;;
    esac
  done

  rm -f "$work/$name/export.csv"
  [ ${#peers[@]} -gt 0 ] && nice "$gsbench" export "$input" --count "$count" --out "$work/$name/peer" --methods "$(IFS=,; echo "${peers[*]}")" \
    --meshlabserver "$meshlabserver" --work "$work/$name" --csv "$work/$name/export.csv"
  for peer in "${peers[@]}"; do
    IFS=, read -r _ _ _ parameters matched _ < <(grep "^$peer," "$work/$name/export.csv")
    reconstruct_and_measure "$name" "$peer" "$work/$name/peer_$peer.ply" none "$parameters" "$matched"
  done
  [ "${FLOOR:-1}" = 0 ] || reconstruct_and_measure "$name" floor "$input" none "S'=S" yes
done

echo "load average at end: $(cut -d' ' -f1-3 /proc/loadavg); benchmark time $((SECONDS - started)) s." >> "$header"
cp "$csv" "$out/downstream.csv" && cp "$header" "$out/raw/downstream_header.txt"
csv="$out/downstream.csv" header="$out/raw/downstream_header.txt"
python=python3
/usr/bin/python3 -c 'import matplotlib' 2>/dev/null && python=/usr/bin/python3
"$python" "$root/bench/downstream_report.py" --csv "$csv" --header "$header" --out "$out"
[ "$out" != "$root/bench/results" ] || "$python" "$root/bench/results_doc.py" > /dev/null
echo "[downstream] done in $((SECONDS - started)) s: $out/downstream.md"
