#!/usr/bin/env bash
# Makes, once, the tarball of a clean Debian root for the package checks (deb_test.sh) and prints
# its path: Debian DIST (bookworm or trixie) with meshlab and what a headless check needs (xvfb
# xauth xdotool imagemagick, and on trixie the libraries of MeshLab's own plugins that its
# package misses), from the mirror of this machine's apt sources, in .deps/clean-DIST.tar
# (bookworm ~2.5 min, trixie ~1.5 min). A tarball made for another package list is made anew;
# concurrent runs wait on a lock.
#
#   scripts/hosts/clean_root.sh bookworm|trixie
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
dist="${1:?usage: clean_root.sh bookworm|trixie}"
case "$dist" in bookworm|trixie) ;; *) echo "clean_root.sh: unknown distribution '$dist'" >&2; exit 2 ;; esac

packages=(meshlab xvfb xauth xdotool imagemagick libgl1-mesa-dri)
[ "$dist" = trixie ] && packages+=("${HOSTS_TRIXIE_PLUGIN_LIBS[@]}")
tarball="$(realpath -m "$HOSTS_REPO/.deps/clean-$dist.tar")"
stamp="$(printf '%s\n' "$dist" "${packages[@]}" | md5sum | cut -d' ' -f1)"
exec 7>"$tarball.lock"
flock 7
if [ ! -f "$tarball" ] || [ "$(cat "$tarball.stamp" 2>/dev/null)" != "$stamp" ]; then
  command -v mmdebstrap >/dev/null || DEBIAN_FRONTEND=noninteractive apt-get install -y mmdebstrap
  started=$SECONDS
  mmdebstrap --variant=apt --format=tar --include="$(IFS=,; echo "${packages[*]}")" "$dist" "$tarball.part" \
    "deb $(hosts_debian_uri) $dist main" > "$tarball.log" 2>&1 || { cat "$tarball.log"; exit 1; }
  mv "$tarball.part" "$tarball"
  echo "$stamp" > "$tarball.stamp"
  echo "[clean_root] made the clean $dist root in $((SECONDS - started)) s: $tarball" >&2
fi
flock -u 7
echo "$tarball"
