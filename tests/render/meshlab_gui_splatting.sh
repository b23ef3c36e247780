#!/bin/bash
# GUI end-to-end test: the staged MeshLab opens a sparse oriented point set, "Ellipse
# Splatting" is switched on through Render > Shaders with xdotool, and screenshots before and
# after show MeshLab's own points replaced by closed, grey-lit splats. Then the same sphere as a
# .surfel layer whose surfels carry a fit offset of half the radius (SurfelFitOffset): the splats
# are drawn at P - offset N, a sphere of half the radius in the same frame (the layer's box), and
# at P again once the panel's "Draw at fitted positions" is ticked. Then the sphere with points
# that cannot be drawn mixed in (NaN, infinite and zero normals): they are skipped and logged,
# the sphere is drawn as before; and with positions near 3e38 too (they throw MeshLab's own
# bounding box and view off): MeshLab keeps running. (MeshLab itself deletes vertices with NaN
# or infinite positions on loading, behind a modal dialog: tests/render/hostile_input_test.cpp
# covers those in the renderer.)
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

source "$(dirname "$0")/splat_gui_lib.sh"
splat_sphere_ply "$OUT/sphere.ply"

# The same points as a .surfel file (docs/surfel_format.md, version 3): tangent ellipses of
# semi-axes 0.1 and 0.08, every fit offset 0.5.
python3 - "$OUT/sphere.ply" "$OUT/sphere_fitted.surfel" <<'PY'
import math, struct, sys
rows = [list(map(float, l.split())) for l in open(sys.argv[1]).read().split("end_header\n")[1].split("\n") if l.strip()]
props = "x y z nx ny nz radius major_x major_y major_z minor_x minor_y minor_z quality blend_scale fit_offset".split()
header = ["ply", "format binary_little_endian 1.0", "comment gaussphere-surfel 3", "element vertex %d" % len(rows)]
header += ["property float " + p for p in props] + ["property uchar " + c for c in ("red", "green", "blue", "alpha")]
with open(sys.argv[2], "wb") as f:
    f.write(("\n".join(header + ["end_header"]) + "\n").encode())
    for x, y, z, nx, ny, nz in rows:
        helper = (1, 0, 0) if abs(nx) < 0.9 else (0, 1, 0)
        u = (ny * helper[2] - nz * helper[1], nz * helper[0] - nx * helper[2], nx * helper[1] - ny * helper[0])
        length = math.sqrt(sum(c * c for c in u)); u = [c / length for c in u]
        v = (ny * u[2] - nz * u[1], nz * u[0] - nx * u[2], nx * u[1] - ny * u[0])
        f.write(struct.pack("<16f4B", x, y, z, nx, ny, nz, 0.1, *[0.1 * c for c in u], *[0.08 * c for c in v],
                            1, 1, 0.5, 255, 255, 255, 255))
PY

# The sphere with points that cannot be drawn inserted after its first point: NaN, infinite and
# zero normals (positions inside the sphere); in sphere_far.ply also positions near 3e38.
python3 - "$OUT/sphere.ply" "$OUT/sphere_hostile.ply" "$OUT/sphere_far.ply" <<'PY'
import struct, sys
rows = [list(map(float, l.split())) for l in open(sys.argv[1]).read().split("end_header\n")[1].split("\n") if l.strip()]
nan, inf = float("nan"), float("inf")
hostile = [[0.3, 0.3, 0.3, nan, 0, 1], [0.3, 0.3, 0.3, 0, inf, 0], [0.2, 0.1, 0.3, 0, 0, 0]]
far = [[3e38, 3e38, 3e38, 0, 0, 1], [-3e38, 1, 1, 0, 0, 1]]
for path, extra in ((sys.argv[2], hostile), (sys.argv[3], hostile + far)):
    points = rows[:1] + extra + rows[1:]
    header = "ply\nformat binary_little_endian 1.0\nelement vertex %d\n" % len(points)
    header += "".join("property float %s\n" % p for p in ("x", "y", "z", "nx", "ny", "nz")) + "end_header\n"
    with open(path, "wb") as f:
        f.write(header.encode())
        for point in points:
            f.write(struct.pack("<6f", *point))
PY

# Opens FILE in the staged MeshLab, screenshots the window to BEFORE.png (if given), switches
# Ellipse Splatting on through the menus and screenshots AFTER.png; with TICKED.png, ticks "Draw
# at fitted positions" in the settings panel and screenshots again; closes MeshLab.
splat_screenshots() { # FILE LOG AFTER.png [BEFORE.png] [TICKED.png]
  "$MESHLAB" "$1" > "$2" 2>&1 &
  MESHLAB_PID=$!
  sleep 10
  if [ -n "${4:-}" ]; then import -window root "$4"; fi
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
  import -window root "$3"
  if [ -n "${5:-}" ]; then
    xdotool mousemove 1105 307 click 1   # the panel's last row: Draw at fitted positions
    sleep 2
    import -window root "$5"
  fi
  if kill -0 $MESHLAB_PID 2>/dev/null; then MESHLAB_RAN=1; else MESHLAB_RAN=0; fi
  kill $MESHLAB_PID 2>/dev/null || true
  wait $MESHLAB_PID 2>/dev/null || true
}
trap 'kill $MESHLAB_PID 2>/dev/null || true' EXIT
splat_screenshots "$OUT/sphere.ply" "$OUT/meshlab.log" "$OUT/after.png" "$OUT/before.png"
splat_screenshots "$OUT/sphere_fitted.surfel" "$OUT/meshlab_fitted.log" "$OUT/fitted.png" "" "$OUT/fitted_at_p.png"
splat_screenshots "$OUT/sphere_hostile.ply" "$OUT/meshlab_hostile.log" "$OUT/hostile.png"
HOSTILE_RAN=$MESHLAB_RAN
splat_screenshots "$OUT/sphere_far.ply" "$OUT/meshlab_far.log" "$OUT/far.png"
FAR_RAN=$MESHLAB_RAN

# Pixels of the 3D view (x 0-432, y 72-598, above the info box) by colour class.
classify() { splat_pixel_classes "$1" 433x527+0+72; }
read -r OLIVE_BEFORE GREY_BEFORE < <(classify "$OUT/before.png")
read -r OLIVE_AFTER GREY_AFTER < <(classify "$OUT/after.png")
read -r OLIVE_FITTED GREY_FITTED < <(classify "$OUT/fitted.png")
read -r OLIVE_AT_P GREY_AT_P < <(classify "$OUT/fitted_at_p.png")
read -r OLIVE_HOSTILE GREY_HOSTILE < <(classify "$OUT/hostile.png")
echo "before: olive $OLIVE_BEFORE grey $GREY_BEFORE; after: olive $OLIVE_AFTER grey $GREY_AFTER;" \
     ".surfel with fit offsets 0.5: grey $GREY_FITTED, drawn at the fitted positions: grey $GREY_AT_P;" \
     "with points that cannot be drawn: grey $GREY_HOSTILE"

status=0
check() { if ! eval "$1"; then echo "FAILED: $2"; status=1; fi; }
check "[ $OLIVE_BEFORE -gt 2000 ]" "MeshLab did not draw the point set before splatting"
check "[ $OLIVE_AFTER -lt $((OLIVE_BEFORE / 20 + 50)) ]" "MeshLab's points are still drawn after switching splatting on"
check "[ $GREY_AFTER -gt $((3 * (OLIVE_BEFORE + GREY_BEFORE))) ]" "splats do not cover much more than the points did"
check "! grep -q 'not supported' '$OUT/meshlab.log'" "MeshLab reports the shader as unsupported"
# Half the radius: about a quarter of the area (the splats' rims add a little).
check "[ $GREY_FITTED -gt 1000 ] && [ $GREY_FITTED -lt $((GREY_AFTER / 2)) ]" \
  "the .surfel layer's splats are not drawn at their unfitted positions (P - SurfelFitOffset N)"
check "[ $GREY_AT_P -gt $((3 * GREY_FITTED)) ]" "ticking 'Draw at fitted positions' does not draw the splats at P"
check "[ $HOSTILE_RAN = 1 ] && [ $FAR_RAN = 1 ]" "MeshLab did not survive points that cannot be drawn"
check "grep -q \"has 3 points that cannot be drawn\" '$OUT/meshlab_hostile.log'" "the 3 points that cannot be drawn are not logged"
check "grep -q \"has 5 points that cannot be drawn\" '$OUT/meshlab_far.log'" "the 5 points that cannot be drawn (far ones too) are not logged"
check "[ $((100 * GREY_HOSTILE)) -gt $((98 * GREY_AFTER)) ] && [ $((100 * GREY_HOSTILE)) -lt $((102 * GREY_AFTER)) ]" \
  "the sphere with points that cannot be drawn is not drawn as the sphere alone"
exit $status
