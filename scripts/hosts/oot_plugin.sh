#!/usr/bin/env bash
# Builds MeshLab's own sample filter plugin out of tree against a host (the project in
# scripts/hosts/oot/, with meshlab_host.cmake) in the trixie root, then loads it, and the host's
# io_base, through the host's PluginManager (plugin_probe) and prints what they provide.
#
#   scripts/hosts/oot_plugin.sh 2022.02|2025.07
#
# Build folder: .deps/hosts-oot-VERSION/ (inside the root: /opt/hosts-oot-build); the plugin is
# liboot_filter_sample.so there. When the other host's build folder exists, its plugin is probed
# too: the loader is expected to refuse it (different version).
set -euo pipefail
here="$(dirname "${BASH_SOURCE[0]}")"
source "$here/lib.sh"
source "$here/host_env.sh"
version="${1:?usage: oot_plugin.sh 2022.02|2025.07}"
"$here/trixie_root.sh" >/dev/null
hosts_select "$version"

build="$(realpath -m "$HOSTS_REPO/.deps/hosts-oot-$version")"
mkdir -p "$build"
HOSTS_BINDS="$HOSTS_BINDS $(realpath "$here/oot"):/opt/hosts-oot $build:/opt/hosts-oot-build"
other=2025.07; [ "$version" = 2025.07 ] && other=2022.02
other_plugin="$(realpath -m "$HOSTS_REPO/.deps/hosts-oot-$other")/liboot_filter_sample.so"
[ -f "$other_plugin" ] && HOSTS_BINDS="$HOSTS_BINDS $(dirname "$other_plugin"):/opt/hosts-oot-other"
export HOSTS_BINDS

started=$SECONDS
hosts_in_root nice -n 15 cmake -S /opt/hosts-oot -B /opt/hosts-oot-build -DCMAKE_BUILD_TYPE=Release \
  -DMESHLAB_SOURCE_DIR="$HOST_SRC" -DMESHLAB_COMMON_LIBRARY="$HOST_COMMON"
hosts_in_root nice -n 15 cmake --build /opt/hosts-oot-build -j "${JOBS:-2}"
echo "[oot_plugin] $version: configured and built in $((SECONDS - started)) s"

# The probe links the host's libmeshlab-common.so (for 2025.07 through the build tree's path).
probe=(env QT_QPA_PLATFORM=offscreen LD_LIBRARY_PATH="$(dirname "$HOST_COMMON")" /opt/hosts-oot-build/plugin_probe)
hosts_in_root "${probe[@]}" "$HOST_PLUGINS/libio_base.so" /opt/hosts-oot-build/liboot_filter_sample.so \
  | tee "$build/probe.txt"
if [ -f "$other_plugin" ]; then
  echo "[oot_plugin] the sample built for $other, into $version (expected: refused)"
  hosts_in_root "${probe[@]}" /opt/hosts-oot-other/liboot_filter_sample.so | tee "$build/probe-other.txt" || true
fi
