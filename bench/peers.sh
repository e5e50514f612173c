#!/usr/bin/env bash
# radrecon interpolate side by side with the peer tools that Debian packages (scipy's griddata
# and RBFInterpolator, gdal_grid) on the issue's workloads:
#   W1 = 286 random points -> 400 x 400 raster, W3 = 100,000 random points -> 2000 x 2000.
# Installs python3-scipy and gdal-bin if missing (bench only; the tests do not need them) and
# uses Debian's /usr/bin/python3, where they live.
# Prints the median wall time of RUNS runs per tool and method. Long peers run once (see below).
# ONLY=REGEX times only the lines whose label matches (e.g. ONLY='linear|Clough').
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${BUILD:-build}
RUNS=${RUNS:-3}
missing=()
for p in python3-scipy gdal-bin; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

source bench/workloads.sh
make_workloads "$work"
ONLY=${ONLY:-}  # a regular expression: time only the lines whose label matches it
timeit() {  # LABEL RUNS COMMAND...
  local label=$1 runs=$2; shift 2
  if [ -n "$ONLY" ] && ! [[ "$label" =~ $ONLY ]]; then return; fi
  : > "$work/t"
  for _ in $(seq "$runs"); do
    local s e
    s=$(date +%s.%N); "$@" >/dev/null 2>&1; e=$(date +%s.%N)
    echo "$e - $s" | bc -l >> "$work/t"
  done
  printf '%-58s %8.3f s  (%s runs)\n' "$label" "$(median < "$work/t")" "$runs"
}

rr() { "$BUILD/radrecon" interpolate --quiet --samples "$work/$1.csv" "${@:2}"; }
echo "== W1: 286 points -> 400 x 400"
timeit "radrecon natural-neighbour (PFM)" "$RUNS" rr w1 --method natural-neighbour --raster 400x400 --domain 0,0,1,1 --out "$work/o.pfm"
timeit "radrecon shepard mu=4 (PFM)" "$RUNS" rr w1 --method shepard --raster 400x400 --domain 0,0,1,1 --out "$work/o.pfm"
timeit "radrecon multiquadric (PFM)" "$RUNS" rr w1 --method multiquadric --raster 400x400 --domain 0,0,1,1 --out "$work/o.pfm"
timeit "radrecon thin-plate (PFM)" "$RUNS" rr w1 --method thin-plate --raster 400x400 --domain 0,0,1,1 --out "$work/o.pfm"
timeit "gdal_grid invdist power=4, 2 threads (GeoTIFF)" "$RUNS" gdal_grid --config GDAL_NUM_THREADS 2 -q -a invdist:power=4:smoothing=0 \
  -txe 0 1 -tye 0 1 -outsize 400 400 -l w1 "$work/w1.vrt" "$work/g.tif"
cat > "$work/rbf.py" <<'PY'
import sys, numpy as np
from scipy.interpolate import CloughTocher2DInterpolator, RBFInterpolator, griddata
d = np.loadtxt(sys.argv[1], delimiter=",", skiprows=1)
n = int(sys.argv[2]); kind = sys.argv[3]
stride = int(sys.argv[5]) if len(sys.argv) > 5 else 1  # every stride-th row and column of the raster
g = (np.arange(0, n, stride) + 0.5) / n
X, Y = np.meshgrid(g, g)
q = np.column_stack([X.ravel(), Y.ravel()])
if kind == "rbf":
    r = RBFInterpolator(d[:, :2], d[:, 2], kernel="multiquadric", epsilon=1.0)(q)  # scipy's MQ: -sqrt(1 + (eps r)^2)
elif kind == "rbf32":
    r = RBFInterpolator(d[:, :2], d[:, 2], kernel="multiquadric", epsilon=1.0, neighbors=32)(q)
elif kind == "tps":
    r = RBFInterpolator(d[:, :2], d[:, 2], kernel="thin_plate_spline")(q)  # degree 1, as radrecon's
elif kind == "tps32":
    r = RBFInterpolator(d[:, :2], d[:, 2], kernel="thin_plate_spline", neighbors=32)(q)
elif kind == "ct":
    r = CloughTocher2DInterpolator(d[:, :2], d[:, 2])(q)  # all the raster's points in one call
else:
    r = griddata(d[:, :2], d[:, 2], q, method="linear")
np.save(sys.argv[4], r)
PY
timeit "scipy RBFInterpolator multiquadric" "$RUNS" /usr/bin/python3 "$work/rbf.py" "$work/w1.csv" 400 rbf "$work/r.npy"
timeit "scipy RBFInterpolator thin_plate_spline" "$RUNS" /usr/bin/python3 "$work/rbf.py" "$work/w1.csv" 400 tps "$work/r.npy"
timeit "radrecon linear (PFM)" "$RUNS" rr w1 --method linear --raster 400x400 --domain 0,0,1,1 --out "$work/o.pfm"
timeit "scipy griddata linear" "$RUNS" /usr/bin/python3 "$work/rbf.py" "$work/w1.csv" 400 linear "$work/r.npy"
timeit "radrecon clough-tocher (PFM)" "$RUNS" rr w1 --method clough-tocher --raster 400x400 --domain 0,0,1,1 --out "$work/o.pfm"
timeit "scipy CloughTocher2DInterpolator" "$RUNS" /usr/bin/python3 "$work/rbf.py" "$work/w1.csv" 400 ct "$work/r.npy"

echo "== W3: 100,000 points -> 2000 x 2000"
timeit "radrecon natural-neighbour (PFM)" "$RUNS" rr w3 --method natural-neighbour --raster 2000x2000 --domain 0,0,1,1 --out "$work/o.pfm"
timeit "radrecon shepard mu=4 k=32 (PFM)" "$RUNS" rr w3 --method shepard --param k=32 --raster 2000x2000 --domain 0,0,1,1 --out "$work/o.pfm"
timeit "radrecon multiquadric k=32, local patches (PFM)" "$RUNS" rr w3 --method multiquadric --param k=32 --raster 2000x2000 --domain 0,0,1,1 --out "$work/o.pfm"
timeit "radrecon thin-plate k=32, local patches (PFM)" "$RUNS" rr w3 --method thin-plate --param k=32 --raster 2000x2000 --domain 0,0,1,1 --out "$work/o.pfm"
# RBFInterpolator(neighbors=32) solves one 32-point system per query: on every 5th row and column
# of the raster (1/25 of the queries); multiply by 25 for the whole raster.
timeit "scipy RBFInterpolator thin_plate_spline neighbors=32, 1/25 of W3's queries" 1 \
  /usr/bin/python3 "$work/rbf.py" "$work/w3.csv" 2000 tps32 "$work/r.npy" 5
timeit "radrecon sibson-c1 (PFM)" "$RUNS" rr w3 --method sibson-c1 --raster 2000x2000 --domain 0,0,1,1 --out "$work/o.pfm"
timeit "radrecon laplace (PFM)" "$RUNS" rr w3 --method laplace --raster 2000x2000 --domain 0,0,1,1 --out "$work/o.pfm"
timeit "radrecon linear (PFM)" "$RUNS" rr w3 --method linear --raster 2000x2000 --domain 0,0,1,1 --out "$work/o.pfm"
timeit "scipy griddata linear" "$RUNS" /usr/bin/python3 "$work/rbf.py" "$work/w3.csv" 2000 linear "$work/r.npy"
timeit "radrecon clough-tocher (PFM)" "$RUNS" rr w3 --method clough-tocher --raster 2000x2000 --domain 0,0,1,1 --out "$work/o.pfm"
timeit "scipy CloughTocher2DInterpolator" "$RUNS" /usr/bin/python3 "$work/rbf.py" "$work/w3.csv" 2000 ct "$work/r.npy"
timeit "gdal_grid invdistnn power=4 max_points=32 radius=0.05, 2 threads" 1 gdal_grid --config GDAL_NUM_THREADS 2 -q \
  -a invdistnn:power=4:max_points=32:radius=0.05 -txe 0 1 -tye 0 1 -outsize 2000 2000 -l w3 "$work/w3.vrt" "$work/g.tif"
echo "(scipy RBFInterpolator(neighbors=32) on W3 takes ~160 s on this machine (design brief); not rerun.)"
