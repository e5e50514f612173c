#!/usr/bin/env bash
# Whole-run benchmark of `radrecon paper` plus the Google Benchmark programs. Prints medians of
# RUNS runs (default 5) of wall time and peak memory; the figures go to docs/benchmarks.md.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${BUILD:-build}
RUNS=${RUNS:-5}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

median() { sort -g | awk '{a[NR]=$1} END {print (NR%2) ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2}'; }

echo "== radrecon paper ($RUNS runs, $(nproc) cores)"
: > "$out/times"; : > "$out/mem"; : > "$out/stages"
for i in $(seq "$RUNS"); do
  /usr/bin/time -f "%e %M" -o "$out/run" "$BUILD/radrecon" paper --out "$out/paper" 2> "$out/log"
  read -r secs kb < "$out/run"
  echo "$secs" >> "$out/times"; echo "$kb" >> "$out/mem"
  grep "paper: done" "$out/log" >> "$out/stages"
done
echo "wall time median: $(median < "$out/times") s   (runs: $(tr '\n' ' ' < "$out/times"))"
echo "peak memory median: $(( $(median < "$out/mem" | cut -d. -f1) / 1024 )) MiB"
echo "stages of the last run: $(tail -1 "$out/stages")"

echo "== radrecon solve --mesh quadtree:N (hierarchical radiosity, epsilon search included; median of $RUNS)"
for n in 100 286 1000 4000; do
  : > "$out/times"; : > "$out/mem"
  for i in $(seq "$RUNS"); do
    /usr/bin/time -f "%e %M" -o "$out/run" "$BUILD/radrecon" solve --mesh "quadtree:$n" --out "$out/q.json" --quiet
    read -r secs kb < "$out/run"
    echo "$secs" >> "$out/times"; echo "$kb" >> "$out/mem"
  done
  links=$(grep -o '"links": [0-9]*' "$out/q.json" | grep -o '[0-9]*')
  eps=$(grep -o '"epsilon_w": [0-9.e-]*' "$out/q.json" | grep -o '[0-9.e-]*$')
  elements=$(grep -o '"elements": [0-9]*' "$out/q.json" | tail -1 | grep -o '[0-9]*')
  echo "quadtree:$n  time $(median < "$out/times") s  peak $(( $(median < "$out/mem" | cut -d. -f1) / 1024 )) MiB  links $links  all leaves $elements  epsilon $eps W"
done

echo "== Google Benchmark"
"$BUILD/bench/bench_solver" --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
"$BUILD/bench/bench_reconstruct" --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
