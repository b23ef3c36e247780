#!/usr/bin/env bash
# Installs every Debian package the project needs (build, run, test, benchmark) and
# unpacks the MeshLab 2020.09 source (headers for the plugin API) into .deps/.
# Idempotent: a second run only checks. Needs root (or sudo) for apt-get.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
deps="$here/.deps"

SUDO=""
if [ "$(id -u)" != 0 ]; then SUDO="sudo"; fi

packages=(
  # build
  build-essential cmake pkg-config dpkg-dev
  qtbase5-dev libqt5opengl5-dev libqt5xmlpatterns5-dev libglew-dev libeigen3-dev
  libgtest-dev libnanoflann-dev glslang-tools nlohmann-json3-dev
  # sanitizer and fuzz builds: clang with libFuzzer and the sanitizer runtimes, LLVM's OpenMP
  clang-14 libclang-rt-14-dev libomp-14-dev
  # host application and headless runs
  meshlab xvfb xauth libgl1-mesa-dri mesa-utils imagemagick xdotool
  # benchmark peers and plots
  libcgal-dev python3 python3-matplotlib python3-numpy time hyperfine
  # distributed tiled runs (scripts/gstile_dask.py)
  python3-distributed
  # the Debian roots of the hosts stage (MeshLab 2022.02 and 2025.07, the package checks), and
  # the bind mounts into them (mount is "required", not essential: a minimal root may lack it)
  mmdebstrap mount
  # the .deb packages (CPack's dependency scan reads the plugins with file)
  file
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "[setup] installing: ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -q
  $SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

# MeshLab's plugin headers are only in Debian's source package.
src_marker="$deps/meshlab-src/src/common/generated_version_header.h"
if [ ! -f "$src_marker" ]; then
  if ! grep -rqs '^Types: deb-src' /etc/apt/sources.list.d/ /etc/apt/sources.list 2>/dev/null &&
     ! grep -rqs '^deb-src' /etc/apt/sources.list.d/ /etc/apt/sources.list 2>/dev/null; then
    echo "[setup] adding a deb-src entry derived from this machine's Debian sources"
    if [ -f /etc/apt/sources.list.d/debian.sources ]; then
      sed 's/^Types: deb$/Types: deb-src/' /etc/apt/sources.list.d/debian.sources |
        $SUDO tee /etc/apt/sources.list.d/debian-src.sources >/dev/null
    else
      sed -n 's/^deb /deb-src /p' /etc/apt/sources.list |
        $SUDO tee /etc/apt/sources.list.d/debian-src.list >/dev/null
    fi
    $SUDO apt-get update -q
  fi
  mkdir -p "$deps/download"
  (cd "$deps/download" && apt-get source -q meshlab=2020.09+dfsg1-2 >/dev/null 2>&1 ||
     apt-get source -q meshlab)
  tree=$(find "$deps/download" -maxdepth 1 -type d -name 'meshlab-2020.09*' | head -1)
  [ -n "$tree" ] || { echo "[setup] error: MeshLab source did not unpack" >&2; exit 1; }
  rm -rf "$deps/meshlab-src"
  mv "$tree" "$deps/meshlab-src"
  rm -rf "$deps/download"
  # Debian's build generates this header; the plugin API includes it.
  echo 'static constexpr auto VERSION_STRING = "2020.09";' > "$src_marker"
fi
echo "[setup] ok: packages installed, MeshLab source in $deps/meshlab-src"
