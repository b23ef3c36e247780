#!/usr/bin/env bash
# A tiled run against the whole run of the same input:
#   tiled_vs_whole.sh INPUT.ply|generated TILE_POINTS [GSRESAMPLE OPTIONS...]
# ("generated": the dragon densified to 300,000 points by gsscale, in random order; the options,
# e.g. --target N, go to both runs). Checks, from
# gstile_compare's figures:
#  - surfel count within 0.5 %; every error figure (RMS, 99.9th percentile) within 1 %, and the
#    largest ones at most 1 % above the whole run's (a single point, which tiles may meet
#    lower: at a target, the exchanges that lower it are shared out over the tiles);
#  - the points represented within 0.5 % of the input's (no cluster lost or kept twice beyond a
#    few at borders);
#  - no doubles at borders: the median distance from a surfel to its nearest surfel of another
#    tile is not below the median to its nearest of its own tile;
#  - no holes along tile faces beyond the whole run's, plus 0.1 % of the points there.
# Environment: GSRESAMPLE, GSTILE, GSTILE_COMPARE, WORK_DIR, and GSSCALE for "generated".
set -euo pipefail
input=$1 tile_points=$2
shift 2
rm -rf "$WORK_DIR" && mkdir -p "$WORK_DIR" && cd "$WORK_DIR"
if [ "$input" = generated ]; then
  "$GSSCALE" generate --points 300000 --shape dragon --out generated.ply >/dev/null
  input=$PWD/generated.ply
fi
"$GSRESAMPLE" "$input" whole.surfel "$@" >/dev/null
"$GSTILE" all "$input" tiled.surfel "$@" --tile-points "$tile_points" --tile-dir tiles > tiled.log
"$GSTILE_COMPARE" tiles whole.surfel tiled.surfel > figures.txt
cat figures.txt

failures=0
check() { # NAME CONDITION (awk, over the figures as variables)
  if awk -F= '{ v[$1] = $2 } END { exit !('"$2"') }' figures.txt; then echo "ok: $1"
  else echo "FAILED: $1"; failures=$((failures + 1)); fi
}
abs() { echo "(v[\"$1\"] < 0 ? -v[\"$1\"] : v[\"$1\"])"; }
check "count within 0.5 %" "$(abs count_diff_pct) <= 0.5"
for figure in delta_rms delta_p999 l21_own_rms l21_own_p999 l21_blended_rms l21_blended_p999; do
  check "$figure within 1 %" "$(abs ${figure}_diff_pct) <= 1"
done
for figure in delta_max l21_own_max l21_blended_max; do
  check "$figure at most 1 % above the whole run's" "v[\"${figure}_diff_pct\"] <= 1"
done
check "represented points within 0.5 %" "$(abs members_diff_pct) <= 0.5"
check "no doubles across tiles" 'v["tiled_nn_across_median"] >= v["tiled_nn_inside_median"]'
check "no holes along tile faces" \
  'v["tiled_border_uncovered"] <= v["whole_border_uncovered"] + 0.001 * v["tiled_border_points"]'
echo "tiles: $(grep -c '^\[run\]' tiled.log)"
[ "$(grep -c '^\[run\]' tiled.log)" -ge 4 ] || { echo "FAILED: fewer than 4 tiles"; failures=$((failures + 1)); }
exit $((failures > 0))
