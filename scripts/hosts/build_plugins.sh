#!/usr/bin/env bash
# Builds the project's plugins for MeshLab 2022.02 or 2025.07 (cmake/host_plugins: the
# 2021.05+ adapters, vcg_ext against the host's vcglib, and the probes plugin_probe and
# filter_run) in the trixie root, with the repository bind-mounted at /opt/gaussphere, then
# lists what the plugins provide through the host's PluginManager (plugin_probe).
#
#   scripts/hosts/build_plugins.sh 2022.02|2025.07
#
# Build folder: .deps/plugins-VERSION/ (inside the root: /opt/gaussphere-build); the plugins are
# lib*.so there. Sourcing scripts use $PLUGINS_BUILD and $PLUGINS_PROBE_ENV.
set -euo pipefail
here="$(dirname "${BASH_SOURCE[0]}")"
source "$here/lib.sh"
source "$here/host_env.sh"
version="${1:?usage: build_plugins.sh 2022.02|2025.07}"
"$here/trixie_root.sh" >/dev/null
hosts_select "$version"

build="$(realpath -m "$HOSTS_REPO/.deps/plugins-$version")"
mkdir -p "$build"
HOSTS_BINDS="$HOSTS_BINDS $HOSTS_REPO:/opt/gaussphere $build:/opt/gaussphere-build"
export HOSTS_BINDS

started=$SECONDS
hosts_in_root nice -n 10 cmake -S /opt/gaussphere/cmake/host_plugins -B /opt/gaussphere-build \
  -DCMAKE_BUILD_TYPE=Release -DMESHLAB_SOURCE_DIR="$HOST_SRC" -DMESHLAB_COMMON_LIBRARY="$HOST_COMMON"
hosts_in_root nice -n 10 cmake --build /opt/gaussphere-build -j "${JOBS:-2}"
echo "[build_plugins] $version: configured and built in $((SECONDS - started)) s"

# The probes link the host's libmeshlab-common.so (for 2025.07 through the build tree's path).
probe_env=(env QT_QPA_PLATFORM=offscreen LD_LIBRARY_PATH="$(dirname "$HOST_COMMON")")
hosts_in_root "${probe_env[@]}" /opt/gaussphere-build/plugin_probe /opt/gaussphere-build/libfilter_gaussphere.so \
  | tee "$build/probe.txt"
hosts_in_root "${probe_env[@]}" /opt/gaussphere-build/plugin_probe /opt/gaussphere-build/librender_ellipsesplat.so \
  | tee -a "$build/probe.txt"
