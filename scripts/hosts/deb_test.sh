#!/usr/bin/env bash
# Installs a meshlab-gaussphere .deb into a clean root of its distribution, uses it there, and
# removes it again. Exit status non-zero on any failure.
#
#   scripts/hosts/deb_test.sh bookworm|trixie [PACKAGE.deb]   (default: the newest in out/packages)
#
# The clean root: Debian DIST with meshlab and what a headless check needs (clean_root.sh),
# unpacked afresh for every run.
# Checks:
#   1. dpkg -i succeeds: the package's dependencies, the exact meshlab version among them, are
#      met by the distribution's packages;
#   2. gsresample resamples the packaged bunny (HOSTS_BUNNY_SURFELS surfels, lib.sh);
#   3. the installed MeshLab runs the installed filter on the bunny: on bookworm meshlabserver
#      with the packaged resample_level8.mlx, on trixie (no meshlabserver) filter_run, which loads
#      the installed plugins through MeshLab's own PluginManager (built by build_plugins.sh 2022.02);
#   4. the GUI starts with the installed plugins and the bunny under Xvfb and shows no error
#      window (screenshot out/packages/DIST-gui.png);
#   5. dpkg --purge leaves /usr and /etc as they were before the installation.
set -euo pipefail
here="$(dirname "${BASH_SOURCE[0]}")"
source "$here/lib.sh"
dist="${1:?usage: deb_test.sh bookworm|trixie [PACKAGE.deb]}"
out="$HOSTS_REPO/out/packages"
deb="${2:-$(ls -t "$out"/meshlab-gaussphere_*~"$dist"_amd64.deb 2>/dev/null | head -1)}"
[ -f "$deb" ] || { echo "[deb_test] no package for $dist: run scripts/package.sh $dist" >&2; exit 1; }
expected="$HOSTS_BUNNY_SURFELS"

tarball="$("$here/clean_root.sh" "$dist")"

HOSTS_ROOT="$(realpath -m "$HOSTS_REPO/.deps/deb-test-$dist-$$")"
cleanup() { hosts_xvfb_stop; [ -n "${gui_job:-}" ] && kill "$gui_job" 2>/dev/null; rm -rf "$HOSTS_ROOT" "$HOSTS_ROOT".*; }
trap cleanup EXIT
mkdir -p "$HOSTS_ROOT"
tar -xf "$tarball" -C "$HOSTS_ROOT"
fail() { echo "[deb_test] $dist: FAIL: $*"; exit 1; }
snapshot() { hosts_in_root sh -c 'find /usr /etc -xdev | LC_ALL=C sort'; }

cp "$deb" "$HOSTS_ROOT/tmp/package.deb"
snapshot > "$HOSTS_ROOT.before"
hosts_in_root dpkg -i /tmp/package.deb > "$HOSTS_ROOT.log" 2>&1 || { cat "$HOSTS_ROOT.log"; fail "dpkg -i"; }
version="$(hosts_in_root dpkg-query -W -f='${Version}' meshlab-gaussphere)"
meshlab="$(hosts_in_root dpkg-query -W -f='${Version}' meshlab)"
echo "[deb_test] $dist: installed meshlab-gaussphere $version beside meshlab $meshlab"

share=/usr/share/meshlab-gaussphere
line="$(hosts_in_root gsresample $share/bunny.ply /tmp/bunny.surfel 2>&1 | tail -1)"
count="$(sed -n 's/.* output \([0-9]*\) .*/\1/p' <<<"$line")"
[ "$count" = "$expected" ] || fail "gsresample gave '$line'"
echo "[deb_test] $dist: gsresample: $count surfels"

if [ "$dist" = bookworm ]; then
  hosts_in_root xvfb-run -a meshlabserver -i $share/bunny.ply -s $share/scripts/resample_level8.mlx \
    -o /tmp/bunny_resampled.ply > "$HOSTS_ROOT.filter" 2>&1 || true
else
  probe="$(realpath -m "$HOSTS_REPO/.deps/plugins-2022.02/filter_run")"
  [ -x "$probe" ] || fail "no $probe: run scripts/hosts/build_plugins.sh 2022.02"
  cp "$probe" "$HOSTS_ROOT/tmp/"
  plugins=/usr/lib/x86_64-linux-gnu/meshlab
  hosts_in_root env QT_QPA_PLATFORM=offscreen LD_LIBRARY_PATH=$plugins /tmp/filter_run $share/bunny.ply \
    "Gaussian Sphere Feature-Sensitive Resampling" $plugins/plugins/libio_base.so \
    $plugins/plugins/libfilter_gaussphere.so > "$HOSTS_ROOT.filter" 2>&1 || true
fi
grep -q "points -> $expected surfels" "$HOSTS_ROOT.filter" || { cat "$HOSTS_ROOT.filter"; fail "the filter did not give $expected surfels"; }
echo "[deb_test] $dist: the installed filter in the installed MeshLab: $(grep -o "[0-9]* points -> [0-9]* surfels" "$HOSTS_ROOT.filter" | head -1)"

mkdir -p "$HOSTS_ROOT/tmp/home"
hosts_quiet_settings "$HOSTS_ROOT/tmp/home"
hosts_xvfb_start
# The GUI's pid (a host pid: the root shares the pid namespace) goes to /tmp/gui.pid.
hosts_in_root env HOME=/tmp/home XDG_RUNTIME_DIR=/tmp sh -c 'echo $$ > /tmp/gui.pid; exec meshlab "$1"' sh \
  $share/bunny.ply > "$HOSTS_ROOT.gui" 2>&1 &
gui_job=$!
sleep "${WAIT:-12}"
windows="$(hosts_in_root sh -c 'for w in $(xdotool search --onlyvisible --name "."); do xdotool getwindowname $w; done' 2>/dev/null | sort -u | tr '\n' '|')"
hosts_screenshot "$out/$dist-gui.png"
gui_pid="$(cat "$HOSTS_ROOT/tmp/gui.pid")"
kill -0 "$gui_pid" 2>/dev/null || { cat "$HOSTS_ROOT.gui"; fail "the GUI did not keep running"; }
kill "$gui_pid"
wait "$gui_job" 2>/dev/null || true
gui_job=
hosts_xvfb_stop
case "$windows" in *MeshLab*) ;; *) fail "no MeshLab window (windows: $windows)" ;; esac
case "$windows" in *rror*|*arning*) fail "an error window is open (windows: $windows)" ;; esac
echo "[deb_test] $dist: GUI up with the bunny, windows: ${windows%|}; screenshot $out/$dist-gui.png"

hosts_in_root dpkg --purge meshlab-gaussphere >> "$HOSTS_ROOT.log" 2>&1 || { cat "$HOSTS_ROOT.log"; fail "dpkg --purge"; }
snapshot > "$HOSTS_ROOT.after"
if ! diff "$HOSTS_ROOT.before" "$HOSTS_ROOT.after" > "$HOSTS_ROOT.diff"; then
  cat "$HOSTS_ROOT.diff"; fail "removing the package left /usr or /etc changed"
fi
echo "[deb_test] $dist: PASS (removed cleanly)"
