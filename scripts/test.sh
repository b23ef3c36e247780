#!/usr/bin/env bash
# Sets up (Debian packages, MeshLab source), builds everything and runs every test,
# including the end-to-end runs of meshlabserver and the GUI under Xvfb.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${BUILD_DIR:-$here/build}"
bash "$here/scripts/setup.sh"
cmake -S "$here" -B "$build" -DCMAKE_BUILD_TYPE=Release -DGAUSSPHERE_BUILD_PLUGINS=ON -DGAUSSPHERE_BUILD_TESTS=ON >/dev/null
cmake --build "$build" -j "$(nproc)"
cd "$build"
ctest --output-on-failure -j 2 "$@"
