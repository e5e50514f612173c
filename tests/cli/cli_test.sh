#!/usr/bin/env bash
# The command-line contract: exit codes (0 success, 2 refused input), messages naming the
# problem, and no output file left behind by a refused or failed run.
# Usage: cli_test.sh /path/to/radrecon
set -u

RADRECON=${1:?usage: cli_test.sh /path/to/radrecon}
TMP=$(mktemp -d "${TMPDIR:-/tmp}/radrecon_cli_test.XXXXXX")
trap 'rm -rf "$TMP"' EXIT
RADRECON_COMMAND=()
# shellcheck source=harness.sh
source "$(dirname "$0")/harness.sh"




# --- help ---------------------------------------------------------------------------------
run help --help
expect_rc help 0

run solve_help solve --help
expect_rc solve_help 0
if ! grep -qF -- "--mesh" "$TMP/solve_help.stdout" "$TMP/solve_help.stderr"; then
  fail "solve_help: 'solve --help' does not mention --mesh"
fi

# --- refused scenes -----------------------------------------------------------------------
printf '{\n  "name": "broken",\n  this is not json\n}\n' >"$TMP/notjson.json"
run notjson solve --scene "$TMP/notjson.json" --mesh grid:2 --out "$TMP/notjson_out.json" --quiet
expect_rc notjson 2
expect_stderr_has notjson "notjson.json"
expect_no_output notjson "$TMP/notjson_out.json"

cat >"$TMP/refl.json" <<'EOF'
{"surfaces": [
  {"name": "floor", "corners": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]], "reflectance": 1.5},
  {"name": "lamp", "corners": [[0,0,1],[0,1,1],[1,1,1],[1,0,1]], "reflectance": 0, "emission": 5}
]}
EOF
run refl solve --scene "$TMP/refl.json" --mesh grid:2 --out "$TMP/refl_out.json" --quiet
expect_rc refl 2
expect_stderr_has refl "refl.json"
expect_stderr_has refl "reflectance"
expect_no_output refl "$TMP/refl_out.json"

run missing solve --scene "$TMP/does_not_exist.json" --mesh grid:2 --out "$TMP/missing_out.json" --quiet
expect_rc missing 2
expect_stderr_has missing "does_not_exist.json"
expect_no_output missing "$TMP/missing_out.json"

# --- where the power went, said after a solve: a closed room absorbs nearly all of it ----------
printf '%s\n' '{"name": "room", "surfaces": [' \
  '{"name": "bottom", "corners": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]], "reflectance": 0.5},' \
  '{"name": "top", "corners": [[0,0,1],[0,1,1],[1,1,1],[1,0,1]], "reflectance": 0.5, "emission": 1},' \
  '{"name": "x0", "corners": [[0,0,0],[0,1,0],[0,1,1],[0,0,1]], "reflectance": 0.5},' \
  '{"name": "x1", "corners": [[1,0,0],[1,0,1],[1,1,1],[1,1,0]], "reflectance": 0.5},' \
  '{"name": "y0", "corners": [[0,0,0],[0,0,1],[1,0,1],[1,0,0]], "reflectance": 0.5},' \
  '{"name": "y1", "corners": [[0,1,0],[1,1,0],[1,1,1],[0,1,1]], "reflectance": 0.5}]}' > "$TMP/room.json"
run room_power solve --scene "$TMP/room.json" --mesh grid:4 --out "$TMP/room_out.json"
expect_rc room_power 0
expect_stderr_has room_power "solve: of 3 W emitted, 100.0% absorbed"

# --- refused mesh options -----------------------------------------------------------------
i=0
for mesh in grid:0 grid:abc foo:3 grid: grid:-1 grid:3x; do
  i=$((i + 1))
  run "mesh$i" solve --scene paper --mesh "$mesh" --out "$TMP/mesh${i}_out.json" --quiet
  expect_rc "mesh$i" 2
  expect_stderr_has "mesh$i" "--mesh"
  expect_no_output "mesh$i" "$TMP/mesh${i}_out.json"
done

# --- a real solve -------------------------------------------------------------------------
run solve solve --scene paper --mesh grid:4 --out "$TMP/solution.json" --quiet
expect_rc solve 0
if [ ! -f "$TMP/solution.json" ]; then
  fail "solve: $TMP/solution.json was not written"
elif ! python3 - "$TMP/solution.json" <<'EOF'
import json, sys
doc = json.load(open(sys.argv[1]))
names = sorted(s["name"] for s in doc["surfaces"])
want = sorted(["ground", "light", "wall1/front", "wall1/back", "wall2/front", "wall2/back"])
if names != want:
    sys.exit(f"surfaces {names}, expected {want}")
if not doc["stats"]["shots"] > 0:
    sys.exit(f"stats.shots = {doc['stats']['shots']}, expected > 0")
EOF
then
  fail "solve: $TMP/solution.json is not a valid solution (see above)"
fi
if compgen -G "$TMP/solution.json.tmp*" >/dev/null; then fail "solve: temporary file left behind"; fi

# --- quadtrees --------------------------------------------------------------------------
for spec in quadtree:287 quadtree:0 quadtree:abc quadtree-eps:-1 quadtree-eps:0 quadtree-eps:nan quadtree:1000000; do
  run "qt_$spec" solve --scene paper --mesh "$spec" --out "$TMP/qt_out.json" --quiet
  expect_rc "qt_$spec" 2
  expect_stderr_has "qt_$spec" "--mesh"
  expect_no_output "qt_$spec" "$TMP/qt_out.json"
done
run qt100 solve --scene paper --mesh quadtree:100 --out "$TMP/qt100.json" --quiet
expect_rc qt100 0
python3 - "$TMP/qt100.json" <<'EOF' || fail "qt100: the ground does not have exactly 100 leaves"
import json, sys
doc = json.load(open(sys.argv[1]))
ground = [s for s in doc["surfaces"] if s["name"] == "ground"][0]
sys.exit(0 if len(ground["elements"]) == 100 and doc["stats"]["method"] == "hierarchical" else 1)
EOF

# --- every command's options: an empty value refused (a required one offered no default), and a
# number option's text that is no number refused in radrecon's words before its range check -------
run patches_text solve --scene paper --mesh grid:4 --patches abc --out "$TMP/pt.json"
expect_rc patches_text 2 && expect_stderr_has patches_text "radrecon: error: --patches: must be a number, got 'abc'"
run fraction_count render --scene paper --solution "$TMP/solution.json" --camera view --samples 2.5 --out "$TMP/fc.png"
expect_rc fraction_count 2 && expect_stderr_has fraction_count "radrecon: error: --samples: must be a whole number, got '2.5'"
run infinite_count render --scene paper --solution "$TMP/solution.json" --camera view --samples inf --out "$TMP/ic.png"
expect_rc infinite_count 2 && expect_stderr_has infinite_count "--samples: must be a whole number, got 'inf'"
run written_count render --scene paper --solution "$TMP/solution.json" --camera view --samples 2.0 --size 8x6 --out "$TMP/wc.png" --quiet
expect_rc written_count 0  # a whole number written as "2.0" or "2e0" is that number
# Decimal numbers only: CLI11 read a hexadecimal "0x10" as 16 (and "0x1p1" as 2).
run hex_count render --scene paper --solution "$TMP/solution.json" --camera view --samples 0x10 --out "$TMP/hex.png"
expect_rc hex_count 2 && expect_stderr_has hex_count "radrecon: error: --samples: must be a decimal number, got '0x10'"
run hex_float render --scene paper --solution "$TMP/solution.json" --camera view --white 0x1p1 --out "$TMP/hex.png"
expect_rc hex_float 2 && expect_stderr_has hex_float "radrecon: error: --white: must be a decimal number, got '0x1p1'"
expect_no_output hex_float "$TMP/hex.png"
run empty_positional compare "" "$TMP/solution.json"
expect_rc empty_positional 2 && expect_stderr_has empty_positional "must not be empty"
if grep -q "leave the option out" "$TMP/empty_positional.stderr"; then fail "empty_positional: offered a default it has not"; fi
run empty_optional solve --scene paper --mesh "" --out "$TMP/em.json"
expect_rc empty_optional 2 && expect_stderr_has empty_optional "--mesh: must not be empty (leave the option out for its default)"

# --- no input overwritten, outputs checked before any work ---------------------------------
cp "$TMP/solution.json" "$TMP/sol_copy.json"
ln -s "$TMP/sol_copy.json" "$TMP/sol_link.png"  # an image name that is the solution
run render_over render --scene paper --solution "$TMP/sol_copy.json" --camera view --size 8x6 --out "$TMP/sol_link.png" --quiet
expect_rc render_over 2
expect_stderr_has render_over "refusing to overwrite"
cmp -s "$TMP/solution.json" "$TMP/sol_copy.json" || fail "render_over: the solution was changed"
cat >"$TMP/scene_in.json" <<'EOF'
{"surfaces": [{"name": "floor", "corners": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]], "reflectance": 0.5},
              {"name": "lamp", "corners": [[0,0,1],[0,1,1],[1,1,1],[1,0,1]], "reflectance": 0, "emission": 1}]}
EOF
cp "$TMP/scene_in.json" "$TMP/scene_keep.json"
run solve_over solve --scene "$TMP/scene_in.json" --mesh grid:2 --out "$TMP/./scene_in.json" --quiet
expect_rc solve_over 2
expect_stderr_has solve_over "refusing to overwrite"
cmp -s "$TMP/scene_in.json" "$TMP/scene_keep.json" || fail "solve_over: the scene was changed"
# Nor a file the scene reads through it: a model's MTL, a glTF's external buffer, the model itself.
mkdir -p "$TMP/models"
cat >"$TMP/models/lamp.obj" <<'EOF'
mtllib lamp.mtl
v 0 0 1
v 0 1 1
v 1 1 1
v 1 0 1
usemtl glow
f 1 2 3 4
EOF
printf 'newmtl glow\nKd 0 0 0\nKe 1 1 1\n' >"$TMP/models/lamp.mtl"
cat >"$TMP/models/floor.gltf" <<'EOF'
{"asset": {"version": "2.0"}, "buffers": [{"uri": "floor.bin", "byteLength": 48}]}
EOF
printf 'not read here' >"$TMP/models/floor.bin"
cat >"$TMP/models/scene.json" <<'EOF'
{"meshes": [{"file": "lamp.obj"}, {"file": "floor.gltf"}],
 "surfaces": [{"name": "floor", "corners": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]], "reflectance": 0.5}]}
EOF
cp -r "$TMP/models" "$TMP/models_keep"
for target in lamp.mtl lamp.obj floor.bin floor.gltf; do
  run "solve_over_$target" solve --scene "$TMP/models/scene.json" --mesh grid:2 --out "$TMP/models/$target" --quiet
  expect_rc "solve_over_$target" 2
  expect_stderr_has "solve_over_$target" "refusing to overwrite"
done
run solve_over_mtl solve --scene "$TMP/models/lamp.obj" --mesh grid:2 --out "$TMP/models/lamp.mtl" --quiet
expect_rc solve_over_mtl 2
diff -r "$TMP/models" "$TMP/models_keep" >/dev/null || fail "solve_over: a model file was changed"
echo "a file" >"$TMP/afile"
start=$(date +%s%N)
run paper_file paper --out "$TMP/afile" --quiet
elapsed_ms=$(( ($(date +%s%N) - start) / 1000000 ))
expect_rc paper_file 2
expect_stderr_has paper_file "not a folder"
[ "$elapsed_ms" -lt 2500 ] || fail "paper_file: refused after $elapsed_ms ms; the folder must be checked before the solve"
run solve_dir solve --scene paper --mesh grid:4 --out "$TMP" --quiet
expect_rc solve_dir 2
expect_stderr_has solve_dir "is a folder"
# Command-line errors the parser finds are worded as every other refusal (docs/cli.md).
run option_twice solve --scene paper --scene paper --mesh grid:4 --out "$TMP/twice.json" --quiet
expect_rc option_twice 2
expect_stderr_has option_twice "radrecon: error: --scene: "
run no_command
expect_rc no_command 2
expect_stderr_has no_command "radrecon: error: A subcommand is required"
# A misspelt command is refused, with --help after it too (that printed the general help, exit 0).
for args in "reconstruct" "reconstruct --help"; do
  run misspelt_command $args
  expect_rc misspelt_command 2
  expect_stderr_has misspelt_command "radrecon: error: reconstruct: not a command; the commands are solve, paper"
done
# A misspelt option leaves the one it meant missing: the misspelling is named first (it was
# hidden behind "--out is required"; an outside-in trial).
run misspelt solve --scene paper --mesh grid:4 --ouy "$TMP/misspelt.json" --quiet
expect_rc misspelt 2
expect_stderr_has misspelt "radrecon: error: --ouy $TMP/misspelt.json: not an option or argument of 'radrecon solve'"
expect_stderr_has misspelt "; and --out is required"
# NaN passes CLI11's ranges: each command that takes --residual refuses it itself (paper and
# cornell aborted on the solver's internal check).
for command in solve paper cornell; do
  run "residual_nan_$command" "$command" --residual nan --out "$TMP/nan_$command" --quiet
  expect_rc "residual_nan_$command" 2
  expect_stderr_has "residual_nan_$command" "--residual: must be a number in [1e-12, 0.5], got nan"
done
run unknown_option solve --scene paper --mesh grid:4 --out "$TMP/unknown.json" --quiet --bogus 3
expect_rc unknown_option 2
expect_stderr_has unknown_option "radrecon: error: --bogus 3: not an option or argument of 'radrecon solve'"
expect_no_output unknown_option "$TMP/unknown.json"

# A solution of another scene (same side names, other lengths) is refused, not drawn wrongly;
# so is a method that fits no side of the solution.
sed 's/"length_u_m": 4,/"length_u_m": 8,/' "$TMP/solution.json" > "$TMP/other_scene.json"
run render_other render --scene paper --solution "$TMP/other_scene.json" --camera view --size 8x6 --out "$TMP/other.png" --quiet
expect_rc render_other 2
expect_stderr_has render_other "another scene"
expect_no_output render_other "$TMP/other.png"
# A solution cut short (a side of the scene missing) or holding no sides: refused, not drawn
# black or aborted (export had failed an internal check on no sides).
/usr/bin/python3 -c '
import json, sys
doc = json.load(open(sys.argv[1]))
doc["surfaces"] = [s for s in doc["surfaces"] if s["name"] != "ground"]
json.dump(doc, open(sys.argv[2], "w"))
doc["surfaces"] = []
json.dump(doc, open(sys.argv[3], "w"))' "$TMP/solution.json" "$TMP/cut.json" "$TMP/no_sides.json"
run render_cut render --scene paper --solution "$TMP/cut.json" --camera view --size 8x6 --out "$TMP/cut.png" --quiet
expect_rc render_cut 2
expect_stderr_has render_cut "cut.json: the scene's side 'ground' is not in the solution (it holds 5 sides)"
expect_no_output render_cut "$TMP/cut.png"
run export_no_sides export --scene paper --solution "$TMP/no_sides.json" --out "$TMP/no_sides.glb" --quiet
expect_rc export_no_sides 2
expect_stderr_has export_no_sides "no_sides.json: surfaces: must be a non-empty array"
expect_no_output export_no_sides "$TMP/no_sides.glb"
run qt_sol solve --scene paper --mesh quadtree:4 --out "$TMP/qt4.json" --quiet
# quadtree:LEAVES counts a room's floor by default (the Cornell box's ceiling, a little larger, had
# taken them).
run qt_cornell solve --scene cornell --mesh quadtree:10 --out "$TMP/qt_cornell.json"
expect_rc qt_cornell 0 && expect_stderr_has qt_cornell "gives 10 leaves on floor"
run render_nofit render --scene paper --solution "$TMP/qt4.json" --method bilinear --camera view --size 8x6 --out "$TMP/nofit.png" --quiet
expect_rc render_nofit 2
expect_stderr_has render_nofit "cannot reconstruct any side"
expect_stderr_has render_nofit "the scattered methods (natural-neighbour"
expect_no_output render_nofit "$TMP/nofit.png"

# --- barriers: the solution lists the wall feet on the ground; render honours them unless told not
# to, and the pictures differ (light no longer leaks under the walls).
grep -q '"barriers": \[\[\[2.6' "$TMP/solution.json" || fail "solve: the ground's barriers are missing from the solution"
for flags in "" "--no-barriers" "--border-samples"; do
  name=render_nn${flags//-/_}
  run "$name" render --scene paper --solution "$TMP/solution.json" --method natural-neighbour --camera closeup \
    --size 48x36 --out "$TMP/$name.pfm" --quiet $flags
  expect_rc "$name" 0
done
cmp -s "$TMP/render_nn.pfm" "$TMP/render_nn__no_barriers.pfm" && fail "render --no-barriers: the same image as with barriers"
cmp -s "$TMP/render_nn.pfm" "$TMP/render_nn__border_samples.pfm" && fail "render --border-samples: the same image as without"

# --- replacing an output keeps its permissions: a private 0600 file stays 0600 (it became 0644,
# the new file's), a 0640 one 0640 ----------------------------------------------------------
for mode in 600 640; do
  run "mode_$mode" solve --scene paper --mesh grid:2 --out "$TMP/mode.json" --quiet
  chmod "$mode" "$TMP/mode.json"
  run "mode_${mode}_again" solve --scene paper --mesh grid:3 --out "$TMP/mode.json" --quiet
  expect_rc "mode_${mode}_again" 0
  [ "$(stat -c %a "$TMP/mode.json")" = "$mode" ] || fail "mode_$mode: the replaced output is $(stat -c %a "$TMP/mode.json")"
  grep -q '"grid": \[3, 3\]' "$TMP/mode.json" || fail "mode_$mode: the output was not replaced"
done
rm -f "$TMP/mode.json"

# --- other failures -----------------------------------------------------------------------
run unknown frobnicate
expect_nonzero unknown
expect_stderr_nonempty unknown

run noout solve --scene paper --mesh grid:2
expect_nonzero noout

run unwritable solve --scene paper --mesh grid:2 --out /proc/nonexistent/x.json --quiet
expect_rc unwritable 2
expect_stderr_has unwritable "/proc/nonexistent"

# A write that fails after the work (a full disk; here a file-size limit of 8 KiB, its signal
# ignored so that the write itself fails, with EFBIG) says so with the system's reason, for each
# writer, and leaves nothing: exit code 2.
limited() {  # NAME ARGS...: run under `ulimit -f 8`, SIGXFSZ ignored
  local name=$1
  shift
  (trap '' XFSZ; ulimit -f 8; exec "$RADRECON" "$@") >"$TMP/$name.stdout" 2>"$TMP/$name.stderr"
  echo $? >"$TMP/$name.rc"
}
awk 'BEGIN { print "x,y"; for (k = 0; k < 1000; k++) printf "%.17g,%.17g\n", k / 1000, 1 - k / 1000 }' >"$TMP/many_queries.csv"
printf 'x,y,v\n0,0,1\n1,0,2\n0,1,3\n1,1,4\n' >"$TMP/four.csv"
limited efbig_json solve --scene paper --mesh grid:8 --out "$TMP/efbig.json" --quiet
limited efbig_csv interpolate --samples "$TMP/four.csv" --queries "$TMP/many_queries.csv" --method shepard \
  --out "$TMP/efbig.csv" --quiet
limited efbig_png render --scene paper --solution "$TMP/solution.json" --camera view --size 640x480 --out "$TMP/efbig.png" --quiet
limited efbig_pfm render --scene paper --solution "$TMP/solution.json" --camera view --size 64x48 --out "$TMP/efbig.pfm" --quiet
limited efbig_glb export --scene paper --solution "$TMP/solution.json" --out "$TMP/efbig.glb" --quiet
for ext in json csv png pfm glb; do
  expect_rc "efbig_$ext" 2
  expect_stderr_has "efbig_$ext" "radrecon: error: $TMP/efbig.$ext: cannot write: File too large"
  expect_no_output "efbig_$ext" "$TMP/efbig.$ext"
done
# A GeoTIFF (libtiff) and an Arc/Info grid (GDAL): the libraries' words, and the system's reason.
for ext in tif asc; do
  limited "efbig_$ext" interpolate --samples "$TMP/four.csv" --raster 100x100 --domain 0,0,1,1 --method shepard \
    --out "$TMP/efbig.$ext" --quiet
  expect_rc "efbig_$ext" 2
  expect_stderr_has "efbig_$ext" "radrecon: error: $TMP/efbig.$ext: "
  expect_stderr_has "efbig_$ext" "File too large"
  expect_no_output "efbig_$ext" "$TMP/efbig.$ext"
done
if compgen -G "$TMP/.radrecon-gdal-*" >/dev/null; then fail "efbig_asc: the temporary folder is left"; fi
# The same limit without the shell ignoring SIGXFSZ: radrecon ignores it itself, so the write fails
# and is said as above; it was killed by the signal (exit 153), silent, its temporary file left.
# An earlier output of the name stays as it was.
cp "$TMP/solution.json" "$TMP/xfsz.json"
(ulimit -f 8; exec "$RADRECON" solve --scene paper --mesh grid:8 --out "$TMP/xfsz.json" --quiet) >"$TMP/xfsz.stdout" 2>"$TMP/xfsz.stderr"
echo $? >"$TMP/xfsz.rc"
expect_rc xfsz 2
expect_stderr_has xfsz "radrecon: error: $TMP/xfsz.json: cannot write: File too large"
cmp -s "$TMP/solution.json" "$TMP/xfsz.json" || fail "xfsz: the earlier xfsz.json was changed"
if compgen -G "$TMP/xfsz.json.tmp*" >/dev/null; then fail "xfsz: temporary file left: $(ls "$TMP"/xfsz.json.tmp*)"; fi
(ulimit -f 8; exec "$RADRECON" interpolate --samples "$TMP/four.csv" --raster 100x100 --domain 0,0,1,1 --method shepard \
  --out "$TMP/xfsz.asc" --quiet) >"$TMP/xfsz_asc.stdout" 2>"$TMP/xfsz_asc.stderr"
echo $? >"$TMP/xfsz_asc.rc"
expect_rc xfsz_asc 2
expect_stderr_has xfsz_asc "File too large"
expect_no_output xfsz_asc "$TMP/xfsz.asc"
if compgen -G "$TMP/.radrecon-gdal-*" >/dev/null; then fail "xfsz_asc: the temporary folder is left"; fi

finish cli_test
