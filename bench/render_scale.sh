#!/usr/bin/env bash
# Rendering that scales (issue 11): time and peak memory (/usr/bin/time -v, "Maximum resident
# set size") of whole `radrecon render` runs of the paper scene's view, from a grid:16 solution,
# at 4000 x 4000 pixels and 1 and 16 rays a pixel (PNG, default white), and at 16 rays to
# EXR. One run each (a run takes tens of seconds); an OLD binary, if given, runs the same for
# comparison (where it is killed or refused, that is printed).
# Usage: bench/render_scale.sh RADRECON [OLD_RADRECON]
set -uo pipefail
BIN=${1:?usage: render_scale.sh RADRECON [OLD_RADRECON]}
OLD=${2:-}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$BIN" solve --scene paper --mesh grid:16 --out "$work/s.json" --quiet

one() {  # LABEL BINARY SAMPLES OUT
  /usr/bin/time -v -o "$work/time" "$2" render --scene paper --solution "$work/s.json" --camera view \
    --size 4000x4000 --samples "$3" --out "$work/$4" --quiet 2>"$work/err"
  local rc=$?
  local secs rss
  secs=$(awk -F': ' '/Elapsed \(wall clock\)/ {print $2}' "$work/time")
  rss=$(awk -F': ' '/Maximum resident set size/ {printf "%.0f", $2 / 1024}' "$work/time")
  printf "%-4s 4000x4000 x %3d rays -> %-4s  exit %d  %s wall  %s MiB peak  %s\n" "$1" "$(($3 * $3))" "${4##*.}" "$rc" \
    "$secs" "$rss" "$(head -c 200 "$work/err" | tr '\n' ' ')"
  rm -f "$work/$4"
}
echo "== radrecon render, paper scene, camera view, grid:16 constant; $(nproc) cores"
for s in 1 4; do one new "$BIN" "$s" out.png; done
one new "$BIN" 4 out.exr
if [ -n "$OLD" ]; then
  for s in 1 4; do one old "$OLD" "$s" out.png; done
fi
