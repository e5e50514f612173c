#!/bin/sh
# Visibility at scale (docs/benchmarks.md, "Visibility through a BVH"): whole solves of the
# scenes bench/make_scenes.py writes, three runs each, with /usr/bin/time's wall and user
# seconds and peak memory. Usage: bash bench/scale.sh RADRECON [OLD_RADRECON]
set -eu
new=$1
old=${2:-}
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
python3 "$(dirname "$0")/make_scenes.py" "$dir" 10 20
run() {  # label binary scene mesh [extra...]
  label=$1 bin=$2 scene=$3 mesh=$4
  shift 4
  for r in 1 2 3; do
    /usr/bin/time -f "$label $scene $mesh $* run$r: %e s wall, %U s user, %M KB" \
      "$bin" solve --scene "$dir/$scene.json" --mesh "$mesh" "$@" --quiet --out "$dir/out.json" 2>&1 | tail -1
  done
}
for bin in "$new" $old; do
  label=$([ "$bin" = "$new" ] && echo new || echo old)
  run $label "$bin" cornell_quads grid:64
  run $label "$bin" cornell_quads quadtree:1000 --leaves-on floor
  run $label "$bin" boxes_10 grid:8 --residual 0.3
  run $label "$bin" boxes_20 grid:8 --residual 0.3
done
