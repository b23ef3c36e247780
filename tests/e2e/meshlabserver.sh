#!/usr/bin/env bash
# meshlabserver.sh [meshlabserver arguments...]
#
# Runs the staged meshlabserver ($MESHLABSERVER_BIN, set by tests/e2e/CMakeLists.txt to
# <build>/stage/bin/meshlabserver so that it loads the project's plugins) under a virtual X
# server, since it needs a display even for batch work, and returns its exit status:
# 0 on success, 255 when an input does not load, 128+N when killed by signal N
# (134 SIGABRT, 139 SIGSEGV), 124 when it ran longer than $MESHLABSERVER_TIMEOUT seconds
# (default 300).
#   bash meshlabserver.sh -i in.surfel -s script.mlx -o out.surfel
set -uo pipefail
: "${MESHLABSERVER_BIN:?set MESHLABSERVER_BIN to the staged bin/meshlabserver}"
if [ ! -x "$MESHLABSERVER_BIN" ]; then
  echo "meshlabserver.sh: $MESHLABSERVER_BIN is missing: build the 'stage' target" >&2
  exit 127
fi
# timeout signals the whole process group, Xvfb included.
exec timeout --kill-after=10 "${MESHLABSERVER_TIMEOUT:-300}" \
  xvfb-run -a -s "-screen 0 1280x1024x24" "$MESHLABSERVER_BIN" "$@"
