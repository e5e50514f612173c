#!/usr/bin/env bash
# Barriers at scale (issue 9): W3 (100,000 random points -> 2000 x 2000 raster) interpolated
# without barriers and with 500 barrier segments (50 random-walk polylines of 10 segments, steps
# of 0.5-2% of the domain: faults), run alternately. Prints the median wall time of each and the
# ratio; the target is natural-neighbour with barriers within 2x of the plain method.
# Usage: bench/barriers.sh RADRECON [RUNS=5] [METHOD...]
set -euo pipefail
BIN=${1:?usage: barriers.sh RADRECON [RUNS] [METHOD...]}
RUNS=${2:-5}
shift $(( $# >= 2 ? 2 : 1 ))
METHODS=("$@")
[ ${#METHODS[@]} -eq 0 ] && METHODS=(natural-neighbour)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

python3 - "$work" <<'PY'
import json, math, random, sys
work = sys.argv[1]
rng = random.Random(2024)
with open(f"{work}/w3.csv", "w") as f:
    f.write("x,y,value\n")
    for _ in range(100000):
        x, y = rng.random(), rng.random()
        f.write(f"{x!r},{y!r},{math.sin(6 * x) * math.cos(4 * y)!r}\n")
rng = random.Random(9)
lines = []
for _ in range(50):
    p = [rng.uniform(0.05, 0.95), rng.uniform(0.05, 0.95)]
    heading = rng.uniform(0, 2 * math.pi)
    line = [list(p)]
    for _ in range(10):
        heading += rng.uniform(-0.6, 0.6)
        step = rng.uniform(0.005, 0.02)
        p = [p[0] + step * math.cos(heading), p[1] + step * math.sin(heading)]
        line.append(list(p))
    lines.append(line)
json.dump({"type": "MultiLineString", "coordinates": lines}, open(f"{work}/faults.geojson", "w"))
PY

median() { sort -g | awk '{a[NR]=$1} END {print (NR%2) ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2}'; }
seconds() {  # ARGS...: wall time of one run
  local t0=$EPOCHREALTIME
  "$BIN" interpolate "$@" >/dev/null 2>&1
  local t1=$EPOCHREALTIME
  awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.4f\n", b - a }'
}
echo "== W3 with 500 barrier segments, $RUNS runs each, alternating, $(nproc) cores"
for m in "${METHODS[@]}"; do
  : > "$work/plain.t"
  : > "$work/walled.t"
  common=(--samples "$work/w3.csv" --method "$m" --raster 2000x2000 --domain 0,0,1,1 --quiet)
  [ "$m" = shepard ] && common+=(--param k=32)
  [ "$m" = multiquadric ] && common+=(--param k=32)
  for _ in $(seq "$RUNS"); do
    seconds "${common[@]}" --out "$work/plain.pfm" >> "$work/plain.t"
    seconds "${common[@]}" --barriers "$work/faults.geojson" --out "$work/walled.pfm" >> "$work/walled.t"
  done
  p=$(median < "$work/plain.t")
  w=$(median < "$work/walled.t")
  printf '%-20s plain %7.3f s   500 barrier segments %7.3f s   ratio %.2f\n' "$m" "$p" "$w" \
    "$(awk -v w="$w" -v p="$p" 'BEGIN { print w / p }')"
done
