# meshlabserver refuses broken .surfel files with an error status: no crash (a signal gives
# 128+N, e.g. 134 SIGABRT, 139 SIGSEGV), no hang (124), no output.
source "$E2E_COMMON"
"$SURFEL_FIXTURE" good.surfel 50
size=$(stat -c %s good.surfel)
head -c $((size - 7)) good.surfel > truncated_data.surfel
head -c 200 good.surfel > truncated_header.surfel
: > zero_bytes.surfel
head -c 5000 /dev/zero | tr '\0' '\252' > garbage.surfel
printf 'ply\nformat ascii 1.0\ncomment gaussphere-surfel 1\nelement vertex 1\nend_header\n1 2 3\n' \
  > ascii.surfel

failed=0
for input in truncated_data truncated_header zero_bytes garbage ascii; do
  status=0
  "$RUN_MESHLABSERVER" -i "$input.surfel" -o "$input.out.surfel" || status=$?
  if [ "$status" = 0 ] || [ "$status" = 124 ] || { [ "$status" -gt 128 ] && [ "$status" -le 192 ]; }; then
    echo "FAIL: $input.surfel: meshlabserver exit status $status, expected a load error" >&2
    failed=1
  elif [ -e "$input.out.surfel" ]; then
    echo "FAIL: $input.surfel: meshlabserver wrote $input.out.surfel" >&2
    failed=1
  else
    echo "ok: $input.surfel refused with exit status $status"
  fi
done
exit $failed
