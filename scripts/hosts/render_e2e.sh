#!/usr/bin/env bash
# End-to-end GUI test of Ellipse Splatting in MeshLab 2022.02 or 2025.07: builds the plugins
# (build_plugins.sh), opens a sparse oriented point set (1500 points on a unit sphere with
# outward normals, tests/render/splat_gui_lib.sh) in the host's GUI under Xvfb with our render
# plugin (gui_shot.sh), takes a screenshot, switches Render > Shaders > Ellipse Splatting on with
# xdotool, moves the settings panel off the view and takes another. Exit status non-zero on
# failure. The menus' places per host are in gui_menus.sh.
#
#   scripts/hosts/render_e2e.sh 2022.02|2025.07
#
# Checks, on the pixels of the 3D view (tests/render/splat_gui_lib.sh: MeshLab's points are
# yellow, the splats grey): MeshLab drew the points before; after, its points are gone (fewer
# than 1/20 of the point pixels, plus 50) and the splats cover more than three times the pixels
# the points and the view's grey lines did. Then the same points without normals: MeshLab's
# points (more than 2000 pixels), no splats (grey under a tenth of the splats') and the plugin's
# warning, red in the log pane (more than 500 red pixels there). Writes its files to
# .deps/render-e2e-VERSION/ and, when it passes with DOC_IMAGES=1, the screenshot with the splats
# to docs/images/hosts-VERSION-splatting.png.
set -euo pipefail
here="$(dirname "${BASH_SOURCE[0]}")"
version="${1:?usage: render_e2e.sh 2022.02|2025.07}"
"$here/build_plugins.sh" "$version"

source "$here/lib.sh"
source "$HOSTS_REPO/tests/render/splat_gui_lib.sh"
source "$here/gui_menus.sh"
hosts_gui_menus "$version"

out="$HOSTS_REPO/.deps/render-e2e-$version"
mkdir -p "$out"
splat_sphere_ply "$out/sphere.ply"
splat_sphere_ply "$out/bare.ply" bare
splat_on() { # MESH AFTER.png [STEP]...: the GUI with MESH, Ellipse Splatting switched on
  local mesh=$1 shot=$2
  shift 2
  "$here/gui_shot.sh" "$version" "$shot" "$mesh" --plugin "$HOSTS_REPO/.deps/plugins-$version/librender_ellipsesplat.so" \
    "$@" "${GUI_SPLAT_STEPS[@]}"
}
splat_on "$out/sphere.ply" "$out/after.png" --shot "$out/before.png"
splat_on "$out/bare.ply" "$out/bare.png"

read -r olive_before grey_before < <(splat_pixel_classes "$out/before.png" "$GUI_VIEW")
read -r olive_after grey_after < <(splat_pixel_classes "$out/after.png" "$GUI_VIEW")
read -r olive_bare grey_bare < <(splat_pixel_classes "$out/bare.png" "$GUI_VIEW")
red_log="$(convert "$out/bare.png" -crop "$GUI_LOG" -depth 8 txt:- |
  awk -F'[(),]' 'NR > 1 && $3 - $4 > 100 && $3 - $5 > 100 { red++ } END { print red + 0 }')"
echo "[render_e2e] $version: pixels of the view: before: points $olive_before, grey $grey_before;" \
     "after: points $olive_after, splats (grey) $grey_after; without normals: points $olive_bare, grey $grey_bare," \
     "red in the log pane $red_log"
status=0
fail() { echo "[render_e2e] $version: FAIL: $*"; status=1; }
[ "$olive_before" -gt 2000 ] || fail "MeshLab did not draw the point set before splatting"
[ "$olive_after" -lt $((olive_before / 20 + 50)) ] || fail "MeshLab's points are still drawn after switching splatting on"
[ "$grey_after" -gt $((3 * (olive_before + grey_before))) ] || fail "the splats do not cover much more than the points did"
[ "$olive_bare" -gt 2000 ] && [ "$grey_bare" -lt $((grey_after / 10)) ] ||
  fail "the points without normals are not drawn by MeshLab alone"
[ "$red_log" -gt 500 ] || fail "no warning in the log pane for points without normals"
[ "$status" = 0 ] || exit 1
# DOC_IMAGES=1 refreshes the documentation's screenshot; a test run leaves the tree as it is.
[ "${DOC_IMAGES:-0}" = 1 ] && cp "$out/after.png" "$HOSTS_REPO/docs/images/hosts-$version-splatting.png"
echo "[render_e2e] $version: PASS ($out/after.png)"
