#!/usr/bin/env bash
# radrecon interpolate to GeoTIFF beside gdal_grid on the same data (issue 12's acceptance):
# natural neighbour against gdal_grid's linear, and shepard with a search radius against
# gdal_grid's invdistnn, on W1 (286 random points -> 400 x 400) and, with W3=1, W3 (100,000 ->
# 2000 x 2000).
# Whole commands, alternating, median wall time of RUNS runs. Both write Float32 GeoTIFFs with a
# no-data value; gdal_grid reads the CSV through an OGR VRT.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${BUILD:-build}
RUNS=${RUNS:-3}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
source bench/workloads.sh
make_workloads "$work"
pair() {  # LABEL_A LABEL_B -- A... -- B...: alternate A and B RUNS times, print both medians
  local la=$1 lb=$2; shift 2; shift  # --
  local a=() b=()
  while [ "$1" != "--" ]; do a+=("$1"); shift; done; shift
  b=("$@")
  : > "$work/ta"; : > "$work/tb"
  for _ in $(seq "$RUNS"); do
    local s e
    s=$(date +%s.%N); "${a[@]}" >/dev/null 2>&1; e=$(date +%s.%N); echo "$e - $s" | bc -l >> "$work/ta"
    s=$(date +%s.%N); "${b[@]}" >/dev/null 2>&1; e=$(date +%s.%N); echo "$e - $s" | bc -l >> "$work/tb"
  done
  local ma mb
  ma=$(median < "$work/ta"); mb=$(median < "$work/tb")
  printf '%-52s %8.3f s\n%-52s %8.3f s   ratio %.2f\n' "$la" "$ma" "$lb" "$mb" "$(echo "$ma / $mb" | bc -l)"
}
# W3 only with W3=1: gdal_grid's linear takes minutes a run there (more than 20 minutes on this
# machine, 2026-12-01), so at W3 it runs only with W3_LINEAR=1.
sets=("w1 400")
if [ "${W3:-0}" = 1 ]; then sets+=("w3 2000"); fi
for w in "${sets[@]}"; do
  set -- $w
  name=$1 size=$2
  echo "== ${name^^}: $(($(wc -l < "$work/$name.csv") - 1)) points -> $size x $size GeoTIFF"
  if [ "$name" = w1 ] || [ "${W3_LINEAR:-0}" = 1 ]; then
  pair "radrecon natural-neighbour outside=none" "gdal_grid linear (2 threads)" -- \
    "$BUILD/radrecon" interpolate --quiet --samples "$work/$name.csv" --method natural-neighbour --param outside=none \
      --raster "${size}x${size}" --domain 0,0,1,1 --out "$work/rr.tif" -- \
    gdal_grid --config GDAL_NUM_THREADS 2 -q -a linear:nodata=-9999 -txe 0 1 -tye 1 0 -outsize "$size" "$size" \
      -ot Float32 -of GTiff -l "$name" "$work/$name.vrt" "$work/gg.tif"
  fi
  pair "radrecon shepard mu=2 radius=0.1 k=32" "gdal_grid invdistnn r=0.1 max_points=32 (2 thr.)" -- \
    "$BUILD/radrecon" interpolate --quiet --samples "$work/$name.csv" --method shepard --param mu=2 --param radius=0.1 \
      --param k=32 --raster "${size}x${size}" --domain 0,0,1,1 --out "$work/rr.tif" -- \
    gdal_grid --config GDAL_NUM_THREADS 2 -q -a invdistnn:power=2:radius=0.1:max_points=32:nodata=-9999 -txe 0 1 -tye 1 0 \
      -outsize "$size" "$size" -ot Float32 -of GTiff -l "$name" "$work/$name.vrt" "$work/gg.tif"
  # The two shepard rasters hold the same function: their largest difference where both have values.
  /usr/bin/python3 - "$work/rr.tif" "$work/gg.tif" <<'PY'
import sys
import numpy as np
from osgeo import gdal
a = gdal.Open(sys.argv[1]).ReadAsArray().astype(float)
b = gdal.Open(sys.argv[2]).ReadAsArray().astype(float)
both = (a != -9999) & (b != -9999)
print(f"   shepard rasters agree to {np.abs(a - b)[both].max():.2e} on {both.sum()} cells; no-data: radrecon {(a == -9999).sum()}, gdal_grid {(b == -9999).sum()}")
PY
done
