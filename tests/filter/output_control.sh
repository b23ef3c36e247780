# Output-size control from scripts: TargetPercentage gives the requested count exactly, a
# TargetCount too; MaxError adds surfels where the bound needs them and logs whether it holds.
source "$E2E_COMMON"
source "$FILTER_TESTS_DIR/lib.sh"
bunny="$SAMPLE_DIR/bunny.ply"
count=$(resample "$bunny" ten.surfel "$SAMPLE_DIR/resample_10_percent.mlx")
echo "bunny at 10%: $count surfels"
[ "$count" = 3483 ]   # round(0.10 x 34,834)
"$SURFEL_CHECK" ten.surfel --count 3483 --require-ellipses --quality-sum 34834
count=$(resample "$bunny" exact.surfel "$(script_with TargetCount=1234)")
[ "$count" = 1234 ]
"$SURFEL_CHECK" exact.surfel --count 1234 --require-ellipses --quality-sum 34834
# At a target size, exchanges of clusters lower the largest distance to the blended surface
# (MaxErrorExchanges, 16 by default); the log gives it before and after.
PYTHONPATH="$FILTER_TESTS_DIR" python3 - ten.surfel.log <<'PY'
import re, sys
m = re.search(r"(\d+) exchange\(s\) of clusters kept of (\d+) tried, largest distance to the blended surface "
              r"([0-9.e-]+) -> ([0-9.e-]+) x diagonal", open(sys.argv[1]).read())
kept, tried, before, after = int(m.group(1)), int(m.group(2)), float(m.group(3)), float(m.group(4))
print("bunny at 10%%: %d exchange(s) kept of %d, largest distance %g -> %g x diagonal" % (kept, tried, before, after))
assert 0 < kept <= 16 and tried >= 2 * kept and after < before
PY
plain=$(resample "$bunny" plain.surfel "$SAMPLE_DIR/resample_level8.mlx")
bounded=$(resample "$bunny" bounded.surfel "$(script_with MaxError=0.0005)")
echo "bunny: $plain surfels without a bound, $bounded with MaxError 0.0005"
[ "$bounded" -gt "$plain" ]
grep -q "split(s) (own planes + blended surface)" bounded.surfel.log
# Below the blend's resolution at creases and thin parts (the bunny's ears) splitting alone
# leaves points beyond it; narrowing the one-point surfels there meets it, and the log says so.
grep -q "[1-9][0-9]* halving(s) of one-point surfels' blend scales" bounded.surfel.log
grep -q "error bound met" bounded.surfel.log
# The narrowed blend is saved (.surfel version 3, blend_scale in each record):
# some surfels below 1, none below 1/8.
PYTHONPATH="$FILTER_TESTS_DIR" python3 - bounded.surfel <<'PY'
import sys
from surfel_records import records, BLEND_SCALE
scales = [r[BLEND_SCALE] for r in records(sys.argv[1])]
print("blend scales: %d below 1, smallest %g" % (sum(s < 1 for s in scales), min(scales)))
assert any(s < 1 for s in scales) and min(scales) >= 0.125 and max(scales) == 1
PY
loose=$(resample "$bunny" loose.surfel "$(script_with MaxError=0.01)")
grep -q "error bound met" loose.surfel.log
grep -q " 0 halving(s) of one-point surfels' blend scales" loose.surfel.log
echo "bunny: $loose surfels with MaxError 0.01"
# FitOffsets (on by default) moves surfels along their normals onto the blended surface, and
# says so; off, the surfels stay at their clusters' centroids: same count, same ellipses. The
# move is saved (fit_offset in each record): moved back by it, the fitted surfels are the centroids.
grep -q "surfel(s) fitted to the blended surface" plain.surfel.log
centroids=$(resample "$bunny" centroids.surfel "$(script_with FitOffsets=false)")
[ "$centroids" = "$plain" ]
if grep -q "fitted to the blended surface" centroids.surfel.log; then exit 1; fi
PYTHONPATH="$FILTER_TESTS_DIR" python3 - plain.surfel centroids.surfel <<'PY'
import sys
from surfel_records import records, FIT_OFFSET
fitted, plain = records(sys.argv[1]), records(sys.argv[2])
moves = [sum((a[k] - b[k]) ** 2 for k in range(3)) ** 0.5 for a, b in zip(fitted, plain)]
print("fitted surfels: %d of %d moved, longest move %g" % (sum(m > 0 for m in moves), len(moves), max(moves)))
assert sum(m > 0 for m in moves) > len(moves) // 2 and max(moves) < 0.01   # the bunny is ~0.25 across
assert all(a[3:13] == b[3:13] for a, b in zip(fitted, plain))               # normals, radius, axes unchanged
unfitted = max(sum((a[k] - a[FIT_OFFSET] * a[3 + k] - b[k]) ** 2 for k in range(3)) ** 0.5 for a, b in zip(fitted, plain))
print("fitted surfels moved back by their fit offsets: at most %g from the centroids" % unfitted)
assert unfitted < 1e-6 and all(b[FIT_OFFSET] == 0 for b in plain)
PY
# Around creases (the bunny's ears and base) the surfels blend narrower, and the log says how
# many; the scale is saved (blend_scale); without a crease angle no surfel is narrowed.
grep -q "surfel(s) around creases blend narrower" plain.surfel.log
smooth=$(resample "$bunny" smooth.surfel "$(script_with CreaseAngle=0)")
if grep -q "around creases blend" smooth.surfel.log; then exit 1; fi
PYTHONPATH="$FILTER_TESTS_DIR" python3 - plain.surfel smooth.surfel <<'PY'
import sys
from surfel_records import records, BLEND_SCALE
def scales(path):
    return [round(r[BLEND_SCALE], 6) for r in records(path)]
narrowed, smooth = scales(sys.argv[1]), scales(sys.argv[2])
print("blend scales around creases: %d of %d at 0.65" % (narrowed.count(0.65), len(narrowed)))
assert set(narrowed) == {0.65, 1.0} and set(smooth) == {1.0}
PY
