#!/usr/bin/env bash
# How the cost grows (docs/scaling.md): whole commands at four sizes each, the median wall time
# of RUNS runs (default 3) and the peak resident memory (/usr/bin/time), then the exponent b of
# time ~ a n^b fitted by least squares over the sizes (the smallest size, where start-up
# dominates, left out of the fit when its time is under 0.2 s).
#   bash bench/scaling.sh build/radrecon [RUNS]
# Prints one Markdown table per family: solve against elements (grid:N) and against leaves and
# links (quadtree:LEAVES), interpolate against samples and against queries (natural-neighbour,
# uniform random samples, seed 1), render against pixels and against rays per pixel.
set -euo pipefail
BIN=${1:?usage: bench/scaling.sh RADRECON [RUNS]}
RUNS=${2:-3}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# One measurement: the median wall seconds and the largest peak RSS (MiB) over RUNS runs.
measure() {  # COMMAND...
  local times=() peak=0
  for _ in $(seq "$RUNS"); do
    /usr/bin/time -f "%e %M" -o "$work/time" "$@" >/dev/null 2>"$work/err" || {
      echo "failed: $*" >&2
      cat "$work/err" >&2
      exit 1
    }
    read -r secs kb <"$work/time"
    times+=("$secs")
    [ "$kb" -gt "$peak" ] && peak=$kb
  done
  local median
  median=$(printf '%s\n' "${times[@]}" | sort -g | awk '{a[NR]=$1} END {print a[int((NR + 1) / 2)]}')
  echo "$median $((peak / 1024))"
}

# A family's table and its fitted exponent, from lines "n seconds MiB extra" on stdin.
table() {  # TITLE N-NAME EXTRA-NAME < rows
  cat >"$work/rows"
  python3 - "$@" "$work/rows" <<'EOF'
import math, sys
title, n_name, extra_name, path = sys.argv[1:5]
rows = [line.split() for line in open(path) if line.strip()]
print(f"\n{title}\n")
print(f"| {n_name} | {extra_name} | wall s (median) | peak MiB |" if extra_name != "-" else f"| {n_name} | wall s (median) | peak MiB |")
print("|---:|---:|---:|---:|" if extra_name != "-" else "|---:|---:|---:|")
for r in rows:
    print(f"| {int(float(r[0])):,} | {r[3]} | {r[1]} | {r[2]} |" if extra_name != "-" else f"| {int(float(r[0])):,} | {r[1]} | {r[2]} |")
fit = [r for r in rows if float(r[1]) >= 0.2] or rows
if len(fit) >= 2:
    xs = [math.log(float(r[0])) for r in fit]
    ys = [math.log(max(float(r[1]), 1e-3)) for r in fit]
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    b = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)
    print(f"\ntime ~ {n_name}^{b:.2f} (fitted over {len(fit)} sizes)")
EOF
}

stat() {  # SOLUTION KEY: a number from the solution's stats
  python3 -c "import json, sys; print(json.load(open(sys.argv[1]))['stats'][sys.argv[2]])" "$1" "$2"
}

# --- solve against elements: progressive refinement on the paper scene ---------------------------
for n in 100 200 400 800; do
  read -r secs mib < <(measure "$BIN" solve --scene paper --mesh "grid:$n" --out "$work/g.json" --quiet)
  echo "$(stat "$work/g.json" elements) $secs $mib $(stat "$work/g.json" shots)"
done | table "Solve, progressive (paper scene, grid:100 to grid:800)" elements shots

# --- solve against leaves and links: hierarchical radiosity -----------------------------------
for leaves in 100 400 1600 6400; do
  read -r secs mib < <(measure "$BIN" solve --scene paper --mesh "quadtree:$leaves" --out "$work/q.json" --quiet)
  echo "$leaves $secs $mib $(stat "$work/q.json" links)"
done | table "Solve, hierarchical (paper scene, quadtree:100 to quadtree:6400 leaves on the ground)" leaves links

# --- interpolate against samples, and against queries ------------------------------------------
python3 - "$work" <<'EOF'
import random, sys
random.seed(1)
for n in (1000, 10000, 100000, 1000000):
    with open(f"{sys.argv[1]}/s{n}.csv", "w") as f:
        f.write("x,y,v\n")
        for _ in range(n):
            x, y = random.random(), random.random()
            f.write(f"{x!r},{y!r},{x * x - y!r}\n")
EOF
for n in 1000 10000 100000 1000000; do
  read -r secs mib < <(measure "$BIN" interpolate --samples "$work/s$n.csv" --method natural-neighbour \
    --raster 500x500 --domain 0,0,1,1 --out "$work/r.pfm" --quiet)
  echo "$n $secs $mib"
done | table "Interpolate against samples (natural-neighbour onto 500 x 500)" samples -
for side in 250 500 1000 2000; do
  read -r secs mib < <(measure "$BIN" interpolate --samples "$work/s10000.csv" --method natural-neighbour \
    --raster "${side}x$side" --domain 0,0,1,1 --out "$work/r.pfm" --quiet)
  echo "$((side * side)) $secs $mib"
done | table "Interpolate against queries (natural-neighbour, 10,000 samples)" queries -

# --- render against pixels, and against rays per pixel ------------------------------------------
"$BIN" solve --scene paper --mesh grid:16 --out "$work/s16.json" --quiet
for w in 200 400 800 1600; do
  read -r secs mib < <(measure "$BIN" render --scene paper --solution "$work/s16.json" --method bilinear --camera view \
    --size "${w}x$((w * 3 / 4))" --out "$work/v.pfm" --quiet)
  echo "$((w * w * 3 / 4)) $secs $mib"
done | table "Render against pixels (paper view, bilinear from grid:16, 1 ray a pixel)" pixels -
for s in 1 2 4 8; do
  read -r secs mib < <(measure "$BIN" render --scene paper --solution "$work/s16.json" --method bilinear --camera view \
    --size 400x300 --samples "$s" --out "$work/v.pfm" --quiet)
  echo "$((400 * 300 * s * s)) $secs $mib $((s * s))"
done | table "Render against rays (paper view, 400 x 300 pixels)" rays "rays a pixel"
