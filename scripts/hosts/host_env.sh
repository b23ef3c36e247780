# Sourced after lib.sh: hosts_select VERSION sets, for MeshLab VERSION (2022.02 or 2025.07),
#   HOST_SRC     its source tree inside the root (ML_VERSION, src/common, src/vcglib)
#   HOST_COMMON  its libmeshlab-common.so inside the root
#   HOST_BIN     its meshlab executable inside the root
#   HOST_PLUGINS its plugin folder inside the root
# and adds the binds it needs to HOSTS_BINDS (2025.07: .deps/meshlab-2025.07 at /opt/meshlab-2025.07).
hosts_select() {
  case "$1" in
    2022.02)
      HOST_SRC=/usr/src/meshlab
      HOST_COMMON=/usr/lib/x86_64-linux-gnu/meshlab/libmeshlab-common.so
      HOST_BIN=/usr/bin/meshlab
      HOST_PLUGINS=/usr/lib/x86_64-linux-gnu/meshlab/plugins
      HOSTS_BINDS="${HOSTS_BINDS:-}" ;;
    2025.07)
      "$HOSTS_REPO/scripts/hosts/meshlab2025.sh"
      HOSTS_BINDS="${HOSTS_BINDS:-} $(realpath "$HOSTS_REPO/.deps/meshlab-2025.07"):/opt/meshlab-2025.07"
      HOST_SRC=/opt/meshlab-2025.07/src
      HOST_COMMON=/opt/meshlab-2025.07/build/src/distrib/libmeshlab-common.so
      HOST_BIN=/opt/meshlab-2025.07/build/src/distrib/meshlab
      HOST_PLUGINS=/opt/meshlab-2025.07/build/src/distrib/plugins ;;
    *) echo "unknown MeshLab host '$1' (2022.02 or 2025.07)" >&2; return 2 ;;
  esac
  export HOSTS_BINDS
}

# hosts_plugins_select VERSION: hosts_select VERSION for the project's plugins, and sets
#   PLUGINS_BUILD      their build folder .deps/plugins-VERSION (/opt/gaussphere-build in the
#                      root; the repository is bound at /opt/gaussphere)
#   PLUGINS_PROBE_ENV  the env command the probes run under (offscreen Qt, the host's
#                      libmeshlab-common.so on the library path: 2025.07's is in its build tree)
hosts_plugins_select() {
  hosts_select "$1" || return
  PLUGINS_BUILD="$(realpath -m "$HOSTS_REPO/.deps/plugins-$1")"
  HOSTS_BINDS="$HOSTS_BINDS $HOSTS_REPO:/opt/gaussphere $PLUGINS_BUILD:/opt/gaussphere-build"
  export HOSTS_BINDS
  PLUGINS_PROBE_ENV=(env QT_QPA_PLATFORM=offscreen LD_LIBRARY_PATH="$(dirname "$HOST_COMMON")")
}
