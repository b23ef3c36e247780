#!/usr/bin/env bash
# End-to-end test of the .surfel IO plugin and the surfel error filter in MeshLab 2022.02 or
# 2025.07: builds the plugins (build_plugins.sh), then io_run (oot/io_run.cpp) loads the host's
# io_base and the project's plugins through the host's PluginManager and, with the host's own
# loader and saver (the IO plugin looked up by extension):
#   resamples sample_data/bunny.ply (the filter's defaults), saves the new layer as .surfel,
#   opens it again and compares it with the saved layer: vertex count, positions, normals, radii,
#   quality, colour, EllipseMajorAxis, EllipseMinorAxis, SurfelFitOffset, SurfelBlendScale;
#   opens hostile .surfel files (truncated, NaN position, infinite normal, not a PLY) and saves a
#   layer with a NaN position: each must throw MLException with the reader's one-line reason;
#   runs "Surfel Approximation Error" on the resampled and on the reopened layer against the
#   bunny: both must log the same figures.
# Exit status non-zero on any failure (a crash included); prints the figures.
#
#   scripts/hosts/io_e2e.sh 2022.02|2025.07
#
# Output: .deps/plugins-VERSION/io_e2e.txt, the files in .deps/plugins-VERSION/io_e2e/.
set -euo pipefail
here="$(dirname "${BASH_SOURCE[0]}")"
version="${1:?usage: io_e2e.sh 2022.02|2025.07}"
"$here/build_plugins.sh" "$version"

source "$here/lib.sh"
source "$here/host_env.sh"
hosts_plugins_select "$version"
out="$PLUGINS_BUILD/io_e2e.txt"
rm -rf "$PLUGINS_BUILD/io_e2e"
mkdir -p "$PLUGINS_BUILD/io_e2e"
status=0
b=/opt/gaussphere-build
hosts_in_root "${PLUGINS_PROBE_ENV[@]}" $b/io_run /opt/gaussphere/sample_data/bunny.ply $b/io_e2e \
  "$HOST_PLUGINS/libio_base.so" $b/libfilter_gaussphere.so $b/libio_surfel.so $b/libfilter_surfel_error.so \
  >"$out" 2>&1 || status=$?
cat "$out"

fail() { echo "[io_e2e] $version: FAIL: $*"; exit 1; }
[ "$status" = 0 ] || fail "io_run exited with $status, $(grep -c ': FAIL, ' "$out" || true) failed check(s)"
grep -q '^all checks passed$' "$out" || fail "io_run did not finish its checks"
checks=$(grep -c '^check .*: ok, ' "$out")
[ "$checks" -ge 20 ] || fail "only $checks checks ran"
saved="$(sed -n 's/^saved \([0-9]*\) surfels to .*, \([0-9]*\) bytes$/\1 surfels, \2 bytes/p' "$out")"
refused=$(grep -c '^check hostile .*: ok, MLException: ' "$out")
echo "[io_e2e] $version: PASS: $checks checks; saved and reopened $saved, equal; $refused hostile cases refused"
grep '^check hostile .*: ok, MLException: ' "$out" | sed 's/^check /[io_e2e]   /'
grep '^log .*: Surfel error' "$out" | sed 's/^log [0-9]*: /[io_e2e]   /'
