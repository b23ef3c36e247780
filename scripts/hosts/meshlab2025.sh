#!/usr/bin/env bash
# Builds MeshLab 2025.07 (MESHLAB_BUILD_MINI=ON: meshlab-common, the GUI, shaders) plus the
# io_base plugin (PLY, OBJ, OFF, STL, ...) in the trixie root, from the published source tarball
# (default ../shared/meshlab-2025.07-src.tar.xz; MESHLAB2025_TARBALL overrides). Once per machine:
# the result is cached in .deps/meshlab-2025.07/ with a marker naming the tarball's sha256 and
# the build options; a later run with the same ones only reports.
#
#   scripts/hosts/meshlab2025.sh
#
# Layout (the folder is bound at /opt/meshlab-2025.07 inside the root, where CMake's cache
# expects it):
#   .deps/meshlab-2025.07/src/                     the unpacked tarball (src/, resources/, ...)
#   .deps/meshlab-2025.07/build/src/distrib/       meshlab, libmeshlab-common.so, plugins/, shaders/
#   .deps/meshlab-2025.07/.hosts-build-complete    the marker; .hosts-build-seconds the build time
#                                                  (summed over interrupted attempts)
# In a MINI build add_meshlab_plugin() (src/cmake/meshlab_tools.cmake) marks every plugin
# EXCLUDE_FROM_ALL, so plugins are built by naming their targets; MESHLAB_PLUGINS limits the
# configured ones (src/CMakeLists.txt). JOBS sets the parallel jobs (default 2).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"

tarball="${MESHLAB2025_TARBALL:-$HOSTS_REPO/../shared/meshlab-2025.07-src.tar.xz}"
dir="$(realpath -m "$HOSTS_REPO/.deps/meshlab-2025.07")"
inside=/opt/meshlab-2025.07
plugins=(io_base)
jobs="${JOBS:-2}"
# -O1: the host is a test fixture, built on every CI machine in the CPU the other stages leave;
# its optimisation changes nothing the checks see, and -O1 compiles in less CPU time than -O3.
options=(-DCMAKE_BUILD_TYPE=Release "-DCMAKE_CXX_FLAGS_RELEASE=-O1 -DNDEBUG" "-DCMAKE_C_FLAGS_RELEASE=-O1 -DNDEBUG"
         -DMESHLAB_BUILD_MINI=ON "-DMESHLAB_PLUGINS=$(printf 'meshlabplugins/%s;' "${plugins[@]}" | sed 's/;$//')")

"$(dirname "${BASH_SOURCE[0]}")/trixie_root.sh"

mkdir -p "$dir"
exec 8>"$dir.lock"
flock 8

stamp="$(sha256sum < "$tarball" | cut -d' ' -f1) ${options[*]}"
marker="$dir/.hosts-build-complete"
if [ -f "$marker" ] && [ "$(cat "$marker")" = "$stamp" ]; then
  echo "[meshlab2025] reusing $dir/build/src/distrib (built in $(cat "$dir/.hosts-build-seconds" 2>/dev/null || echo '?') s)"
  exit 0
fi

if [ ! -f "$dir/src/CMakeLists.txt" ] || [ "$(cat "$dir/.hosts-tarball" 2>/dev/null)" != "${stamp%% *}" ]; then
  rm -rf "$dir/src" "$dir/build"
  mkdir -p "$dir/src"
  tar -xf "$tarball" -C "$dir/src" --strip-components=1
  echo "${stamp%% *}" > "$dir/.hosts-tarball"
fi

export HOSTS_BINDS="$dir:$inside"
# An interrupted build resumes where it stopped; the time of every attempt is summed in
# .hosts-build-seconds-spent until one completes.
spent="$dir/.hosts-build-seconds-spent"
started=$SECONDS
trap 'echo $(( $(cat "$spent" 2>/dev/null || echo 0) + SECONDS - started )) > "$spent.new" && mv "$spent.new" "$spent"' EXIT
hosts_in_root nice -n 15 cmake -S "$inside/src" -B "$inside/build" "${options[@]}"
hosts_in_root nice -n 15 cmake --build "$inside/build" -j "$jobs"
hosts_in_root nice -n 15 cmake --build "$inside/build" -j "$jobs" --target "${plugins[@]}"
trap - EXIT
seconds=$(( $(cat "$spent" 2>/dev/null || echo 0) + SECONDS - started ))

for f in meshlab libmeshlab-common.so; do
  [ -e "$dir/build/src/distrib/$f" ] || { echo "[meshlab2025] missing build/src/distrib/$f" >&2; exit 1; }
done
for p in "${plugins[@]}"; do
  [ -e "$dir/build/src/distrib/plugins/lib$p.so" ] || { echo "[meshlab2025] missing plugin lib$p.so" >&2; exit 1; }
done

echo "$seconds" > "$dir/.hosts-build-seconds"
rm -f "$spent"
echo "$stamp" > "$marker"
echo "[meshlab2025] built in $seconds s: $dir/build/src/distrib"
