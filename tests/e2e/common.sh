# Sourced first by every meshlabserver test script (see CMakeLists.txt): strict mode, and a
# fresh $WORK_DIR as the current folder, kept after the run for a look at the files.
set -euo pipefail
: "${WORK_DIR:?}"
rm -rf "$WORK_DIR"
mkdir -p "$WORK_DIR"
cd "$WORK_DIR"
