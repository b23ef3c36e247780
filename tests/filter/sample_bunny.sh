# The shipped bunny through the shipped level-8 script: a .surfel with a sensible count,
# unit normals, radii > 0 and ellipse frames that survive the batch run and a reload; a
# plain PLY with normals and radii next to it.
source "$E2E_COMMON"
source "$FILTER_TESTS_DIR/lib.sh"
points=34834
count=$(resample "$SAMPLE_DIR/bunny.ply" bunny.surfel "$SAMPLE_DIR/resample_level8.mlx")
echo "bunny: $count surfels"
"$SURFEL_CHECK" bunny.surfel --min-count $((points / 10)) --max-count $((points * 3 / 10)) \
  --require-ellipses --quality-sum $points
# Reload the result and save it again: the ellipses survive.
"$RUN_MESHLABSERVER" -i bunny.surfel -o reloaded.surfel >reload.log 2>&1
cmp bunny.surfel reloaded.surfel
grep -q "Gaussian sphere resampling: .* surfels .*; time [0-9.]* s on [1-9][0-9]* thread(s) (neighbours" bunny.surfel.log
# The command-line resampler writes the same file, byte for byte, without MeshLab.
"$GSRESAMPLE" "$SAMPLE_DIR/bunny.ply" standalone.surfel >standalone.log
cmp bunny.surfel standalone.surfel
# Colouring the input by cluster works from a script too.
"$RUN_MESHLABSERVER" -i "$SAMPLE_DIR/bunny.ply" -s "$SAMPLE_DIR/resample_colorize.mlx" \
  -o coloured.surfel >coloured.log 2>&1
"$SURFEL_CHECK" coloured.surfel --count "$count" --require-ellipses
# ...and the surfels carry the cluster colours (68-byte records, RGBA in the last 4 bytes).
python3 - coloured.surfel <<'PY'
import sys
data = open(sys.argv[1], "rb").read()
body = data.split(b"end_header\n", 1)[1]
assert len(body) % 68 == 0, len(body)
colours = {body[i + 64:i + 68] for i in range(0, len(body), 68)}
print(f"coloured.surfel: {len(colours)} distinct surfel colours")
sys.exit(0 if len(colours) > 100 else 1)
PY
