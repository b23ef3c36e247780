#!/usr/bin/env bash
# Builds the Debian packages of the plugins and gsresample into out/packages/:
#   meshlab-gaussphere_VERSION-1~bookworm_amd64.deb   for Debian 12's meshlab 2020.09 (this machine)
#   meshlab-gaussphere_VERSION-1~trixie_amd64.deb     for Debian 13's meshlab 2022.02 (built in the
#                                                     trixie root, scripts/hosts/trixie_root.sh)
# Each depends on the exact meshlab version it was built against (cmake/packaging.cmake).
#   bash scripts/package.sh [bookworm] [trixie]      (default: both)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="$here/out/packages"
mkdir -p "$out"
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(bookworm trixie)
for target in "${targets[@]}"; do
  started=$SECONDS
  case "$target" in
    bookworm)
      bash "$here/scripts/setup.sh" >/dev/null
      build="${BUILD_DIR:-$here/build}"
      cmake -S "$here" -B "$build" -DCMAKE_BUILD_TYPE=Release -DGAUSSPHERE_BUILD_PLUGINS=ON >/dev/null
      cmake --build "$build" -j "$(nproc)" --target gsresample filter_gaussphere filter_surfel_error io_surfel \
        render_ellipsesplat >/dev/null
      (cd "$build" && cpack -G DEB -B "$out" >/dev/null)
      ;;
    trixie)
      "$here/scripts/hosts/build_plugins.sh" 2022.02 >/dev/null
      source "$here/scripts/hosts/lib.sh"
      source "$here/scripts/hosts/host_env.sh"
      hosts_plugins_select 2022.02
      HOSTS_BINDS="$HOSTS_BINDS $out:/opt/packages" \
        hosts_in_root sh -c 'cd /opt/gaussphere-build && cpack -G DEB -B /opt/packages >/dev/null'
      ;;
    *) echo "package.sh: unknown target '$target' (bookworm or trixie)" >&2; exit 2 ;;
  esac
  rm -rf "$out/_CPack_Packages"
  deb="$(ls -t "$out"/meshlab-gaussphere_*~"$target"_amd64.deb | head -1)"
  echo "[package] $target: $deb ($((SECONDS - started)) s)"
  dpkg-deb -f "$deb" Depends | tr ',' '\n' | grep -m1 'meshlab ' | sed 's/^ */[package]   depends on /'
done
