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

echo "== Google Benchmark"
"$BUILD/bench/bench_solver" --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
"$BUILD/bench/bench_reconstruct" --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
