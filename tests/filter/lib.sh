# Helpers for the filter's end-to-end scripts (sourced after $E2E_COMMON).

# resample IN OUT SCRIPT: runs the filter through meshlabserver, keeps its output in
# OUT.log, prints the surfel count from the filter's log line. Not anchored at the line start:
# meshlabserver writes the progress messages to stdout without newlines, and a LOG line from
# stderr may land in the middle of them.
resample() {
  local in=$1 out=$2 script=$3
  "$RUN_MESHLABSERVER" -i "$in" -s "$script" -o "$out" -m vn vr >"$out.log" 2>&1 || {
    echo "meshlabserver failed (status $?) on $in with $script:" >&2; tail -5 "$out.log" >&2; return 1; }
  sed -n 's/.*LOG: [0-9] Gaussian sphere resampling: [0-9]* points -> \([0-9]*\) surfels.*/\1/p' "$out.log" | head -1
}

# script_with NAME=VALUE...: a copy of the level-8 sample script with parameters changed.
script_with() {
  local out=script_$RANDOM.mlx
  cp "$SAMPLE_DIR/resample_level8.mlx" "$out"
  for kv in "$@"; do
    sed -i "s/value=\"[^\"]*\" name=\"${kv%%=*}\"/value=\"${kv#*=}\" name=\"${kv%%=*}\"/" "$out"
  done
  echo "$out"
}

# write_ply FILE: a binary PLY with x y z nx ny nz from "x y z nx ny nz" lines on stdin.
write_ply() {
  python3 -c '
import struct, sys
rows = [list(map(float, l.split())) for l in sys.stdin if l.strip()]
with open(sys.argv[1], "wb") as f:
    f.write(("ply\nformat binary_little_endian 1.0\nelement vertex %d\n" % len(rows)).encode())
    for p in "x y z nx ny nz".split(): f.write(("property float %s\n" % p).encode())
    f.write(b"end_header\n")
    for r in rows: f.write(struct.pack("<6f", *r))
' "$1"
}
