#!/usr/bin/env bash
# Results do not depend on the number of threads: every command's outputs (solutions, rasters,
# CSV values, pictures, glTF, the paper's tables and figures) are byte for byte the same with 1
# and 2 OpenMP threads, timings left out (the solutions' and errors.json's "seconds").
# Usage: threads_test.sh /path/to/radrecon
set -u

RADRECON=${1:?usage: threads_test.sh /path/to/radrecon}
RADRECON=$(cd "$(dirname "$RADRECON")" && pwd)/$(basename "$RADRECON")
HERE=$(cd "$(dirname "$0")" && pwd)
TMP=$(mktemp -d "${TMPDIR:-/tmp}/radrecon_threads_test.XXXXXX")
trap 'rm -rf "$TMP"' EXIT
cd "$TMP" || exit 1
RADRECON_COMMAND=()
# shellcheck source=harness.sh
source "$HERE/harness.sh"

# Samples: 300 random points of a smooth function (fixed seed), and a 7 x 5 grid of nodes.
awk 'BEGIN { srand(42); print "x,y,v"; for (i = 0; i < 300; i++) { x = rand(); y = rand();
             printf "%.17g,%.17g,%.17g\n", x, y, sin(6 * x) * cos(4 * y) } }' > s.csv
awk 'BEGIN { print "x,y,v"; for (j = 0; j < 5; j++) for (i = 0; i < 7; i++) printf "%d,%d,%d\n", i, j, i * i - 3 * j }' > g.csv
awk 'BEGIN { srand(7); print "x,y"; for (i = 0; i < 500; i++) printf "%.17g,%.17g\n", rand(), rand() }' > q.csv

# Drops timing fields (a line holding "seconds") from JSON outputs.
strip_times() { grep -v '"seconds"' "$1"; }

# both NAME FILES -- ARGS...: runs the command with 1 and with 2 threads, each in its own folder,
# and compares the named output files.
both() {
  local name=$1 files=() t
  shift
  while [ "$1" != "--" ]; do files+=("$1"); shift; done
  shift
  for t in 1 2; do
    mkdir -p "t$t"
    (cd "t$t" && OMP_NUM_THREADS=$t "$RADRECON" "$@" --quiet > "../$name.$t.out" 2>&1) ||
      { fail "$name with $t thread(s): exit code $?: $(head -c 400 "$name.$t.out")"; return; }
  done
  local f
  for f in "${files[@]}"; do
    if [ ! -e "t1/$f" ]; then fail "$name: no $f"; continue; fi
    case "$f" in
      *.json) cmp -s <(strip_times "t1/$f") <(strip_times "t2/$f") || fail "$name: $f differs between 1 and 2 threads" ;;
      *) cmp -s "t1/$f" "t2/$f" || fail "$name: $f differs between 1 and 2 threads" ;;
    esac
  done
}

mkdir -p t1 t2
cp s.csv g.csv q.csv t1/
cp s.csv g.csv q.csv t2/

# --- solve: progressive, hierarchical, the Cornell box --------------------------------------------
both solve_grid paper_grid.json -- solve --scene paper --mesh grid:12 --out paper_grid.json
both solve_quadtree paper_qt.json -- solve --scene paper --mesh quadtree:64 --out paper_qt.json
both solve_cornell cornell.json -- solve --scene cornell --mesh grid:6 --out cornell.json

# --- interpolate: every method that takes points, on a raster and at query points -----------------
for m in constant shepard "shepard k=12" multiquadric "multiquadric k=24" thin-plate "thin-plate k=24" \
         natural-neighbour laplace sibson-c1 linear clough-tocher; do
  read -r method params <<< "$m"
  args=()
  for p in $params; do args+=(--param "$p"); done
  tag=${m// /_}
  both "raster_$tag" "r_$tag.pfm" -- interpolate --samples s.csv --method "$method" "${args[@]}" \
    --raster 64x48 --domain=-0.1,-0.1,1.1,1.1 --out "r_$tag.pfm"
  both "queries_$tag" "q_$tag.csv" -- interpolate --samples s.csv --method "$method" "${args[@]}" \
    --queries q.csv --out "q_$tag.csv"
done
# With barriers: the fits of the subsets a query sees are shared between threads (a cache).
printf '%s\n' '{"type": "LineString", "coordinates": [[0.5, -0.2], [0.5, 0.7]]}' > wall.geojson
cp wall.geojson t1/
cp wall.geojson t2/
for m in shepard natural-neighbour "multiquadric k=24" thin-plate sibson-c1; do
  read -r method params <<< "$m"
  args=()
  for p in $params; do args+=(--param "$p"); done
  tag=${m// /_}
  both "barriers_$tag" "b_$tag.pfm" -- interpolate --samples s.csv --method "$method" "${args[@]}" --barriers wall.geojson \
    --raster 64x48 --domain=-0.1,-0.1,1.1,1.1 --out "b_$tag.pfm"
done
for method in bilinear bicubic hermite; do
  both "grid_$method" "g_$method.pfm" -- interpolate --samples g.csv --method "$method" --raster 50x40 \
    --domain 0,0,6,4 --out "g_$method.pfm"
done

# --- render, export, compare: from the 1-thread solutions ------------------------------------------
cp t1/paper_grid.json t1/paper_qt.json t1/cornell.json t2/
for method in constant natural-neighbour gouraud multiquadric; do
  for ext in png pfm; do
    both "render_${method}_$ext" "v_$method.$ext" -- render --scene paper --solution paper_qt.json --method "$method" \
      --camera view --size 64x48 --samples 2 --out "v_$method.$ext"
  done
done
both export cornell.glb -- export --scene cornell --solution cornell.json --texels 48 --out cornell.glb
for t in 1 2; do
  (cd "t$t" && OMP_NUM_THREADS=$t "$RADRECON" compare v_natural-neighbour.pfm v_constant.pfm --json --diff cmp.png \
     > compare.json 2>/dev/null) || fail "compare with $t thread(s): exit code $?"
done
[ -s t1/compare.json ] || fail "compare: no figures"
cmp -s t1/compare.json t2/compare.json || fail "compare: the figures differ between 1 and 2 threads"
cmp -s t1/cmp.png t2/cmp.png || fail "compare: the difference image differs between 1 and 2 threads"

# --- the paper run at a small reference ----------------------------------------------------------
both paper paper/errors.json paper/table1.md paper/table2.md paper/solutions/reference.json \
  paper/solutions/quadtree.json paper/figures/fig2_reference_ground.png paper/figures/fig3_natural-neighbour_ground.png \
  -- paper --reference 32 --no-barriers --out paper
# With the scene's barriers: the barrier data sets (visible-sample fits, parallel neighbour ranges
# over what each point sees) too.
both paper_barriers walled/errors.json walled/table3.md walled/figures/fig5_natural-neighbour_ground.png \
  walled/figures/fig6_multiquadric_ground.png walled/figures/fig5_sibson-c1_difference.png \
  -- paper --reference 32 --out walled

finish threads_test
