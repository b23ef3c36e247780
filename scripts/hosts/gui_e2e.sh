#!/usr/bin/env bash
# End-to-end test of the project's plugins through the GUI of MeshLab 2022.02 or 2025.07 under
# Xvfb: builds the plugins (build_plugins.sh), then two GUI runs (gui_shot.sh) with the four
# plugins next to the host's own (io_base among them). Exit status non-zero on failure.
#
#   scripts/hosts/gui_e2e.sh 2022.02|2025.07
#
# 1. The GUI opens sample_data/bunny.ply; Filters > Point Set > Gaussian Sphere Feature-Sensitive
#    Resampling is clicked, its dialog's Apply pressed (Return), the dialog moved aside, the
#    bunny's layer hidden and the result screenshot; then File > Export Mesh As (Ctrl+Shift+E) for the layer "bunny.ply
#    resampled" (the file dialog is waited for by that title), the path of a .surfel typed,
#    the save-options dialog accepted (Return). Checks, on MeshLab's output (its log lines) and
#    the saved file: the filter's log line "34834 points -> N surfels" and "Applied filter",
#    "Saved Mesh" for that path, the file's header (element vertex N, N = HOSTS_BUNNY_SURFELS of
#    lib.sh, and the properties major_x ... minor_z of docs/surfel_format.md) and its records:
#    every surfel an ellipse (non-zero axes, the major one as long as the radius, the minor one
#    no longer and orthogonal to it).
# 2. A fresh GUI opens the saved .surfel; a screenshot of MeshLab's points, then Render >
#    Shaders > Ellipse Splatting and another. Checks, on the pixels of the 3D view
#    (tests/render/splat_gui_lib.sh): the splats cover more than 1.15 times the pixels the
#    points did, and they fill the gaps between the points: more than a fifth of the points'
#    pixels drawn only with splats, more than 5 times those drawn only with points.
# The menus' places per host are in gui_menus.sh. Writes its files to .deps/gui-e2e-VERSION/ and,
# when it passes with DOC_IMAGES=1, the first run's screenshot to docs/images/hosts-VERSION-gui-filter.png.
set -euo pipefail
here="$(dirname "${BASH_SOURCE[0]}")"
version="${1:?usage: gui_e2e.sh 2022.02|2025.07}"
"$here/build_plugins.sh" "$version"

source "$here/lib.sh"
source "$HOSTS_REPO/tests/render/splat_gui_lib.sh"
source "$here/gui_menus.sh"
hosts_gui_menus "$version"
started=$SECONDS
out="$HOSTS_REPO/.deps/gui-e2e-$version"
rm -rf "$out"
mkdir -p "$out"
plugins=()
for p in filter_gaussphere filter_surfel_error io_surfel render_ellipsesplat; do
  plugins+=(--plugin "$HOSTS_REPO/.deps/plugins-$version/lib$p.so")
done
# The GUI saves into $out, bound in the root at /opt/gui-e2e (gui_shot.sh keeps HOSTS_BINDS).
export HOSTS_BINDS="${HOSTS_BINDS:-} $out:/opt/gui-e2e"
saved=/opt/gui-e2e/resampled.surfel surfel="$out/resampled.surfel"
expected="$HOSTS_BUNNY_SURFELS"
status=0
fail() { echo "[gui_e2e] $version: FAIL: $*"; status=1; }

# 1. The filter from the menu on the bunny, the result exported as .surfel.
gui_status=0
"$here/gui_shot.sh" "$version" "$out/exported.png" "$HOSTS_REPO/sample_data/bunny.ply" "${plugins[@]}" \
  --wait-log "All files opened" "${GUI_FILTER_STEPS[@]}" --click "$GUI_FIRST_EYE" --shot "$out/filter.png" \
  --xdotool "key ctrl+shift+e" --window '^Save "bunny.ply resampled" Layer$' --xdotool "key ctrl+a" \
  --xdotool "type --delay 30 $saved" --xdotool "key Return" --window "^Choose Saving Options" \
  --xdotool "key Return" --wait-log "Saved Mesh $saved" || gui_status=$?
log="$out/exported.log"
[ "$gui_status" = 0 ] || fail "the GUI run with the bunny (gui_shot.sh status $gui_status: its lines above, log $log)"
resampled="$(sed -n 's/.*Gaussian sphere resampling: \([0-9]*\) points -> \([0-9]*\) surfels.*/\1 \2/p' "$log")"
echo "[gui_e2e] $version: filter from the menu: ${resampled:-no log line} (points -> surfels)"
[ "$resampled" = "34834 $expected" ] || fail "the filter's log line does not read 34834 points -> $expected surfels"
grep -qE "Applied filter:? Gaussian Sphere Feature-Sensitive Resampling" "$log" || fail "MeshLab did not log the filter as applied"
grep -q "Saved Mesh $saved" "$log" ||
  fail "MeshLab did not save the layer \"bunny.ply resampled\" as $saved (no \"Saved Mesh\" in $log)"

# The saved file: the header, then the records (68 bytes: 16 floats and the colour) as floats.
if [ -f "$surfel" ]; then
  header="$(head -c 4096 "$surfel" | sed -n '1,/^end_header/p')"
  count="$(sed -n 's/^element vertex \([0-9]*\)$/\1/p' <<< "$header")"
  properties="$(sed -n 's/^property float \(m[a-z]*_[xyz]\)$/\1/p' <<< "$header" | tr '\n' ' ')"
  echo "[gui_e2e] $version: saved $surfel: ${count:-no} surfels, ellipse properties: ${properties:-none}"
  [ "$count" = "$expected" ] || fail "the saved file announces ${count:-no} surfels, expected $expected"
  [ "$properties" = "major_x major_y major_z minor_x minor_y minor_z " ] || fail "the saved file's header lacks the ellipse properties"
  offset=$(( $(grep -abo '^end_header' <<< "$header" | cut -d: -f1) + 11 ))
  read -r records ellipses < <(od -An -v -tf4 -w68 -j "$offset" "$surfel" | awk '
    function dot(a, b, c, d, e, f) { return a * d + b * e + c * f }
    { n++; r = $7; M = sqrt(dot($8, $9, $10, $8, $9, $10)); m = sqrt(dot($11, $12, $13, $11, $12, $13));
      if (M > 0 && m > 0 && m <= M * 1.00001 && (M - r) ^ 2 <= (1e-5 * r) ^ 2 &&
          dot($8, $9, $10, $11, $12, $13) ^ 2 <= (1e-4 * M * m) ^ 2) ok++ }
    END { print n + 0, ok + 0 }')
  echo "[gui_e2e] $version: records $records, ellipses (major = radius, 0 < minor <= major, orthogonal) $ellipses"
  [ "$records" = "$count" ] && [ "$ellipses" = "$count" ] || fail "not every saved surfel is an ellipse"

  # 2. The .surfel in a fresh GUI, MeshLab's points, then the splats.
  gui_status=0
  "$here/gui_shot.sh" "$version" "$out/splats.png" "$surfel" "${plugins[@]}" \
    --wait-log "All files opened" --shot "$out/points.png" "${GUI_SPLAT_STEPS[@]}" || gui_status=$?
  [ "$gui_status" = 0 ] || fail "the GUI run with the .surfel (gui_shot.sh status $gui_status: its lines above)"
  grep -q "Opened mesh .*/resampled.surfel" "$out/splats.log" || fail "MeshLab did not open the .surfel"
  read -r olive grey < <(splat_pixel_classes "$out/points.png" "$GUI_VIEW")
  points=$((olive + grey))
  read -r olive grey < <(splat_pixel_classes "$out/splats.png" "$GUI_VIEW")
  splats=$((olive + grey))
  read -r filled emptied < <(splat_pixel_change "$out/points.png" "$out/splats.png" "$GUI_VIEW")
  echo "[gui_e2e] $version: pixels of the view: points $points, splats $splats;" \
       "drawn only with splats $filled, only with points $emptied"
  [ $((100 * splats)) -gt $((115 * points)) ] || fail "the splats do not cover much more than the points did"
  [ $((5 * filled)) -gt "$points" ] && [ "$filled" -gt $((5 * emptied)) ] ||
    fail "the splats do not fill the gaps between the points"
else
  fail "no file $surfel: the second GUI run (the .surfel reopened, Ellipse Splatting) is skipped"
fi
echo "[gui_e2e] $version: the GUI runs and the checks in $((SECONDS - started)) s"
[ "$status" = 0 ] || exit 1
# DOC_IMAGES=1 refreshes the documentation's screenshot; a test run leaves the tree as it is.
[ "${DOC_IMAGES:-0}" = 1 ] && cp "$out/filter.png" "$HOSTS_REPO/docs/images/hosts-$version-gui-filter.png"
echo "[gui_e2e] $version: PASS ($out/filter.png)"
