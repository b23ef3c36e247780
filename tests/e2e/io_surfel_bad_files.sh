# meshlabserver refuses broken .surfel files with an error status: no crash (a signal gives
# 128+N, e.g. 134 SIGABRT, 139 SIGSEGV), no hang (124), no output, and the reader's reason in
# its output as one short printable line. It refuses to save a layer the reader would refuse.
source "$E2E_COMMON"
"$SURFEL_FIXTURE" good.surfel 50
size=$(stat -c %s good.surfel)
data=$(( $(grep -abo '^end_header$' good.surfel | head -n 1 | cut -d: -f1) + 11 ))
head -c $((size - 7)) good.surfel > truncated_data.surfel
head -c 200 good.surfel > truncated_header.surfel
: > zero_bytes.surfel
head -c 5000 /dev/zero | tr '\0' '\252' > garbage.surfel
printf 'ply\nformat ascii 1.0\ncomment gaussphere-surfel 1\nelement vertex 1\nend_header\n1 2 3\n' \
  > ascii.surfel
{ printf 'ply\nformat \033[2J'; head -c 60000 /dev/zero | tr '\0' 'A'; printf ' 1.0\n'; } \
  > long_header_line.surfel
# with_float NAME RECORD PROPERTY BYTES: good.surfel with float PROPERTY (0 = x, 5 = nz,
# 12 = minor_z) of RECORD replaced by little-endian BYTES.
with_float() {
  cp good.surfel "$1.surfel"
  printf "$4" | dd of="$1.surfel" bs=1 seek=$((data + $2 * 68 + $3 * 4)) conv=notrunc status=none
}
with_float nan_position 7 0 '\000\000\300\177'
with_float inf_normal 0 5 '\000\000\200\177'
with_float nan_axis 49 12 '\000\000\300\377'

declare -A reason=(
  [truncated_data]="truncated file: the header announces 50 surfels, the data holds 49"
  [truncated_header]="the PLY header has no 'end_header' line"
  [zero_bytes]="not a PLY file"
  [garbage]="not a PLY file"
  [ascii]="unsupported PLY encoding 'format ascii 1.0': .surfel files are binary_little_endian 1.0"
  [long_header_line]="unsupported PLY encoding 'format \\x1b[2JAAAA"
  [nan_position]="surfel 7 has a non-finite x (nan)"
  [inf_normal]="surfel 0 has a non-finite nz (inf)"
  [nan_axis]="surfel 49 has a non-finite minor_z (nan)"
)

failed=0
fail() { echo "FAIL: $*" >&2; failed=1; }
# check_reason LOG FILE ACTION REASON: LOG holds "IOSurfel: cannot ACTION '<path>/FILE': REASON...",
# and that line is short and printable.
check_reason() {
  local line
  line=$(grep -a "^IOSurfel: cannot $3 " "$1" || true)
  if ! grep -qF -- "/$2': $4" <<< "$line"; then
    fail "$1: no line 'IOSurfel: cannot $3 '.../$2': $4'"
  elif [ "$(wc -l <<< "$line")" != 1 ] || [ "${#line}" -gt 400 ] || LC_ALL=C grep -q '[^ -~]' <<< "$line"; then
    fail "$1: the reason is not one short printable line: $line"
  else
    echo "ok: $line"
  fi
}

for input in "${!reason[@]}"; do
  status=0
  "$RUN_MESHLABSERVER" -i "$input.surfel" -o "$input.out.surfel" > "$input.log" 2>&1 || status=$?
  if [ "$status" = 0 ] || [ "$status" = 124 ] || { [ "$status" -gt 128 ] && [ "$status" -le 192 ]; }; then
    fail "$input.surfel: meshlabserver exit status $status, expected a load error"
  elif [ -e "$input.out.surfel" ]; then
    fail "$input.surfel: meshlabserver wrote $input.out.surfel"
  else
    echo "ok: $input.surfel refused with exit status $status"
  fi
  check_reason "$input.log" "$input.surfel" load "${reason[$input]}"
done

# A layer with a NaN position (PLY loads it) is not saved as .surfel: the file would not load.
printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n1 nan 0\n0 1 0\n' \
  > nan_layer.ply
"$RUN_MESHLABSERVER" -i nan_layer.ply -o nan_layer.surfel > nan_layer.log 2>&1 || fail "nan_layer.ply: meshlabserver exit status $?"
if [ -e nan_layer.surfel ] || compgen -G 'nan_layer.surfel.*.part' > /dev/null; then
  fail "nan_layer.ply: meshlabserver wrote nan_layer.surfel"
fi
check_reason nan_layer.log nan_layer.surfel save "surfel 1 has a non-finite y (nan)"
exit $failed
