# gsresample's output path: the input is never replaced or removed, nothing is written through a
# link planted beside the output, a device is written in place, an unwritable path fails before
# the resampling runs, an output ending in .surfel in any case is a .surfel file, and a missed
# error bound warns.
# Environment: GSRESAMPLE (the program), SAMPLE_DIR (sample_data), WORK_DIR (a folder of its own).
set -u
rm -rf "$WORK_DIR" && mkdir -p "$WORK_DIR" && cd "$WORK_DIR" || exit 1

failures=0
fail() { echo "FAILED: $*" >&2; failures=$((failures + 1)); }
ok() { echo "ok: $*"; }
run() { status=0; "$GSRESAMPLE" "$@" >stdout.log 2>stderr.log || status=$?; }
parts() { find . -maxdepth 1 -name "$1.*.part" | wc -l; }
cp "$SAMPLE_DIR/fandisk.ply" input.ply
original=$(sha256sum < input.ply)

# The input as the output, by its name, a link or a hard link: refused, the input unchanged.
ln -s input.ply link.ply
ln input.ply hard.ply
for output in input.ply link.ply hard.ply; do
  run input.ply "$output"
  if [ "$status" = 2 ] && grep -q "is the input file" stderr.log && [ "$(sha256sum < input.ply)" = "$original" ]; then
    ok "output $output = input: refused"
  else fail "output $output = input: status $status, $(cat stderr.log)"; fi
done

# An input named like the old temporary file of the output stays.
cp input.ply out.ply.part
run out.ply.part out.ply
if [ "$status" = 0 ] && [ "$(sha256sum < out.ply.part)" = "$original" ] && [ -s out.ply ]; then
  ok "input out.ply.part kept, out.ply written"
else fail "input out.ply.part: status $status, $(cat stderr.log)"; fi

# A link planted at any name beside the output is not written through.
echo precious > victim.txt
ln -s victim.txt planted.surfel.part
run input.ply planted.surfel
if [ "$status" = 0 ] && [ "$(cat victim.txt)" = precious ] && [ "$(parts planted.surfel)" = 0 ]; then
  ok "planted link not followed"
else fail "planted link: status $status, victim: $(head -c 40 victim.txt)"; fi

# A device is written in place and stays a device.
run input.ply /dev/null
if [ "$status" = 0 ] && [ -c /dev/null ]; then ok "/dev/null written in place"
else fail "/dev/null: status $status, $(ls -l /dev/null)"; fi

# Unwritable outputs fail before the resampling (no figures line) with the reason, leaving nothing.
mkdir folder.ply
for output in folder.ply missing/out.ply ""; do
  run input.ply "$output"
  if [ "$status" = 1 ] && [ ! -s stdout.log ] && grep -q "^gsresample: error: cannot write" stderr.log; then
    ok "output '$output': $(cat stderr.log)"
  else fail "output '$output': status $status, stdout $(wc -c < stdout.log) bytes, $(cat stderr.log)"; fi
done
[ "$(parts folder.ply)" = 0 ] || fail "a temporary file left beside folder.ply"

# The .surfel suffix in any case.
run input.ply upper.SURFEL
if [ "$status" = 0 ] && head -c 200 upper.SURFEL | grep -q "comment gaussphere-surfel"; then ok "upper.SURFEL is a .surfel file"
else fail "upper.SURFEL: status $status, $(head -c 80 upper.SURFEL | tr '\n' ' ')"; fi

# A bound the refinement cannot meet: status 0, the output written, one warning with the count.
run input.ply bound.surfel --max-error 1e-12
if [ "$status" = 0 ] && [ -s bound.surfel ] &&
   grep -qE "^gsresample: warning: [1-9][0-9]* point\(s\) remain beyond the error bound" stderr.log; then
  ok "missed bound: $(cat stderr.log)"
else fail "missed bound: status $status, $(cat stderr.log)"; fi

[ "$failures" = 0 ] || { echo "$failures failure(s)" >&2; exit 1; }
