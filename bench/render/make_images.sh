#!/usr/bin/env bash
# Makes the README pictures in docs/images/ (PNG montages, 640x640 panels):
#   dragon_mesh_points_splats.png, bunny_mesh_points_splats.png: original mesh | plain points of
#     the level-8 resampled set | three-pass ellipse splats of it (same camera and lighting),
#   dragon_closeup.png: zoom 3 on the middle of the dragon: mesh | points | one-pass | three-pass
#     (480x480 panels),
#   clusters.png: the input points coloured by cluster (ColorizeClusters), shown on the mesh
#     (same vertices in the same order) for the bunny and (zoom 3) the dragon.
# Surfels are drawn in the mesh's grey and framed like the mesh (bench/render/render_bench.py frame).
#   bash bench/render/make_images.sh        (BUILD_DIR, DATA_DIR, PYTHON as in scripts/bench_render.sh)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
build="${BUILD_DIR:-$here/build}"
data="${DATA_DIR:-$here/../shared/data}"
if [ -z "${BENCH_RENDER_UNDER_XVFB:-}" ]; then
  BENCH_RENDER_UNDER_XVFB=1 exec xvfb-run -a -s "-screen 0 1280x1024x24" bash "${BASH_SOURCE[0]}" "$@"
fi
source "$here/bench/render/find_python.sh"
find_numpy_python make_images.sh
tool="$here/bench/render/render_bench.py"
server="$build/stage/bin/meshlabserver"
render="$build/tools/splat_render/splat_render"
# The .mlx scripts of the tree the build was configured from (their parameters match its plugin).
src="$(sed -n 's/^CMAKE_HOME_DIRECTORY:INTERNAL=//p' "$build/CMakeCache.txt" 2>/dev/null || true)"
mlx_dir="$here/sample_data"
[ -n "$src" ] && [ -f "$src/sample_data/resample_level8.mlx" ] && mlx_dir="$src/sample_data"
images="$here/docs/images"
work="$here/bench/render/scratch/images"
mkdir -p "$images" "$work"
px=640

# sample_data/resample_colorize.mlx (the filter colours the input layer by cluster), then make the
# input layer current again so that meshlabserver saves it.
sed 's#</FilterScript>#<filter name="Change the current layer">\n  <Param type="RichMesh" value="0" name="layer"/>\n </filter>\n</FilterScript>#' \
  "$mlx_dir/resample_colorize.mlx" > "$work/colorize_input.mlx"

# shot MODEL NAME FILE MODE AZ EL ZOOM [options]
shot() {
  local model="$1" name="$2" file="$3" mode="$4" az="$5" el="$6" zoom="$7"; shift 7  # size: $px
  "$render" "$file" -o "$work/${model}_${name}.png" --mode "$mode" --width "$px" --height "$px" \
    --azimuth "$az" --elevation "$el" --zoom "$zoom" "$@" 2>/dev/null
}

for spec in "dragon 20 20 1.25" "bunny -30 15 1.25"; do
  set -- $spec
  model="$1" az="$2" el="$3" zoom="$4"
  points="$data/$model.ply" mesh="$data/${model}_mesh.ply"
  if [ ! -f "$points" ] || [ ! -f "$mesh" ]; then echo "skipping $model: input or mesh not found in $data"; continue; fi
  "$server" -i "$points" -s "$mlx_dir/resample_level8.mlx" -o "$work/$model.surfel" > "$work/$model.log" 2>&1 ||
    { echo "meshlabserver failed on $model, see $work/$model.log" >&2; exit 1; }
  "$py" "$tool" frame "$work/$model.surfel" "$mesh" "$work/${model}_framed.surfel" "$work/${model}_framed_mesh.ply" > /dev/null
  surfels="$(sed -n 's/^element vertex \([0-9]*\).*/\1/p' <(head -c 2000 "$work/$model.surfel"))"
  inputs="$(sed -n 's/^element vertex \([0-9]*\).*/\1/p' <(head -c 2000 "$points"))"
  shot "$model" mesh "$work/${model}_framed_mesh.ply" mesh "$az" "$el" "$zoom"
  shot "$model" points "$work/${model}_framed.surfel" points "$az" "$el" "$zoom"
  shot "$model" threepass "$work/${model}_framed.surfel" threepass "$az" "$el" "$zoom"
  "$py" "$tool" montage "$images/${model}_mesh_points_splats.png" \
    "original mesh ($inputs vertices)=$work/${model}_mesh.png" \
    "$surfels resampled points (3 px)=$work/${model}_points.png" \
    "three-pass ellipse splats=$work/${model}_threepass.png"
  if [ "$model" = dragon ]; then
    for mode in mesh points onepass threepass; do
      file="$work/${model}_framed.surfel"; [ "$mode" = mesh ] && file="$work/${model}_framed_mesh.ply"
      px=480 shot "$model" "close_$mode" "$file" "$mode" "$az" "$el" 3
    done
    "$py" "$tool" montage "$images/dragon_closeup.png" --panel=480 "mesh=$work/dragon_close_mesh.png" \
      "points=$work/dragon_close_points.png" "one-pass (opaque) splats=$work/dragon_close_onepass.png" \
      "three-pass splats=$work/dragon_close_threepass.png"
  fi
  # The input coloured by cluster, saved by meshlabserver; the colours go onto the mesh (same
  # vertices in the same order, ../shared/data/README.md).
  "$server" -i "$points" -s "$work/colorize_input.mlx" -o "$work/${model}_clusters.ply" -m vc vn \
    > "$work/${model}_clusters.log" 2>&1 || { echo "meshlabserver (colorize) failed on $model" >&2; exit 1; }
  "$py" "$tool" colorize "$mesh" "$work/${model}_clusters.ply" "$work/${model}_clusters_mesh.ply"
  czoom="$zoom"; [ "$model" = dragon ] && czoom=3  # the dragon's clusters are too small to see whole
  shot "$model" clusters "$work/${model}_clusters_mesh.ply" mesh "$az" "$el" "$czoom"
  clusters="$(sed -n 's/.*Gaussian sphere resampling: [0-9]* points -> \([0-9]*\) surfels.*/\1/p' "$work/${model}_clusters.log" | tail -1)"
  echo "$model: $clusters clusters of $inputs points" >> "$work/clusters.txt"
done
args=()
for model in bunny dragon; do
  [ -f "$work/${model}_clusters.png" ] || continue
  n="$(sed -n "s/^$model: \([0-9]*\) clusters of \([0-9]*\).*/\2 points, \1 clusters/p" "$work/clusters.txt" | tail -1)"
  label="$model"; [ "$model" = dragon ] && label="dragon (zoom 3)"
  args+=("$label: $n=$work/${model}_clusters.png")
done
[ ${#args[@]} -eq 0 ] || "$py" "$tool" montage "$images/clusters.png" "${args[@]}"
rm -f "$work/clusters.txt"
ls -la "$images"
