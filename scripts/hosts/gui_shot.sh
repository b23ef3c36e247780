#!/usr/bin/env bash
# Starts a MeshLab host's GUI in the trixie root under Xvfb with a mesh, takes a screenshot and
# keeps its output: the check that the GUI starts, loads the mesh and (with --plugin) a plugin.
#
#   scripts/hosts/gui_shot.sh VERSION OUT.png MESH [--plugin FILE]... [--exclude NAME]... [STEP]...
#
# VERSION 2022.02 or 2025.07. MESH (a host path) is copied into the root. The GUI runs from a
# staged copy of the host (executable, libmeshlab-common.so, shaders, plugins/ = the host's
# plugins minus --exclude'd file names plus the --plugin files, host paths), with a fresh HOME
# whose MeshLab settings pre-answer the start-up dialogs (QSettings ~/.config/VCG/MeshLab_64bit_fp.conf:
# informativeShown (2025.07's usage-statistics question), dontRemindMeAboutUpgrade, and the
# global parameters MeshLab::System::sendAnonymousData / checkForUpdate = false).
# The STEPs run in the order given, WAIT (default 12) seconds after the start, before OUT.png:
#   --click X,Y       clicks there (xdotool), e.g. to open a menu, then waits 2 s
#   --hover X,Y       moves the pointer there, then waits 1 s (keeps a submenu open on the way)
#   --xdotool ARGS    runs xdotool with ARGS (split at spaces), then waits 2 s
#   --shot FILE.png   takes a screenshot to FILE.png (a host path)
#   --wait-log REGEX  waits until a line of the GUI's output matches REGEX (grep -E), then 1 s
#   --window REGEX    waits until a window whose name matches REGEX (xdotool search --name)
#                     shows, gives it the keyboard focus, then waits 1 s (for --xdotool key/type)
# A wait gives up after STEP_WAIT (default 180) seconds or when the GUI has exited: the steps after it are skipped, the
# screenshot taken, and the exit status is 1 (as when the GUI is no longer running at the end).
# Writes OUT.png and OUT.log (the GUI's stdout and stderr).
set -euo pipefail
here="$(dirname "${BASH_SOURCE[0]}")"
source "$here/lib.sh"
source "$here/host_env.sh"

version="${1:?usage: gui_shot.sh VERSION OUT.png MESH [--plugin FILE]... [--exclude NAME]... [STEP]...}"
out="$(realpath -m "${2:?OUT.png}")"
mesh="$(realpath "${3:?MESH}")"
shift 3
plugins=() excludes=() steps=()
while [ $# -gt 0 ]; do
  case "$1" in
    --plugin) plugins+=("$(realpath "$2")"); shift 2 ;;
    --exclude) excludes+=("$2"); shift 2 ;;
    --click|--hover|--xdotool|--wait-log|--window) steps+=("$1" "$2"); shift 2 ;;
    --shot) steps+=("$1" "$(realpath -m "$2")"); shift 2 ;;
    *) echo "gui_shot.sh: unknown argument $1" >&2; exit 2 ;;
  esac
done

"$here/trixie_root.sh" >/dev/null
hosts_select "$version"

run="/tmp/hosts-gui-$version-$$"        # inside the root
host_run="$HOSTS_ROOT$run"
mkdir -p "$host_run/extra"
chmod 700 "$host_run"
cp "$mesh" "$host_run/"
for p in "${plugins[@]}"; do cp "$p" "$host_run/extra/"; done
hosts_quiet_settings "$host_run/home"

# Stage: the plugin folder is found next to the executable (2025.07: <dir>/plugins) or, for an
# executable in a folder named bin, in ../lib/x86_64-linux-gnu/meshlab/plugins (Debian's 2022.02).
exclude_list="${excludes[*]:-}"
hosts_in_root bash -ec '
  run=$1 bin=$2 common=$3 plugins=$4 version=$5 excludes=$6
  if [ "$version" = 2022.02 ]; then
    mkdir -p $run/stage/bin $run/stage/lib/x86_64-linux-gnu/meshlab/plugins $run/stage/share/meshlab
    cp $bin $run/stage/bin/meshlab
    ln -s $common $run/stage/lib/x86_64-linux-gnu/meshlab/
    ln -s /usr/share/meshlab/shaders $run/stage/share/meshlab/shaders
    dest=$run/stage/lib/x86_64-linux-gnu/meshlab/plugins
    echo $run/stage/bin/meshlab > $run/exe
  else
    mkdir -p $run/stage/plugins
    cp $bin $run/stage/meshlab
    ln -s $common $run/stage/
    ln -s $(dirname $bin)/shaders $run/stage/shaders
    dest=$run/stage/plugins
    echo $run/stage/meshlab > $run/exe
  fi
  for p in $plugins/*.so; do
    case " $excludes " in *" $(basename $p) "*) continue ;; esac
    ln -s $p $dest/
  done
  for p in $run/extra/*.so; do [ -e "$p" ] && ln -s $p $dest/; done
  true' hosts_gui_stage "$run" "$HOST_BIN" "$HOST_COMMON" "$HOST_PLUGINS" "$version" "$exclude_list"

hosts_xvfb_start
trap 'hosts_xvfb_stop; rm -rf "$host_run"' EXIT
exe="$(cat "$host_run/exe")"
# The GUI's pid (a host pid: the root shares the pid namespace) is written to $run/pid.
hosts_in_root env HOME="$run/home" XDG_RUNTIME_DIR="$run" LD_LIBRARY_PATH="$(dirname "$HOST_COMMON")" \
  sh -c 'echo $$ > "$1/pid"; exec "$2" "$3"' sh "$run" "$exe" "$run/$(basename "$mesh")" \
  > "${out%.png}.log" 2>&1 &
gui_job=$!
gave_up=
gui_wait() { # WHAT CMD...: runs CMD every second until it succeeds, STEP_WAIT seconds at most
  local what=$1 until=$((SECONDS + ${STEP_WAIT:-180}))
  shift
  until "$@" >/dev/null 2>&1; do
    kill -0 "$(cat "$host_run/pid")" 2>/dev/null || { gave_up="waiting for $what: the GUI has exited"; return 1; }
    [ "$SECONDS" -lt "$until" ] || { gave_up="waiting for $what after ${STEP_WAIT:-180} s"; return 1; }
    sleep 1
  done
}
sleep "${WAIT:-12}"
set -- "${steps[@]}"
while [ $# -gt 0 ]; do
  case "$1" in
    --click) hosts_in_root xdotool mousemove "${2%,*}" "${2#*,}" click 1; sleep 2 ;;
    --hover) hosts_in_root xdotool mousemove "${2%,*}" "${2#*,}"; sleep 1 ;;
    --xdotool) read -r -a words <<< "$2"; hosts_in_root xdotool "${words[@]}" || true; sleep 2 ;;
    --shot) hosts_screenshot "$2" ;;
    --wait-log) gui_wait "the GUI's output to match '$2'" grep -qE -- "$2" "${out%.png}.log" || break; sleep 1 ;;
    --window)
      gui_wait "a window named '$2'" hosts_in_root xdotool search --onlyvisible --name "$2" || break
      hosts_in_root xdotool search --onlyvisible --name "$2" windowfocus --sync || true
      sleep 1 ;;
  esac
  shift 2
done
hosts_screenshot "$out"
alive=yes
kill -0 "$(cat "$host_run/pid")" 2>/dev/null || alive=no
kill "$(cat "$host_run/pid")" 2>/dev/null || true
wait "$gui_job" 2>/dev/null || true
[ -z "$gave_up" ] || echo "[gui_shot] $version: gave up $gave_up; the steps after it skipped"
echo "[gui_shot] $version: screenshot $out (GUI still running at the shot: $alive), log ${out%.png}.log"
[ "$alive" = yes ] && [ -z "$gave_up" ]
