#!/usr/bin/env bash
# A Python call against the command line's work on the same data (issue 12's acceptance: within
# 10% of the CLI's time minus its input and output). W3: 100,000 random points to a 2000 x 2000
# raster, for natural-neighbour and the local multiquadric (k = 32). The CLI's own timing line
# gives building + interpolating (its reading, checking and writing left out); the Python figure
# is the whole call radrecon.interpolate(points, values, raster=..., domain=...), arrays in memory.
# Median of RUNS alternating runs each.
# Usage: bash bench/python_vs_cli.sh [build folder]
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${1:-build}
RUNS=${RUNS:-5}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
source bench/workloads.sh
make_workloads "$work"
for spec in "natural-neighbour" "multiquadric k=32"; do
  read -r method params <<< "$spec"
  args=()
  for p in $params; do args+=(--param "$p"); done
  : > "$work/cli"; : > "$work/py"
  for _ in $(seq "$RUNS"); do
    "$BUILD/radrecon" interpolate --samples "$work/w3.csv" --method "$method" "${args[@]}" --raster 2000x2000 \
      --domain 0,0,1,1 --out "$work/o.pfm" 2>&1 | sed -n 's/.*building \([0-9.]*\) s, interpolating \([0-9.]*\) s.*/\1 \2/p' |
      awk '{print $1 + $2}' >> "$work/cli"
    PYTHONPATH="$BUILD/python" /usr/bin/python3 - "$work/w3.csv" "$method" $params >> "$work/py" <<'PY'
import sys, time, numpy as np, radrecon
data = np.loadtxt(sys.argv[1], delimiter=",", skiprows=1)
params = {k: int(v) for k, v in (p.split("=") for p in sys.argv[3:])}
points, values = np.ascontiguousarray(data[:, :2]), data[:, 2].copy()
t = time.perf_counter()
radrecon.interpolate(points, values, raster=(2000, 2000), domain=(0, 0, 1, 1), method=sys.argv[2], **params)
print(time.perf_counter() - t)
PY
  done
  c=$(median < "$work/cli"); p=$(median < "$work/py")
  printf '%-24s CLI (building + interpolating) %7.3f s   Python call %7.3f s   ratio %.3f\n' "$spec" "$c" "$p" \
    "$(echo "$p / $c" | bc -l)"
done
