# Everything made from the parameter table agrees with it: the shipped .mlx scripts, the
# README's parameter tables and gsresample's options (the MeshLab dialog is built from the
# table in the filter's code).
set -euo pipefail
work="${WORK_DIR:?}"
rm -rf "$work" && mkdir -p "$work/scripts"
"$GSPARAMS" scripts "$work/scripts"
for generated in "$work"/scripts/*.mlx; do
  shipped="$SAMPLE_DIR/$(basename "$generated")"
  [ -f "$shipped" ] || { echo "FAILED: $(basename "$generated") is not shipped in sample_data/" >&2; exit 1; }
  diff -u "$shipped" "$generated" || { echo "FAILED: $shipped differs from the table (run gsparams scripts sample_data)" >&2; exit 1; }
done
echo "ok: $(ls "$work"/scripts | wc -l) shipped scripts match the table"

"$GSPARAMS" readme > "$work/readme_table.md"
sed -n '/^<!-- parameters:begin -->$/,/^<!-- parameters:end -->$/p' "$README" | sed '1d;$d' > "$work/readme_shipped.md"
diff -u "$work/readme_shipped.md" "$work/readme_table.md" ||
  { echo "FAILED: README.md's parameter tables differ from the table (gsparams readme)" >&2; exit 1; }
echo "ok: README.md's parameter tables match the table"

"$GSRESAMPLE" --help > "$work/help.txt"
options=$(sed -n 's/^| `[A-Za-z]*` | `\(--[a-z-]*\)`.*/\1/p' "$work/readme_table.md")
[ -n "$options" ] || { echo "FAILED: no options in the README's table" >&2; exit 1; }
for option in $options; do
  grep -q -- "^  $option " "$work/help.txt" || { echo "FAILED: gsresample --help does not list $option" >&2; exit 1; }
done
listed=$(grep -c -- '^  --' "$work/help.txt")
[ "$listed" = "$(echo "$options" | wc -l)" ] ||
  { echo "FAILED: gsresample --help lists $listed options, the table $(echo "$options" | wc -l)" >&2; exit 1; }
echo "ok: gsresample --help lists the table's $listed options"
