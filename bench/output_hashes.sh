#!/usr/bin/env bash
# Prints one SHA-256 per model and setting of gsresample's .surfel output on the models of
# ../shared/data, so that a change can show it leaves the output as it is (diff two runs).
#   bash bench/output_hashes.sh GSRESAMPLE [THREADS...]   (default threads: 1 2)
# Settings: the defaults (level 8), a target of 10 % of the points, an error bound of 0.01.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
gsresample="$(realpath "$1")"; shift
threads=(1 2)
[ $# -gt 0 ] && threads=("$@")
data="${SHARED_DATA_DIR:-$here/../shared/data}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
for model in "$data"/*.ply; do
  case "$model" in *_mesh.ply) continue ;; esac
  name="$(basename "$model" .ply)"
  points="$(head -c 1000 "$model" | grep -a -m1 '^element vertex' | awk '{print $3}')"
  for t in "${threads[@]}"; do
    for setting in "level8:" "target10:--target $(( (points + 5) / 10 ))" "maxerror0.01:--max-error 0.01"; do
      label="${setting%%:*}"; options="${setting#*:}"
      # shellcheck disable=SC2086
      OMP_NUM_THREADS="$t" "$gsresample" "$model" "$work/out.surfel" $options >/dev/null
      echo "$name $label threads=$t $(sha256sum < "$work/out.surfel" | cut -c1-16)"
    done
  done
done
