#!/bin/bash
# GUI end-to-end test: the staged MeshLab opens a sparse oriented point set, "Ellipse
# Splatting" is switched on through Render > Shaders with xdotool, and screenshots before and
# after show MeshLab's own points replaced by closed, grey-lit splats.
#   meshlab_gui_splatting.sh <staged bin/meshlab> <output folder>
# Runs itself under xvfb-run at 1280x900, the size the menu coordinates below were taken at.
set -euo pipefail
MESHLAB=$1
OUT=$2
if [ -z "${SPLAT_GUI_TEST_IN_XVFB:-}" ]; then
  export SPLAT_GUI_TEST_IN_XVFB=1
  exec xvfb-run -a -s "-screen 0 1280x900x24" "$0" "$@"
fi
[ -x "$MESHLAB" ] || { echo "no staged MeshLab at $MESHLAB: build the 'stage' target"; exit 1; }
mkdir -p "$OUT"

# 1500 points on a unit sphere with outward normals: sparse enough for gaps between points.
awk 'BEGIN {
  n = 1500; golden = 3.14159265 * (3 - sqrt(5));
  print "ply\nformat ascii 1.0\nelement vertex " n;
  print "property float x\nproperty float y\nproperty float z";
  print "property float nx\nproperty float ny\nproperty float nz\nend_header";
  for (i = 0; i < n; i++) {
    y = 1 - 2 * (i + 0.5) / n; r = sqrt(1 - y * y);
    x = r * cos(golden * i); z = r * sin(golden * i);
    printf "%f %f %f %f %f %f\n", x, y, z, x, y, z;
  }
}' > "$OUT/sphere.ply"

"$MESHLAB" "$OUT/sphere.ply" > "$OUT/meshlab.log" 2>&1 &
MESHLAB_PID=$!
trap 'kill $MESHLAB_PID 2>/dev/null || true' EXIT
sleep 10
import -window root "$OUT/before.png"

xdotool mousemove 178 10 click 1   # Render
sleep 1
xdotool mousemove 205 34 click 1   # Shaders
sleep 1
xdotool mousemove 560 34           # along the submenu's first row, so the submenu stays open
sleep 0.5
xdotool mousemove 590 59 click 1   # Ellipse Splatting (the first plugin entry, below None)
sleep 3
# The settings panel floats over the view: move it aside before the screenshot.
for window in $(xdotool search --name "^Ellipse Splatting$" 2>/dev/null); do
  xdotool windowmove "$window" 900 120
done
sleep 2
import -window root "$OUT/after.png"

# Counts pixels of the 3D view (x 0-432, y 72-598, above the info box) by colour class:
# MeshLab's default point colour is olive (red well above blue), the splats' default is grey,
# the background gradient is blue.
classify() {
  convert "$1" -crop 433x527+0+72 -depth 8 txt:- | awk -F'[(),]' 'NR > 1 {
    r = $3; b = $5;
    if (r - b > 25) olive++; else if (b - r <= 25 && r > 30) grey++;
  } END { printf "%d %d\n", olive, grey }'
}
read -r OLIVE_BEFORE GREY_BEFORE < <(classify "$OUT/before.png")
read -r OLIVE_AFTER GREY_AFTER < <(classify "$OUT/after.png")
echo "before: olive $OLIVE_BEFORE grey $GREY_BEFORE; after: olive $OLIVE_AFTER grey $GREY_AFTER"

status=0
check() { if ! eval "$1"; then echo "FAILED: $2"; status=1; fi; }
check "[ $OLIVE_BEFORE -gt 2000 ]" "MeshLab did not draw the point set before splatting"
check "[ $OLIVE_AFTER -lt $((OLIVE_BEFORE / 20 + 50)) ]" "MeshLab's points are still drawn after switching splatting on"
check "[ $GREY_AFTER -gt $((3 * (OLIVE_BEFORE + GREY_BEFORE))) ]" "splats do not cover much more than the points did"
check "! grep -q 'not supported' '$OUT/meshlab.log'" "MeshLab reports the shader as unsupported"
exit $status
