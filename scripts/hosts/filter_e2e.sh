#!/usr/bin/env bash
# End-to-end test of the resampling filter in MeshLab 2022.02 or 2025.07: builds the plugins
# (build_plugins.sh), then filter_run loads the host's io_base and our plugin through the host's
# PluginManager, opens sample_data/bunny.ply with the host's loader, applies the filter with its
# dialog defaults (no GL context), and this script checks the result. Exit status non-zero on
# failure.
#
#   scripts/hosts/filter_e2e.sh 2022.02|2025.07
#
# Checks: a new current layer "bunny.ply resampled" with HOSTS_BUNNY_SURFELS vertices (lib.sh:
# what gsresample gives for the bunny at the defaults; EXPECTED_SURFELS overrides), with the per-vertex attributes
# EllipseMajorAxis and EllipseMinorAxis, and the filter's log line.
set -euo pipefail
here="$(dirname "${BASH_SOURCE[0]}")"
version="${1:?usage: filter_e2e.sh 2022.02|2025.07}"
"$here/build_plugins.sh" "$version"

source "$here/lib.sh"
source "$here/host_env.sh"
hosts_plugins_select "$version"
out="$PLUGINS_BUILD/filter_e2e.txt"
status=0
hosts_in_root "${PLUGINS_PROBE_ENV[@]}" /opt/gaussphere-build/filter_run /opt/gaussphere/sample_data/bunny.ply \
  "Gaussian Sphere Feature-Sensitive Resampling" "$HOST_PLUGINS/libio_base.so" \
  /opt/gaussphere-build/libfilter_gaussphere.so >"$out" 2>&1 || status=$?
cat "$out"

fail() { echo "[filter_e2e] $version: FAIL: $*"; exit 1; }
[ "$status" = 0 ] || fail "filter_run exited with $status"
layer="$(grep '^layer .* "bunny.ply resampled": ' "$out")" || fail "no layer \"bunny.ply resampled\""
surfels="$(sed -n 's/^layer [0-9]* "bunny.ply resampled": \([0-9]*\) vertices.*/\1/p' "$out")"
expected="$HOSTS_BUNNY_SURFELS"
[ "$surfels" = "$expected" ] || fail "$surfels surfels, expected $expected"
case "$layer" in *" current,"*) ;; *) fail "the new layer is not the current one" ;; esac
for a in EllipseMajorAxis EllipseMinorAxis; do
  case "$layer" in *" $a"*) ;; *) fail "no per-vertex attribute $a on the new layer" ;; esac
done
grep -q 'points -> [0-9]* surfels' "$out" || fail "no log line of the run"
echo "[filter_e2e] $version: PASS: $surfels surfels with EllipseMajorAxis and EllipseMinorAxis"
