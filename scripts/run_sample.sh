#!/usr/bin/env bash
# Sets up (Debian packages, MeshLab source), builds the plugins, and resamples the shipped
# bunny with the shipped level-8 script through meshlabserver, from a staged prefix (no
# change to /usr). Prints where the results are, a picture among them: the input points, the
# surfels as points, and the surfels as three-pass ellipse splats, side by side.
#   bash scripts/run_sample.sh [INPUT.ply [SCRIPT.mlx]]
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${BUILD_DIR:-$here/build}"
input="$(realpath "${1:-$here/sample_data/bunny.ply}")"
script="$(realpath "${2:-$here/sample_data/resample_level8.mlx}")"
out="$here/out"
bash "$here/scripts/setup.sh"
cmake -S "$here" -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" -j "$(nproc)" --target stage splat_render
mkdir -p "$out"
name="$(basename "$input" .ply)"
# Transparent huge pages for the host's heap too (README: Performance).
export GLIBC_TUNABLES=glibc.malloc.hugetlb=1
# OpenMP threads that wait sleep instead of spinning, which matters beside other work on the
# machine (README: Performance).
export OMP_WAIT_POLICY="${OMP_WAIT_POLICY:-passive}"
server=(xvfb-run -a -s "-screen 0 1280x1024x24" "$build/stage/bin/meshlabserver")
# .surfel keeps the ellipse axes; the PLY copy (normals, radii) opens in any viewer.
"${server[@]}" -i "$input" -s "$script" -o "$out/${name}_resampled.surfel" > "$out/${name}_resampled.log" 2>&1 ||
  { echo "meshlabserver failed, see $out/${name}_resampled.log" >&2; exit 1; }
"${server[@]}" -i "$out/${name}_resampled.surfel" -o "$out/${name}_resampled.ply" -m vn vq vr >/dev/null 2>&1
sed -n "s/.*LOG: [0-9] //p" "$out/${name}_resampled.log"
# The picture: one camera for the three panels (splat_render frames each input alike).
render() { xvfb-run -a -s "-screen 0 1280x1024x24" "$build/tools/splat_render/splat_render" "$@" --width 480 --height 480 >/dev/null 2>&1; }
render "$input" -o "$out/${name}_input_points.png" --mode points &&
  render "$out/${name}_resampled.surfel" -o "$out/${name}_surfel_points.png" --mode points &&
  render "$out/${name}_resampled.surfel" -o "$out/${name}_splats.png" --mode threepass &&
  convert "$out/${name}_input_points.png" "$out/${name}_surfel_points.png" "$out/${name}_splats.png" +append \
    "$out/${name}_resampled.png" ||
  { echo "the picture could not be rendered (splat_render under xvfb-run)" >&2; exit 1; }
rm -f "$out/${name}_input_points.png" "$out/${name}_surfel_points.png" "$out/${name}_splats.png"
echo "Results:"
echo "  $out/${name}_resampled.surfel  (surfels with ellipse axes; open in MeshLab with the plugins installed)"
echo "  $out/${name}_resampled.ply     (positions fitted to the blend, normals, represented points as quality, radii)"
echo "  $out/${name}_resampled.log     (meshlabserver log)"
echo "  $out/${name}_resampled.png     (input points | surfels as points | three-pass ellipse splats)"
