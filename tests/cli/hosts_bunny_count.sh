# The count the hosts' end-to-end tests and the package test expect for the shipped bunny
# (HOSTS_BUNNY_SURFELS in scripts/hosts/lib.sh) is what gsresample gives at the defaults: a
# change of the algorithm's output fails here, in the quick stage, not only in the hosts stage.
# Environment: GSRESAMPLE (the program), SOURCE_DIR (the repository), WORK_DIR (a folder of its own).
set -euo pipefail
mkdir -p "$WORK_DIR" && cd "$WORK_DIR"
expected="$(sed -n 's/^HOSTS_BUNNY_SURFELS="${EXPECTED_SURFELS:-\([0-9]*\)}"$/\1/p' "$SOURCE_DIR/scripts/hosts/lib.sh")"
[ -n "$expected" ] || { echo "FAILED: no HOSTS_BUNNY_SURFELS in scripts/hosts/lib.sh" >&2; exit 1; }
"$GSRESAMPLE" "$SOURCE_DIR/sample_data/bunny.ply" bunny.surfel > bunny.log 2>&1
count="$(sed -n 's/.* output \([0-9]*\) .*/\1/p' bunny.log)"
echo "gsresample: $count surfels; scripts/hosts/lib.sh expects $expected"
[ "$count" = "$expected" ] || { echo "FAILED: update HOSTS_BUNNY_SURFELS (and docs/hosts.md) to $count" >&2; exit 1; }
