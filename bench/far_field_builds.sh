#!/usr/bin/env bash
# Two builds' progressive solves side by side (issue 13, point 1): the paper's reference
# (grid:400) and the Cornell box (grid:32) at each build's defaults, runs interleaved, with wall
# time, user time and peak memory of each run; then each build's solution against NEW's solve
# with a fine far-field bound (paper 1e-3, Cornell 1e-4), element by element
# (bench/compare_solutions.py).
# Usage: bench/far_field_builds.sh OLD_RADRECON NEW_RADRECON [RUNS=3]
set -euo pipefail
OLD=${1:?usage: far_field_builds.sh OLD_RADRECON NEW_RADRECON [RUNS]}
NEW=${2:?usage: far_field_builds.sh OLD_RADRECON NEW_RADRECON [RUNS]}
RUNS=${3:-3}
HERE=$(cd "$(dirname "$0")" && pwd)
OUT=$(mktemp -d "${TMPDIR:-/tmp}/radrecon_far_field_builds.XXXXXX")
trap 'rm -rf "$OUT"' EXIT
"$NEW" solve --scene paper --mesh grid:400 --far-field-error 1e-3 --out "$OUT/paper_fine.json" --quiet
"$NEW" solve --scene cornell --mesh grid:32 --far-field-error 1e-4 --out "$OUT/cornell_fine.json" --quiet
for run in $(seq "$RUNS"); do
  for build in OLD NEW; do
    for case in "paper grid:400" "cornell grid:32"; do
      read -r scene mesh <<<"$case"
      /usr/bin/time -f "$build $scene $mesh run $run: %e s wall, %U s user, %M KB" \
        "${!build}" solve --scene "$scene" --mesh "$mesh" --out "$OUT/${build}_$scene.json" --quiet
    done
  done
done
for build in OLD NEW; do
  for scene in paper cornell; do
    echo "$build $scene against NEW's fine solve:"
    python3 "$HERE/compare_solutions.py" "$OUT/${build}_$scene.json" "$OUT/${scene}_fine.json"
  done
done
