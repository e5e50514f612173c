#!/usr/bin/env bash
# Two builds of radrecon side by side, whole commands interleaved run by run (the machine is
# noisy; ratios within one run are what count): the paper run, quadtree solves, a large render
# and interpolation workloads W1 (286 points -> 400 x 400) and W3 (100,000 points -> 2000 x 2000).
# Prints the median wall time of each and the ratio NEW / OLD.
# Usage: bench/compare_builds.sh OLD_RADRECON NEW_RADRECON [RUNS=5]
# CORNELL=1 adds issue 11's Cornell box solves (grid:64, grid:128, quadtree:1000 on the floor):
# minutes more.
set -euo pipefail
OLD=${1:?usage: compare_builds.sh OLD_RADRECON NEW_RADRECON [RUNS]}
NEW=${2:?usage: compare_builds.sh OLD_RADRECON NEW_RADRECON [RUNS]}
RUNS=${3:-5}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

python3 - "$work" <<'PY'
import math, random, sys
work = sys.argv[1]
for name, n in [("w1", 286), ("w3", 100000)]:
    rng = random.Random(2024)
    with open(f"{work}/{name}.csv", "w") as f:
        f.write("x,y,value\n")
        for _ in range(n):
            x, y = rng.random(), rng.random()
            f.write(f"{x!r},{y!r},{math.sin(6 * x) * math.cos(4 * y)!r}\n")
PY
"$NEW" solve --scene paper --mesh grid:16 --out "$work/grid16.json" --quiet

median() { sort -g | awk '{a[NR]=$1} END {print (NR%2) ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2}'; }
# compare LABEL ARGS...: ARGS with OUT in place of the output path, run alternately by both builds.
compare() {
  local label=$1
  shift
  : > "$work/old.t"
  : > "$work/new.t"
  for _ in $(seq "$RUNS"); do
    for which in old new; do
      local bin=$OLD
      [ "$which" = new ] && bin=$NEW
      local args=("${@//OUT/$work/out_$which}")
      local t0=$EPOCHREALTIME
      "$bin" "${args[@]}" >/dev/null 2>&1
      local t1=$EPOCHREALTIME
      awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.4f\n", b - a }' >> "$work/$which.t"
    done
  done
  local o n
  o=$(median < "$work/old.t")
  n=$(median < "$work/new.t")
  printf '%-44s old %7.3f s   new %7.3f s   new/old %.3f\n' "$label" "$o" "$n" "$(awk -v n="$n" -v o="$o" 'BEGIN { print n / o }')"
}

echo "== $RUNS runs each, interleaved, $(nproc) cores"
compare "--version (start-up)" --version
compare "paper" paper --out OUT --quiet
compare "solve quadtree:1000" solve --mesh quadtree:1000 --out OUT.json --quiet
compare "render 1600x1200, 9 rays/pixel, shepard" render --solution "$work/grid16.json" --method shepard \
  --camera view --size 1600x1200 --out OUT.png --quiet
compare "W1 natural-neighbour" interpolate --samples "$work/w1.csv" --method natural-neighbour --raster 400x400 --domain 0,0,1,1 --out OUT.pfm --quiet
# GeoTIFF needs each build's GDAL plugin beside it (a copied binary has none): skipped, said so.
if "$OLD" interpolate --samples "$work/w1.csv" --method constant --raster 2x2 --domain 0,0,1,1 --out "$work/probe_old.tif" --quiet >/dev/null 2>&1 &&
   "$NEW" interpolate --samples "$work/w1.csv" --method constant --raster 2x2 --domain 0,0,1,1 --out "$work/probe_new.tif" --quiet >/dev/null 2>&1; then
  compare "W1 natural-neighbour to GeoTIFF" interpolate --samples "$work/w1.csv" --method natural-neighbour --raster 400x400 --domain 0,0,1,1 --out OUT.tif --quiet
else
  echo "W1 natural-neighbour to GeoTIFF: skipped (a build cannot write GeoTIFF: its GDAL plugin is not beside it)"
fi
compare "W1 shepard" interpolate --samples "$work/w1.csv" --method shepard --raster 400x400 --domain 0,0,1,1 --out OUT.pfm --quiet
compare "W1 multiquadric" interpolate --samples "$work/w1.csv" --method multiquadric --raster 400x400 --domain 0,0,1,1 --out OUT.pfm --quiet
compare "W3 natural-neighbour" interpolate --samples "$work/w3.csv" --method natural-neighbour --raster 2000x2000 --domain 0,0,1,1 --out OUT.pfm --quiet
compare "W3 shepard k=32" interpolate --samples "$work/w3.csv" --method shepard --param k=32 --raster 2000x2000 --domain 0,0,1,1 --out OUT.pfm --quiet
compare "W3 multiquadric k=32" interpolate --samples "$work/w3.csv" --method multiquadric --param k=32 --raster 2000x2000 --domain 0,0,1,1 --out OUT.pfm --quiet
if [ "${CORNELL:-0}" = 1 ]; then
  compare "Cornell quadtree:1000 on the floor" solve --scene cornell --mesh quadtree:1000 --leaves-on floor --out OUT.json --quiet
  compare "Cornell grid:64" solve --scene cornell --mesh grid:64 --out OUT.json --quiet
  compare "Cornell grid:128" solve --scene cornell --mesh grid:128 --out OUT.json --quiet
fi
