# The output grows with the Gaussian sphere level n = 8, 16, 24 on the shipped samples and
# on every model of ../shared/data that is present.
source "$E2E_COMMON"
source "$FILTER_TESTS_DIR/lib.sh"
models=("$SAMPLE_DIR"/*.ply)
if [ -d "$SHARED_DATA_DIR" ]; then
  for f in "$SHARED_DATA_DIR"/*.ply; do
    case "$f" in *_mesh.ply) ;; *) models+=("$f") ;; esac
  done
else
  echo "note: $SHARED_DATA_DIR is absent, checking the shipped samples only"
fi
failed=0
for f in "${models[@]}"; do
  name=$(basename "$f" .ply)
  counts=()
  for n in 8 16 24; do
    counts+=("$(resample "$f" "${name}_$n.ply" "$SAMPLE_DIR/resample_level$n.mlx")")
  done
  echo "$name: n=8 ${counts[0]}, n=16 ${counts[1]}, n=24 ${counts[2]}"
  if ! [ "${counts[0]}" -lt "${counts[1]}" ] || ! [ "${counts[1]}" -lt "${counts[2]}" ]; then
    echo "  FAILED: the count does not grow with n" >&2
    failed=1
  fi
done
exit $failed
