# Sourced by the peer benchmarks: the interpolation workloads of issues 12 and 13 in folder $1,
# as CSV (x,y,value) and as an OGR VRT over the CSV for gdal_grid:
#   w1 = 286 random points, w3 = 100,000 random points, in [0,1]^2, value sin(6x) cos(4y),
#   fixed seed. Also median(): the median of the numbers on stdin.
make_workloads() {
  /usr/bin/python3 - "$1" <<'PY'
import sys, numpy as np
work = sys.argv[1]
for name, n in [("w1", 286), ("w3", 100000)]:
    rng = np.random.default_rng(2024)
    p = rng.random((n, 2))
    v = np.sin(6 * p[:, 0]) * np.cos(4 * p[:, 1])
    np.savetxt(f"{work}/{name}.csv", np.column_stack([p, v]), delimiter=",", header="x,y,value", comments="", fmt="%.17g")
PY
  local name
  for name in w1 w3; do
    cat > "$1/$name.vrt" <<VRT
<OGRVRTDataSource><OGRVRTLayer name="$name"><SrcDataSource>$1/$name.csv</SrcDataSource>
<GeometryType>wkbPoint</GeometryType><GeometryField encoding="PointFromColumns" x="x" y="y" z="value"/>
</OGRVRTLayer></OGRVRTDataSource>
VRT
  done
}

median() { sort -g | awk '{a[NR]=$1} END {print (NR%2) ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2}'; }
