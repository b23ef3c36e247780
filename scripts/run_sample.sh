#!/usr/bin/env bash
# Sets up (Debian packages, MeshLab source), builds the plugins, and resamples the shipped
# bunny with the shipped level-8 script through meshlabserver, from a staged prefix (no
# change to /usr). Prints where the results are.
#   bash scripts/run_sample.sh [INPUT.ply [SCRIPT.mlx]]
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${BUILD_DIR:-$here/build}"
input="$(realpath "${1:-$here/sample_data/bunny.ply}")"
script="$(realpath "${2:-$here/sample_data/resample_level8.mlx}")"
out="$here/out"
bash "$here/scripts/setup.sh"
cmake -S "$here" -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" -j "$(nproc)" --target stage
mkdir -p "$out"
name="$(basename "$input" .ply)"
server=(xvfb-run -a -s "-screen 0 1280x1024x24" "$build/stage/bin/meshlabserver")
# .surfel keeps the ellipse axes; the PLY copy (normals, radii) opens in any viewer.
"${server[@]}" -i "$input" -s "$script" -o "$out/${name}_resampled.surfel" > "$out/${name}_resampled.log" 2>&1 ||
  { echo "meshlabserver failed, see $out/${name}_resampled.log" >&2; exit 1; }
"${server[@]}" -i "$out/${name}_resampled.surfel" -o "$out/${name}_resampled.ply" -m vn vr >/dev/null 2>&1
sed -n "s/.*LOG: [0-9] //p" "$out/${name}_resampled.log"
echo "Results:"
echo "  $out/${name}_resampled.surfel  (surfels with ellipse axes; open in MeshLab with the plugins installed)"
echo "  $out/${name}_resampled.ply     (positions fitted to the blend, normals, radii)"
echo "  $out/${name}_resampled.log     (meshlabserver log)"
