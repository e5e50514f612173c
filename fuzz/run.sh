#!/usr/bin/env bash
# Runs every libFuzzer harness of radrecon for a set time (docs/hostile.md, "Fuzzing"):
#   fuzz/run.sh BUILD_DIR [SECONDS_EACH=60] [OUT=out/fuzz]
# BUILD_DIR is a tree configured with -DRADRECON_FUZZ=ON (clang). The harnesses run FUZZ_JOBS at a
# time (default nproc: two on the project's machine), each from its seed corpus
# (fuzz/corpus/<harness>) and the hostile inputs of its kind (tests/hostile/inputs), growing a
# working corpus in OUT/<harness>/corpus that later runs start from. A crash, leak, timeout or out-of-memory leaves its input in
# OUT/<harness>/ and fails the run, naming it: fix the reader, then add the input to the seed
# corpus, where ctest's fuzz.<harness> replays it from then on.
set -uo pipefail
build=${1:?usage: fuzz/run.sh BUILD_DIR [SECONDS_EACH] [OUT]}
seconds=${2:-60}
out=${3:-out/fuzz}
here="$(cd "$(dirname "$0")" && pwd)"
hostile="$here/../tests/hostile/inputs"
jobs=${FUZZ_JOBS:-$(nproc)}
# Leaks inside Debian's assimp are not ours to fix (fuzz/lsan_suppressions.txt says which).
export LSAN_OPTIONS="suppressions=$here/lsan_suppressions.txt:print_suppressions=0"

harnesses=(scene_json solution_json samples_csv query_csv geojson mesh_obj mesh_gltf mesh_glb mesh_ply picture_pfm
           picture_png)
declare -A hostile_glob=([scene_json]='scene_*.json' [solution_json]='solution_*.json' [samples_csv]='*.csv'
                         [query_csv]='*.csv' [geojson]='*.geojson' [mesh_obj]='*.obj' [mesh_gltf]='*.gltf'
                         [mesh_glb]='*.glb' [mesh_ply]='*.ply' [picture_pfm]='*.pfm'
                         [picture_png]='*.png')

for h in "${harnesses[@]}"; do
  if [ ! -x "$build/fuzz/fuzz_$h" ]; then
    echo "fuzz: $build/fuzz/fuzz_$h is missing: configure $build with -DRADRECON_FUZZ=ON and build it" >&2
    exit 2
  fi
  mkdir -p "$out/$h/corpus"
  # shellcheck disable=SC2086
  cp -n "$hostile"/${hostile_glob[$h]} "$out/$h/corpus/" 2>/dev/null || true
done

run_one() {
  local h=$1
  # The harness's input files, in a folder removed after it (libFuzzer's _Exit cannot).
  export RADRECON_FUZZ_TMP="$out/$h/inputs"
  # Inputs up to 16 KiB (the largest seed is 8 KiB); 10 s per input and 2 GiB are a hang and a
  # memory blow-up.
  "$build/fuzz/fuzz_$h" -max_total_time="$seconds" -max_len=16384 -timeout=10 -rss_limit_mb=2048 \
    -print_final_stats=1 -artifact_prefix="$out/$h/" "$out/$h/corpus" "$here/corpus/$h" \
    > "$out/$h/log.txt" 2>&1
  local status=$?
  rm -rf "$RADRECON_FUZZ_TMP"
  local runs
  runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$out/$h/log.txt" | grep -o '[0-9]*$')
  if [ $status -eq 0 ]; then
    printf 'fuzz: %-14s %8s inputs in %s s, no failure\n' "$h" "${runs:-?}" "$seconds"
  else
    echo "fuzz: $h FAILED (exit $status); its input and log are in $out/$h/:" >&2
    grep -E "ERROR|SUMMARY|Test unit written|==[0-9]+==" "$out/$h/log.txt" | head -12 >&2
  fi
  return $status
}
export -f run_one
export build seconds out here

echo "fuzz: ${#harnesses[@]} harnesses, $seconds s each, $jobs at a time"
printf '%s\n' "${harnesses[@]}" | xargs -P "$jobs" -I{} bash -c 'run_one {}'
status=$?
[ $status -eq 0 ] || echo "fuzz: some harness failed (see above)" >&2
exit $status
