#!/usr/bin/env bash
# The local multiquadric against natural neighbour on a real elevation model (issue 12, item 3):
# the Jacksboro fault DEM that Debian's python-matplotlib-data ships (344 x 403 nodes, 3 arc
# seconds, metres; taken as 74.5 m x 92.5 m cells at its latitude). N random nodes are the
# samples, 20,000 others are held out; errors at the held-out nodes against their true
# elevation, over all of them and over the 10% nearest the edges of the grid (corners included).
# Usage: bash bench/dem_edges.sh [radrecon binary]
# With CHECK=1 (ctest reconstruct.dem_edges) it also requires the target for the default local
# multiquadric (poly=0) at k = 16 and 32: RMSE no worse than natural neighbour's and the largest
# error within 1.5 times its, overall and in the edge band; exit 1 otherwise.
set -euo pipefail
cd "$(dirname "$0")/.."
RADRECON=${1:-build/radrecon}
DEM=/usr/share/matplotlib/mpl-data/sample_data/jacksboro_fault_dem.npz
[ -f "$DEM" ] || { echo "dem_edges: $DEM missing (apt-get install python-matplotlib-data)" >&2; exit 77; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
/usr/bin/python3 - "$DEM" "$work" <<'PY'
import sys, numpy as np
dem, work = sys.argv[1:]
e = np.load(dem)['elevation'].astype(float)
jj, ii = np.mgrid[0:e.shape[0], 0:e.shape[1]]
x, y, z = ii.ravel() * 74.5, jj.ravel() * 92.5, e.ravel()
rng = np.random.default_rng(7)
for n in [1000, 10000, 100000]:
    perm = rng.permutation(x.size)
    s, h = perm[:n], perm[n:][:20000]
    np.savetxt(f'{work}/s{n}.csv', np.column_stack([x[s], y[s], z[s]]), delimiter=',', header='x,y,z', comments='', fmt='%.10g')
    np.savetxt(f'{work}/q{n}.csv', np.column_stack([x[h], y[h], z[h]]), delimiter=',', header='x,y,truth', comments='', fmt='%.10g')
PY
: > "$work/nn"
failed=0
printf '| samples | method | RMSE (m) | max (m) | edge band RMSE (m) | edge band max (m) |\n|---|---|---|---|---|---|\n'
for n in 1000 10000 100000; do
  for m in "natural-neighbour" "multiquadric k=16" "multiquadric k=32" "multiquadric k=16 poly=1" "multiquadric k=32 poly=1"; do
    read -r method params <<< "$m"
    args=()
    for p in $params; do args+=(--param "$p"); done
    "$RADRECON" interpolate --samples "$work/s$n.csv" --queries "$work/q$n.csv" --method "$method" "${args[@]}" \
      --out "$work/o.csv" --quiet
    /usr/bin/python3 - "$work/q$n.csv" "$work/o.csv" "$n" "$m" "$work/nn" "${CHECK:-0}" <<'PY' || failed=1
import sys, numpy as np
q = np.loadtxt(sys.argv[1], delimiter=',', skiprows=1); o = np.loadtxt(sys.argv[2], delimiter=',', skiprows=1)
err = o[:, 2] - q[:, 2]
x, y = q[:, 0], q[:, 1]
edge = np.minimum.reduce([x - x.min(), x.max() - x, y - y.min(), y.max() - y])
band = edge < np.percentile(edge, 10)
rms = lambda a: np.sqrt(np.mean(a ** 2))
figures = [rms(err), np.abs(err).max(), rms(err[band]), np.abs(err[band]).max()]
print(f"| {sys.argv[3]} | {sys.argv[4]} | {figures[0]:.2f} | {figures[1]:.1f} | {figures[2]:.2f} | {figures[3]:.1f} |")
if sys.argv[4] == "natural-neighbour":
    open(sys.argv[5], "w").write(" ".join(map(str, figures)))
elif sys.argv[6] == "1" and "poly" not in sys.argv[4]:
    nn = list(map(float, open(sys.argv[5]).read().split()))
    bad = [what for what, ok in [("RMSE", figures[0] <= nn[0]), ("max", figures[1] <= 1.5 * nn[1]),
                                 ("edge RMSE", figures[2] <= nn[2]), ("edge max", figures[3] <= 1.5 * nn[3])] if not ok]
    if bad:
        print(f"dem_edges: {sys.argv[3]} samples, {sys.argv[4]}: {', '.join(bad)} beyond natural neighbour's target", file=sys.stderr)
        sys.exit(1)
PY
  done
done
exit "$failed"
