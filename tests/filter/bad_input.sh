# Bad input never crashes meshlabserver: each case gives the documented error or fallback.
source "$E2E_COMMON"
source "$FILTER_TESTS_DIR/lib.sh"
script="$SAMPLE_DIR/resample_level8.mlx"

# expect_error IN SCRIPT MESSAGE: the filter fails cleanly (status 255) and logs MESSAGE.
expect_error() {
  local status=0
  "$RUN_MESHLABSERVER" -i "$1" -s "$2" -o out.surfel >run.log 2>&1 || status=$?
  if [ "$status" != 255 ]; then echo "FAILED: $1 with $2 exited $status, expected 255" >&2; tail -5 run.log >&2; exit 1; fi
  grep -q "Gaussian sphere resampling failed: .*$3" run.log || {
    echo "FAILED: no '$3' in the log for $1" >&2; tail -5 run.log >&2; exit 1; }
  echo "ok: $1 ($2): $3"
}

# A point set without normals (PLY without nx ny nz: MeshLab loads zero normals).
printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n1 0 0\n0 1 0\n' > no_normals.ply
expect_error no_normals.ply "$script" "Compute normals for point sets"

# An empty layer and a one-point layer.
write_ply empty.ply </dev/null
expect_error empty.ply "$script" "empty"
echo "0 0 0 0 0 1" | write_ply one.ply
expect_error one.ply "$script" "at least 2"

# Out-of-range parameters name the parameter.
expect_error "$SAMPLE_DIR/fandisk.ply" "$(script_with SubdivisionLevel=1)" "SubdivisionLevel"
expect_error "$SAMPLE_DIR/fandisk.ply" "$(script_with NeighborCount=0)" "NeighborCount"
expect_error "$SAMPLE_DIR/fandisk.ply" "$(script_with CreaseAngle=150)" "CreaseAngle must be at least 0 and below 120"
expect_error "$SAMPLE_DIR/fandisk.ply" "$(script_with TargetCount=-5)" "TargetCount must be at least 0"
expect_error "$SAMPLE_DIR/fandisk.ply" "$(script_with TargetPercentage=150)" "TargetPercentage must be between 0 and 100"
expect_error "$SAMPLE_DIR/fandisk.ply" "$(script_with MaxError=1)" "MaxError must be at least 0 and below 1"

# NaN and zero normals are skipped and counted; the rest is resampled.
python3 - <<'PY' | write_ply mixed.ply
import math
for i in range(30):
    for j in range(30):
        n = "0 0 1"
        if (i * 30 + j) % 10 == 0: n = "nan nan nan"
        elif (i * 30 + j) % 10 == 1: n = "0 0 0"
        print(i * 0.01, j * 0.01, 0, n)
PY
"$RUN_MESHLABSERVER" -i mixed.ply -s "$script" -o mixed.surfel >mixed.log 2>&1
grep -q "skipped 180 point(s) with a zero or invalid normal" mixed.log
"$SURFEL_CHECK" mixed.surfel --min-count 1 --max-count 720 --require-ellipses --quality-sum 720
echo "ok: NaN and zero normals skipped"

# Duplicate points: every point of the fandisk three times, plus 40 copies of one point.
python3 - "$SAMPLE_DIR/fandisk.ply" <<'PY' | write_ply duplicates.ply
import struct, sys
data = open(sys.argv[1], "rb").read()
header, body = data.split(b"end_header\n", 1)
rows = [struct.unpack_from("<6f", body, 24 * i) for i in range(len(body) // 24)]
for r in rows:
    for _ in range(3): print(*r)
for _ in range(40): print(*rows[0])
PY
"$RUN_MESHLABSERVER" -i duplicates.ply -s "$script" -o duplicates.surfel >duplicates.log 2>&1
"$SURFEL_CHECK" duplicates.surfel --min-count 100 --require-ellipses --quality-sum $((6475 * 3 + 40))
echo "ok: duplicate points"

# A scan in georeferenced coordinates (UTM metres): MeshLab holds them in float, in steps of
# 0.25 m there; the run completes and its log says the positions are coarse, and why.
python3 - "$SAMPLE_DIR/fandisk.ply" <<'PY' | write_ply far.ply
import struct, sys
data = open(sys.argv[1], "rb").read()
header, body = data.split(b"end_header\n", 1)
for i in range(len(body) // 24):
    x, y, z, nx, ny, nz = struct.unpack_from("<6f", body, 24 * i)
    print(500000 + x, 4000000 + y, 100 + z, nx, ny, nz)
PY
"$RUN_MESHLABSERVER" -i far.ply -s "$script" -o far.surfel >far.log 2>&1
grep -q "float coordinates there are held in steps of 0.25" far.log || {
  echo "FAILED: no coarse-coordinates warning for far.ply" >&2; tail -5 far.log >&2; exit 1; }
echo "ok: coordinates far from the origin reported coarse"

# Fewer points than k.
printf '0 0 0 0 0 1\n0.1 0 0 0 0 1\n0 0.1 0 0 0 1\n0.1 0.1 0 0 0 1\n0.05 0.05 0 0 0 1\n' | write_ply five.ply
"$RUN_MESHLABSERVER" -i five.ply -s "$script" -o five.surfel >five.log 2>&1
"$SURFEL_CHECK" five.surfel --min-count 1 --max-count 5 --require-ellipses --quality-sum 5
echo "ok: fewer points than k"

# The command-line resampler: the same inputs give one clear line and leave no file; status 1
# for an input it cannot resample or an output it cannot write, 2 for a bad parameter.
# gsresample_fails STATUS IN OUT MESSAGE [OPTION VALUE...]
gsresample_fails() {
  local status=0
  "$GSRESAMPLE" "$2" "$3" "${@:5}" >gsresample.log 2>&1 || status=$?
  if [ "$status" != "$1" ]; then echo "FAILED: gsresample $2 $3 exited $status, expected $1" >&2; cat gsresample.log >&2; exit 1; fi
  grep -q -- "$4" gsresample.log || { echo "FAILED: no '$4' from gsresample $2" >&2; cat gsresample.log >&2; exit 1; }
  if [ -e "$3" ] || compgen -G "$3.*.part" > /dev/null; then echo "FAILED: gsresample left $3 behind" >&2; exit 1; fi
  echo "ok: gsresample $2 -> $3: $4"
}
gsresample_fails 1 missing.ply out_missing.surfel "cannot read missing.ply"
gsresample_fails 1 no_normals.ply out_no_normals.surfel "no per-vertex normals"
gsresample_fails 1 one.ply out_one.surfel "at least 2"
gsresample_fails 2 "$SAMPLE_DIR/fandisk.ply" out_threshold.surfel "--threshold: expected a number above 1, got '1' (out of range)" --threshold 1
gsresample_fails 2 "$SAMPLE_DIR/fandisk.ply" out_exchanges.surfel "--exchanges: expected an integer between 0 and 100000" --target 100 --exchanges -3
gsresample_fails 1 "$SAMPLE_DIR/fandisk.ply" no_such_folder/out.surfel "cannot write 'no_such_folder/out.surfel': No such file or directory"
gsresample_fails 1 "$SAMPLE_DIR/fandisk.ply" no_such_folder/out.ply "cannot write 'no_such_folder/out.ply': No such file or directory"
