#!/usr/bin/env bash
# The far field's error bound (solve --far-field-error, issue 13 point 1): time and accuracy of
# the distance rule (0) and the bound (2e-2, the default; 5e-3) against a solve with a finer bound, on
# the paper's reference (grid:400) and the Cornell box (grid:32).
# Usage: bench/far_field.sh [path/to/radrecon]   (RUNS=3 by default; medians of wall time)
set -euo pipefail
RADRECON=${1:-build/radrecon}
RUNS=${RUNS:-3}
HERE=$(cd "$(dirname "$0")" && pwd)
OUT=$(mktemp -d "${TMPDIR:-/tmp}/radrecon_far_field.XXXXXX")
trap 'rm -rf "$OUT"' EXIT

median_time() {  # median of RUNS wall times of the command, seconds
  local times=()
  for _ in $(seq "$RUNS"); do
    local t0 t1
    t0=$(date +%s.%N); "$@" >/dev/null 2>&1; t1=$(date +%s.%N)
    times+=("$(echo "$t1 - $t0" | bc)")
  done
  printf '%s\n' "${times[@]}" | sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'
}

for case in "paper grid:400 1e-3" "cornell grid:32 1e-4"; do
  read -r scene mesh fine <<<"$case"
  "$RADRECON" solve --scene "$scene" --mesh "$mesh" --far-field-error "$fine" --out "$OUT/$scene.fine.json" --quiet
  for e in 0 2e-2 5e-3; do
    t=$(median_time "$RADRECON" solve --scene "$scene" --mesh "$mesh" --far-field-error "$e" --out "$OUT/$scene.$e.json" --quiet)
    echo "$scene $mesh --far-field-error $e: median of $RUNS: $t s"
    python3 "$HERE/compare_solutions.py" "$OUT/$scene.$e.json" "$OUT/$scene.fine.json"
  done
done
