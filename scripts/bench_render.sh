#!/usr/bin/env bash
# Rendering benchmark of the ellipse splatting (paper section 4) against the original meshes.
#
# For every model (default: dragon igea from ../shared/data; absent ones are skipped with the
# reason): resample MODEL.ply through the staged meshlabserver with a sample_data script
# (default resample_level8.mlx) into a .surfel file, then render from several views at
# 1024x1024 with tools/splat_render, all under one Xvfb (Mesa llvmpipe):
#   - the original full mesh MODEL_mesh.ply (--mode mesh, Phong) as the reference,
#   - the surfels as three-pass splats, one-pass opaque splats and plain 3-pixel points,
# with the same camera and lighting, and measure per view and mode the coverage of the mesh's
# silhouette, the pixels drawn outside it, the PSNR against the mesh image and the time per
# frame. Writes bench/render/results.md and results.csv (definitions: bench/render/README.md).
#
#   bash scripts/bench_render.sh [--models "dragon igea"] [--views "0/15 90/20 ..."] [--bench N]
#                                [--size PX] [--no-variations] [--out DIR] [--script NAME.mlx]
# --script: the sample_data script that resamples (default resample_level8.mlx), e.g.
# resample_max_error.mlx to see the coverage of the error bound's output; the
# results then go to bench/render/<script name>/ unless --out says otherwise.
# Environment: BUILD_DIR (default build/), DATA_DIR (default ../shared/data), PYTHON.
# Needs the built targets `stage` and `splat_render` (it does not configure or build), Xvfb,
# and python3 with numpy and matplotlib (Debian: python3-numpy python3-matplotlib).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${BUILD_DIR:-$here/build}"
data="${DATA_DIR:-$here/../shared/data}"
models="dragon igea"
views="0/15 90/20 180/15 270/20 45/60"
bench_frames=5
size=1024
variations=1
out="$here/bench/render"
script=resample_level8.mlx
while [ $# -gt 0 ]; do
  case "$1" in
    --models) models="$2"; shift 2 ;;
    --views) views="$2"; shift 2 ;;
    --bench) bench_frames="$2"; shift 2 ;;
    --size) size="$2"; shift 2 ;;
    --no-variations) variations=0; shift ;;
    --out) out="$(mkdir -p "$2" && cd "$2" && pwd)"; shift 2 ;;
    --script) script="$2"; shift 2
              [ "$script" = resample_level8.mlx ] || [ "$out" != "$here/bench/render" ] ||
                out="$here/bench/render/${script%.mlx}" ;;
    -h|--help) sed -n '2,20p' "${BASH_SOURCE[0]}"; exit 0 ;;
    *) echo "bench_render.sh: unknown option $1" >&2; exit 2 ;;
  esac
done

# One Xvfb for the whole run (meshlabserver needs a display too).
if [ -z "${BENCH_RENDER_UNDER_XVFB:-}" ]; then
  command -v xvfb-run >/dev/null || { echo "bench_render.sh: xvfb-run not found (Debian: xvfb xauth)" >&2; exit 1; }
  BENCH_RENDER_UNDER_XVFB=1 exec xvfb-run -a -s "-screen 0 1280x1024x24" bash "${BASH_SOURCE[0]}" \
    --models "$models" --views "$views" --bench "$bench_frames" --size "$size" --out "$out" --script "$script" \
    $([ "$variations" = 1 ] || echo --no-variations)
fi

source "$here/bench/render/find_python.sh"
find_numpy_python bench_render.sh
tool="$here/bench/render/render_bench.py"
server="$build/stage/bin/meshlabserver"
render="$build/tools/splat_render/splat_render"
for f in "$server" "$render"; do
  [ -x "$f" ] || { echo "bench_render.sh: $f missing: build the targets stage and splat_render first" >&2; exit 1; }
done

# The .mlx scripts of the tree the build was configured from (their parameters match its plugin).
src="$(sed -n 's/^CMAKE_HOME_DIRECTORY:INTERNAL=//p' "$build/CMakeCache.txt" 2>/dev/null || true)"
mlx_dir="$here/sample_data"
[ -n "$src" ] && [ -f "$src/sample_data/$script" ] && mlx_dir="$src/sample_data"
[ -f "$mlx_dir/$script" ] || { echo "bench_render.sh: $mlx_dir/$script not found" >&2; exit 2; }
work="$out/scratch/runs"
rm -rf "$work"
mkdir -p "$work"
: > "$work/runs.tsv"
started=$(date +%s)

# render MODEL VIEW MODE VARIANT FILE [splat_render options...]: one image, its mask, and the
# time per frame of --bench frames; appends a line to runs.tsv.
render_one() {
  local model="$1" view="$2" mode="$3" variant="$4" file="$5"; shift 5
  local az="${view%/*}" el="${view#*/}" tag="${model}_${view/\//_}_${mode}${variant:+_${variant// /}}"
  tag="${tag//--/}"
  local log="$work/$tag.log" ms frames="$bench_frames"
  [ -z "$variant" ] || frames=$(( (bench_frames + 1) / 2 ))  # variations: fewer timed frames
  if ! "$render" "$file" -o "$work/$tag.png" --mask-out "$work/$tag.mask.png" --mode "$mode" \
      --width "$size" --height "$size" --azimuth "$az" --elevation "$el" --bench "$frames" "$@" > "$log" 2>&1; then
    echo "splat_render failed for $tag:" >&2; cat "$log" >&2; exit 1
  fi
  ms="$(sed -n 's/^\([0-9.]*\) ms\/frame.*/\1/p' "$log")"
  printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$model" "$count" "$view" "$mode" "$variant" \
    "$work/$tag.png" "$work/$tag.mask.png" "$ms" >> "$work/runs.tsv"
}

ran=()
for model in $models; do
  points="$data/$model.ply" mesh="$data/${model}_mesh.ply"
  if [ ! -f "$points" ] || [ ! -f "$mesh" ]; then
    echo "skipping $model: $([ -f "$points" ] || echo "$points") $([ -f "$mesh" ] || echo "$mesh") not found"
    continue
  fi
  echo "== $model: resampling with $script"
  t0=$(date +%s.%N)
  if ! "$server" -i "$points" -s "$mlx_dir/$script" -o "$work/$model.surfel" \
      > "$work/${model}_resample.log" 2>&1; then
    echo "meshlabserver failed on $model, see $work/${model}_resample.log" >&2; exit 1
  fi
  t1=$(date +%s.%N)
  sed -n 's/^.*\(Gaussian sphere resampling: [0-9]* points.*\)$/\1/p' "$work/${model}_resample.log" | tail -1
  # Same camera as the mesh (splat_render frames the file's bounding box) and the mesh's grey.
  "$py" "$tool" frame "$work/$model.surfel" "$mesh" "$work/${model}_framed.surfel" "$work/${model}_framed_mesh.ply"
  count="$(sed -n 's/^element vertex \([0-9]*\).*/\1/p' <(head -c 2000 "$work/$model.surfel" | tr -d '\r'))"
  inputs="$(sed -n 's/^element vertex \([0-9]*\).*/\1/p' <(head -c 2000 "$points" | tr -d '\r'))"
  echo "| $model | $inputs | $count | $(awk -v a="$t0" -v b="$t1" "BEGIN { printf \"%.1f\", b - a }") |" >> "$work/models.md"
  for view in $views; do
    echo "   view $view"
    render_one "$model" "$view" mesh "" "$work/${model}_framed_mesh.ply"
    render_one "$model" "$view" threepass "" "$work/${model}_framed.surfel"
    render_one "$model" "$view" onepass "" "$work/${model}_framed.surfel"
    render_one "$model" "$view" points "" "$work/${model}_framed.surfel"
    if [ "$variations" = 1 ]; then
      # Coverage margin and blending tolerance (see bench/render/README.md, "Findings").
      for s in 1.1 1.25; do
        render_one "$model" "$view" threepass "--splat-scale $s" "$work/${model}_framed.surfel" --splat-scale "$s"
      done
      render_one "$model" "$view" threepass "--depth-offset 0.5" "$work/${model}_framed.surfel" --depth-offset 0.5
      render_one "$model" "$view" threepass "--depth-offset 2" "$work/${model}_framed.surfel" --depth-offset 2
      render_one "$model" "$view" onepass "--splat-scale 1.25" "$work/${model}_framed.surfel" --splat-scale 1.25
      render_one "$model" "$view" points "--point-size 5" "$work/${model}_framed.surfel" --point-size 5
    fi
  done
  ran+=("$model")
done
[ ${#ran[@]} -gt 0 ] || { echo "bench_render.sh: no model to benchmark" >&2; exit 1; }

renderer="$(glxinfo -B 2>/dev/null | sed -n 's/^OpenGL renderer string: //p' || true)"
{
  echo "# Ellipse splatting vs. the original mesh: coverage, overdraw, PSNR, speed"
  echo
  echo "Written by \`bash scripts/bench_render.sh\` on $(date -u +%Y-%m-%d), $(nproc) cores, $(sed -n 's/^model name\s*: //p' /proc/cpuinfo | head -1),"
  echo "OpenGL: ${renderer:-Mesa llvmpipe under Xvfb (glxinfo not installed)}; images ${size}x${size}, field of view 30°,"
  echo "views (azimuth/elevation in degrees) $views; ms/frame = mean of $bench_frames frames after one warm-up frame"
  echo "(\`splat_render --bench $bench_frames\`, clear + draw + glFinish). Definitions: [README.md](README.md)."
  echo
  if [ -f "$src/.commit" ]; then
    echo "Code: build \`$(basename "$build")\` of a clean export of commit $(cat "$src/.commit")."
  elif git -C "${src:-$here}" rev-parse --short HEAD >/dev/null 2>&1; then
    dirty="$(git -C "${src:-$here}" status --porcelain -- filter_gaussphere vcg_ext render_ellipsesplat tools/splat_render \
      io_surfel sample_data 2>/dev/null | awk '{print $2}' | tr '\n' ' ' | sed 's/ $//')"
    echo "Code: build \`$(basename "$build")\` of commit $(git -C "${src:-$here}" rev-parse --short HEAD); uncommitted changes in the"
    echo "resampler, renderer or scripts at run time: ${dirty:-none}."
  fi
  echo "Resampling plugin built $(date -u -r "$build/stage/lib/x86_64-linux-gnu/meshlab/plugins/libfilter_gaussphere.so" '+%Y-%m-%d %H:%M UTC' 2>/dev/null || echo '?'), splat_render built $(date -u -r "$render" '+%Y-%m-%d %H:%M UTC')."
  echo "Load average at the end: $(cut -d' ' -f1-3 /proc/loadavg) (timings on a shared machine are noisy, ±20 %)."
  echo
  echo "| model | input points | surfels ($script) | resampling wall time incl. meshlabserver start (s) |"
  echo "|---|---|---|---|"
  cat "$work/models.md"
  echo
} > "$work/meta.md"
[ -f "$out/notes.md" ] && cp "$out/notes.md" "$work/notes.md"
"$py" "$tool" metrics "$work" "$out/results.csv" "$out/results.md"
echo "wrote $out/results.md and $out/results.csv in $(( $(date +%s) - started )) s"
sed -n '/^## Targets/,/^## Every/p' "$out/results.md" | sed '$d'
