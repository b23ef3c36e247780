#!/usr/bin/env bash
# Creates the Debian 13 (trixie) root that hosts MeshLab 2022.02 (trixie's package) and the
# MeshLab 2025.07 build, at .deps/trixie-root (TRIXIE_ROOT overrides). Once per machine: a
# complete root carries a marker naming its package set and is reused as it is; a root made
# for another package set gets the missing packages installed. Needs root and mmdebstrap
# (installed from Debian when absent). Concurrent runs wait on a lock.
#
# The root holds:
#   - meshlab (2022.02) and the libraries of its plugins that the package does not depend on
#     (without them MeshLab opens a modal dialog listing the plugins that failed to load);
#   - xvfb xauth libgl1-mesa-dri imagemagick xdotool (headless GUI runs, screenshots);
#   - the build dependencies of out-of-tree plugins (the project's: nanoflann) and of a
#     MeshLab 2025.07 MINI build;
#   - trixie's meshlab source package, unpacked (Debian patches applied) at
#     /usr/src/meshlab (a symlink to the versioned folder): the 2022.02 plugin API headers.
#     The root's apt sources carry a deb-src entry for it.
# The mirror is the one of this machine's own apt sources (scripts/hosts/lib.sh).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"

root="$HOSTS_ROOT"
marker="$root/.hosts-root-complete"

packages=(
  meshlab
  xvfb xauth libgl1-mesa-dri imagemagick xdotool
  ca-certificates dpkg-dev xz-utils file binutils
  cmake g++ make pkg-config
  qtbase5-dev libqt5opengl5-dev libqt5svg5-dev
  libglew-dev libeigen3-dev libgtest-dev
  libnanoflann-dev
)
# The shared libraries of MeshLab 2022.02's plugins that trixie's meshlab package misses
# (lib.sh); checked with ldd below.
plugin_libs=("${HOSTS_TRIXIE_PLUGIN_LIBS[@]}")

stamp="$(printf '%s\n' "${packages[@]}" "${plugin_libs[@]}" | sort | md5sum | cut -d' ' -f1)"

exec 9>"$root.lock"
flock 9

if [ -f "$marker" ] && [ "$(cat "$marker")" = "$stamp" ]; then
  echo "[trixie_root] reusing $root"
  exit 0
fi

started=$SECONDS
if [ ! -f "$root/.hosts-mmdebstrap-done" ]; then
  if findmnt -rn -o TARGET | grep -q "^$root/"; then
    echo "[trixie_root] something is mounted under $root; not removing it" >&2
    exit 1
  fi
  rm -rf "$root"
  command -v mmdebstrap >/dev/null || DEBIAN_FRONTEND=noninteractive apt-get install -y mmdebstrap
  uri="$(hosts_debian_uri)"
  [ -n "$uri" ] || { echo "[trixie_root] no Debian mirror found in the machine's apt sources" >&2; exit 1; }
  echo "[trixie_root] mmdebstrap trixie -> $root"
  include="$(IFS=,; echo "${packages[*]}")"
  mmdebstrap --variant=apt --include="$include" trixie "$root" \
    "deb $uri trixie main" "deb-src $uri trixie main"
  touch "$root/.hosts-mmdebstrap-done"
  echo "[trixie_root] mmdebstrap took $((SECONDS - started)) s"
fi

# mmdebstrap leaves no package lists and no resolv.conf behind.
cp /etc/resolv.conf "$root/etc/resolv.conf"
hosts_in_root apt-get update -q
hosts_in_root apt-get install -y -q --no-install-recommends "${packages[@]}" "${plugin_libs[@]}"

# apt-get source unpacks with Debian's patches. Where the mirror serves the upstream tarball but
# not the .dsc / debian.tar.xz (seen here: 404), the tarball, checked against the sha256 of the
# signed Sources index, is unpacked without Debian's patches; /usr/src/meshlab/.hosts-source
# says which of the two it is.
if [ ! -d "$root/usr/src/meshlab/src/common" ]; then
  hosts_in_root bash -ec '
    cd /usr/src
    rm -rf meshlab meshlab-* meshlab_*
    if apt-get source -q meshlab; then
      how="apt-get source (Debian patches applied)"
    else
      orig="$(ls meshlab_*.orig.tar.* | head -n1)"
      want="$(apt-cache showsrc meshlab | awk "/^Checksums-Sha256:/ {s=1; next} /^[^ ]/ {s=0} s && \$3 == \"$orig\" {print \$1; exit}")"
      echo "$want  $orig" | sha256sum -c -
      version="${orig#meshlab_}"; version="${version%.orig.tar.*}"
      mkdir "meshlab-$version"
      tar -xf "$orig" -C "meshlab-$version" --strip-components=1
      how="upstream tarball $orig only (the mirror did not serve the .dsc and Debian patches)"
    fi
    dir="$(basename "$(ls -d /usr/src/meshlab-*/ | head -n1)")"
    ln -sfn "$dir" /usr/src/meshlab
    echo "$how" > /usr/src/meshlab/.hosts-source'
fi

missing="$(hosts_in_root sh -c 'LD_LIBRARY_PATH=/usr/lib/x86_64-linux-gnu/meshlab ldd /usr/bin/meshlab /usr/lib/x86_64-linux-gnu/meshlab/plugins/*.so' | grep 'not found' | sort -u || true)"
if [ -n "$missing" ]; then
  echo "[trixie_root] libraries still missing for MeshLab's plugins:" >&2
  echo "$missing" >&2
  exit 1
fi

echo "$stamp" > "$marker"
echo "[trixie_root] ready: $root ($(du -sh --one-file-system "$root" | cut -f1), $((SECONDS - started)) s)"
