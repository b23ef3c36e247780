#!/usr/bin/env bash
# The "Surfel Approximation Error" filter run by the staged meshlabserver:
#   1. the sample bunny against itself (the floor): both log lines, distances in vertex quality,
#      colours written;
#   2. a layer without normals: the run fails with a message saying so;
#   3. when the resampling plugin is staged too: resample, then measure with SurfelIndex.
# Environment (tests/error/CMakeLists.txt): RUN_MESHLABSERVER, MESHLABSERVER_BIN, SAMPLE_DATA,
# WORK_DIR. Exits 77 (skipped) when the plugin is not staged.
set -uo pipefail
: "${RUN_MESHLABSERVER:?}" "${MESHLABSERVER_BIN:?}" "${SAMPLE_DATA:?}" "${WORK_DIR:?}"
plugins="$(dirname "$MESHLABSERVER_BIN")/../lib/x86_64-linux-gnu/meshlab/plugins"
if [ ! -e "$plugins/libfilter_surfel_error.so" ]; then
  echo "SKIP: $plugins has no libfilter_surfel_error.so: build the 'stage' target"
  exit 77
fi
rm -rf "$WORK_DIR" && mkdir -p "$WORK_DIR" && cd "$WORK_DIR" || exit 1

failures=0
check() { # description command...
  local what="$1"; shift
  if "$@"; then echo "ok: $what"; else echo "FAILED: $what"; failures=$((failures + 1)); fi
}

# error_filter ORIGINAL_LAYER SIMPLIFIED_LAYER COLORIZE: the filter's block with every parameter
# (Debian's meshlabserver aborts on a script that leaves one out).
error_filter() {
  cat <<EOF
 <filter name="Surfel Approximation Error">
  <Param type="RichMesh" value="$1" name="OriginalMesh"/>
  <Param type="RichMesh" value="$2" name="SimplifiedMesh"/>
  <Param type="RichBool" value="true" name="UseSurfelIndex"/>
  <Param type="RichInt" value="8" name="NeighborCount"/>
  <Param type="RichFloat" value="1.5" name="WidthFactor"/>
  <Param type="RichBool" value="$3" name="ColorizeByDistance"/>
 </filter>
EOF
}
{ echo "<!DOCTYPE FilterScript>"; echo "<FilterScript>"; error_filter 0 0 true; echo "</FilterScript>"; } > floor.mlx

"$RUN_MESHLABSERVER" -i "$SAMPLE_DATA/bunny.ply" -s floor.mlx -o floor.ply -m vq vc > floor.log 2>&1
check "floor run succeeds" test $? -eq 0
rms=$(sed -n "s/.*LOG: [0-9] Surfel error of .* D\*rms \([0-9.e+-]*\) D\*max.*/\1/p" floor.log)
check "floor D*rms logged and below 1e-3 (got '${rms}')" awk -v x="$rms" 'BEGIN { exit !(x != "" && x + 0 > 0 && x + 0 < 1e-3) }'
check "floor own-surfel L2,1 is 0" grep -q "own surfel (nearest) rms 0.0000 max 0.0000" floor.log
check "distances saved as vertex quality" grep -aq "^property float quality" floor.ply
check "colours saved" grep -aq "^property uchar red" floor.ply

printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n1 0 0\n0 1 0\n' > no_normals.ply
"$RUN_MESHLABSERVER" -i no_normals.ply -s floor.mlx > no_normals.log 2>&1
check "a layer without normals fails" test $? -ne 0
check "... saying it has no normals" grep -q "has no normals" no_normals.log

if [ -e "$plugins/libfilter_gaussphere.so" ]; then
  { sed '$d' "$SAMPLE_DATA/resample_level8.mlx"; error_filter 0 1 false; echo "</FilterScript>"; } > pipeline.mlx
  "$RUN_MESHLABSERVER" -i "$SAMPLE_DATA/bunny.ply" -s pipeline.mlx > pipeline.log 2>&1
  check "resample then measure succeeds" test $? -eq 0
  check "the own surfel comes from SurfelIndex" grep -q "own surfel (SurfelIndex)" pipeline.log
else
  echo "note: libfilter_gaussphere.so is not staged, the resample-then-measure run is left out"
fi

grep -ho "LOG: .*" ./*.log
exit $((failures > 0))
