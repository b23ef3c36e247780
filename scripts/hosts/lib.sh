# Helpers for the Debian 13 (trixie) root that hosts MeshLab 2022.02 and 2025.07.
# Sourced by the scripts in scripts/hosts/ (bash). Sets:
#   HOSTS_REPO  the repository root
#   HOSTS_ROOT  the root's directory (default $HOSTS_REPO/.deps/trixie-root; TRIXIE_ROOT overrides)
#   HOSTS_TRIXIE_PLUGIN_LIBS  libraries of trixie's MeshLab plugins its package misses
#   HOSTS_BUNNY_SURFELS       the surfel count every host's filter gives for the shipped bunny
# and defines:
#   hosts_debian_uri          the Debian mirror URI of this machine's own apt sources
#   hosts_in_root CMD...      runs CMD chrooted in the root, with /proc /dev /sys /tmp/.X11-unix
#                             bound in a private mount namespace and unmounted on exit (trap);
#                             HOSTS_BINDS="HOSTDIR:ROOTDIR ..." binds more folders;
#                             the environment is reset (PATH HOME LANG, DISPLAY when set)
#   hosts_xvfb_start          starts Xvfb (the root's) on a free display, exports DISPLAY;
#                             it runs as a background job of the caller, so stop it before a bare `wait`
#   hosts_xvfb_stop           stops it
#   hosts_screenshot FILE     `import -window root` of DISPLAY, written to FILE on the host
#   hosts_quiet_settings HOME MeshLab settings in HOME that pre-answer the start-up dialogs

HOSTS_REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
# The shared libraries of MeshLab 2022.02's own plugins that trixie's meshlab package does not
# depend on: muparser (filter_func), mpfr (filter_mesh_booleans), qhull_r (filter_qhull), lib3ds
# (io_3ds), openctm (io_ctm), xerces (io_e57). Without them MeshLab opens a modal dialog listing
# the plugins that failed at start.
HOSTS_TRIXIE_PLUGIN_LIBS=(libmuparser2v5 libmpfr6 libqhull-r8.0 lib3ds-1-3 libopenctm1 libxerces-c3.2t64)
HOSTS_ROOT="${TRIXIE_ROOT:-$HOSTS_REPO/.deps/trixie-root}"
# What gsresample gives for sample_data/bunny.ply at the defaults: the algorithm is
# deterministic and the same code in every plugin, so every host must give this count.
HOSTS_BUNNY_SURFELS="${EXPECTED_SURFELS:-9838}"
# .deps may be a symlink; bind mounts and chroot want the real path.
mkdir -p "$(dirname "$HOSTS_ROOT")"
HOSTS_ROOT="$(realpath -m "$HOSTS_ROOT")"

hosts_debian_uri() {
  local f=/etc/apt/sources.list.d/debian.sources
  if [ -r "$f" ]; then
    # deb822: the URIs of the first stanza whose suites are not the security ones.
    awk -v RS= '$0 !~ /Suites:[^\n]*-security/ {
        if (match($0, /URIs:[ \t]*[^ \t\n]+/)) {
          s = substr($0, RSTART, RLENGTH); sub(/URIs:[ \t]*/, "", s); print s; exit } }' "$f"
  elif [ -r /etc/apt/sources.list ]; then
    awk '$1 == "deb" && $0 !~ /security/ { for (i = 2; i <= NF; i++) if ($i ~ /^[a-z]+:\/\//) { print $i; exit } }' \
      /etc/apt/sources.list
  fi
}

hosts_in_root() {
  [ -d "$HOSTS_ROOT/usr" ] || { echo "hosts_in_root: no root at $HOSTS_ROOT (run scripts/hosts/trixie_root.sh)" >&2; return 1; }
  mkdir -p -m 1777 /tmp/.X11-unix
  # A private mount namespace needs root, and / to be a mount point: inside a plain chroot it is not.
  unshare --mount --propagation private true 2>/dev/null || {
    echo "hosts_in_root: cannot make a private mount namespace (unshare --mount --propagation private):" \
      "run as root, and inside a chroot bind-mount its directory onto itself before entering it" >&2
    return 1
  }
  unshare --mount --propagation private -- bash -c '
    set -e
    root=$1; shift
    mounted=()
    cleanup() {
      local i
      for ((i = ${#mounted[@]} - 1; i >= 0; i--)); do umount -R "${mounted[i]}" 2>/dev/null || umount -l "${mounted[i]}" || true; done
    }
    trap cleanup EXIT
    trap "exit 130" INT TERM
    bind() {  # bind HOSTDIR ROOTDIR
      mkdir -p "$root$2"
      mount --rbind "$1" "$root$2"
      mount --make-rslave "$root$2"
      mounted+=("$root$2")
    }
    bind /proc /proc
    bind /dev /dev
    bind /sys /sys
    bind /tmp/.X11-unix /tmp/.X11-unix
    for pair in ${HOSTS_BINDS:-}; do bind "${pair%%:*}" "${pair#*:}"; done
    env=(PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin HOME=/root LANG=C.UTF-8
         DEBIAN_FRONTEND=noninteractive)
    [ -n "${DISPLAY:-}" ] && env+=(DISPLAY="$DISPLAY")
    chroot "$root" /usr/bin/env -i "${env[@]}" "$@"
  ' hosts_in_root "$HOSTS_ROOT" "$@"
}

# Display numbers from 140 up: clear of xvfb-run -a (99 up), which only looks at the host's /tmp.
hosts_xvfb_start() {
  local n=140
  mkdir -p -m 1777 /tmp/.X11-unix
  while [ -e "/tmp/.X11-unix/X$n" ] || [ -e "/tmp/.X$n-lock" ] || [ -e "$HOSTS_ROOT/tmp/.X$n-lock" ]; do
    n=$((n + 1))
  done
  HOSTS_XVFB_DISPLAY=$n
  HOSTS_XVFB_LOG="${TMPDIR:-/tmp}/hosts-xvfb-$n.log"
  hosts_in_root Xvfb ":$n" -screen 0 "${HOSTS_XVFB_SCREEN:-1280x1024x24}" -nolisten tcp >"$HOSTS_XVFB_LOG" 2>&1 &
  HOSTS_XVFB_JOB=$!
  local i
  for i in $(seq 100); do
    [ -S "/tmp/.X11-unix/X$n" ] && { export DISPLAY=":$n"; return 0; }
    kill -0 "$HOSTS_XVFB_JOB" 2>/dev/null || break
    sleep 0.2
  done
  echo "hosts_xvfb_start: Xvfb :$n did not come up (log: $HOSTS_XVFB_LOG)" >&2
  return 1
}

hosts_xvfb_stop() {
  [ -n "${HOSTS_XVFB_DISPLAY:-}" ] || return 0
  local lock="$HOSTS_ROOT/tmp/.X$HOSTS_XVFB_DISPLAY-lock" pid
  # Xvfb writes its (host) pid into its lock file, inside the root's /tmp.
  pid="$(tr -dc 0-9 < "$lock" 2>/dev/null || true)"
  [ -n "$pid" ] && kill "$pid" 2>/dev/null || true
  wait "$HOSTS_XVFB_JOB" 2>/dev/null || true
  unset HOSTS_XVFB_DISPLAY DISPLAY
}

hosts_screenshot() {
  local tmp="/tmp/hosts-shot-$$.png"
  hosts_in_root import -window root "$tmp"
  mkdir -p "$(dirname "$1")"
  mv "$HOSTS_ROOT$tmp" "$1"
}

# MeshLab's QSettings file (~/.config/VCG/MeshLab_64bit_fp.conf) under HOME: informativeShown
# (2025.07's usage-statistics question), dontRemindMeAboutUpgrade, and the global parameters
# MeshLab::System::sendAnonymousData and checkForUpdate as false (docs/hosts.md).
hosts_quiet_settings() {
  local param='MeshLab%%3A%%3ASystem%%3A%%3A%s="<Param name=\\"MeshLab::System::%s\\" type=\\"RichBool\\" value=\\"false\\"/>"\n'
  mkdir -p "$1/.config/VCG"
  {
    echo "[General]"
    echo "informativeShown=true"
    echo "dontRemindMeAboutUpgrade=true"
    printf "$param" sendAnonymousData sendAnonymousData
    printf "$param" checkForUpdate checkForUpdate
  } > "$1/.config/VCG/MeshLab_64bit_fp.conf"
}
