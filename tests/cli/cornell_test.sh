#!/usr/bin/env bash
# `radrecon cornell` as a user meets it: the built-in Cornell box (small mesh and pictures, for
# speed) gives an HTML page with one picture per reconstruction method, the methods' pictures
# differ, a quads-only scene file works too, and bad options exit with 2 and leave no page.
# Usage: cornell_test.sh /path/to/radrecon
set -u

RADRECON=${1:?usage: cornell_test.sh /path/to/radrecon}
RADRECON=$(cd "$(dirname "$RADRECON")" && pwd)/$(basename "$RADRECON")
HERE=$(cd "$(dirname "$0")" && pwd)
TMP=$(mktemp -d "${TMPDIR:-/tmp}/radrecon_cornell_test.XXXXXX")
trap 'rm -rf "$TMP"' EXIT
cd "$TMP" || exit 1
RADRECON_COMMAND=(cornell)
# shellcheck source=harness.sh
source "$HERE/harness.sh"

SMALL=(--mesh grid:8 --width 40 --height 40 --samples 1 --quiet)

# --- the built-in box: a page, a solution and a picture per method ------------------------------
run box "${SMALL[@]}" --out box
if expect_rc box 0; then
  [ -s box/index.html ] || fail "box: no index.html"
  [ -s box/solution.json ] || fail "box: no solution.json"
  # Every method that `render --help` lists has its picture, named on the page.
  methods=$("$RADRECON" render --help | tr ' ,;()' '\n\n\n\n\n' | grep -xE 'constant|gouraud|bilinear|bicubic|hermite|shepard|multiquadric|thin-plate|natural-neighbour|laplace|sibson-c1|linear|clough-tocher' | sort -u)
  [ "$(echo "$methods" | wc -l)" -ge 13 ] || fail "box: render --help lists only: $methods"
  for m in $methods; do
    [ -s "box/cornell_published_$m.png" ] || fail "box: no picture for $m"
    grep -qF "<b>$m</b>" box/index.html || fail "box: index.html does not name $m"
  done
  # Reconstructions differ: piecewise constant against a smooth method.
  if cmp -s box/cornell_published_constant.png box/cornell_published_shepard.png; then
    fail "box: constant and shepard pictures are identical"
  fi
  # The grid methods fall back on the red wall's triangles, and the page says so.
  grep -qF "red_wall" box/index.html || fail "box: index.html names no fallback on the red wall"
fi

# --- another camera of the box ------------------------------------------------------------------
run blocks "${SMALL[@]}" --camera blocks --out blocks
expect_rc blocks 0 && { [ -s blocks/cornell_blocks_constant.png ] || fail "blocks: no picture"; }

# --- --scene cornell in solve and render: the published camera's picture ---------------------------
"$RADRECON" solve --scene cornell --mesh grid:8 --out solved.json --quiet 2>solve.stderr || fail "solve --scene cornell: $(head -c 300 solve.stderr)"
"$RADRECON" render --scene cornell --solution solved.json --camera published --size 32x32 --samples 1 --out published.png \
  --quiet 2>render.stderr || fail "render --scene cornell: $(head -c 300 render.stderr)"
[ -s published.png ] || fail "render --scene cornell: no picture"

# --- a scene file of quads only -------------------------------------------------------------------
cat >quads.json <<'JSON'
{"name": "room", "surfaces": [
  {"name": "floor", "corners": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]], "reflectance": 0.5},
  {"name": "wall", "corners": [[0,1,0],[1,1,0],[1,1,1],[0,1,1]], "reflectance": [0.6, 0.2, 0.2]},
  {"name": "light", "corners": [[0.3,0.3,1],[0.3,0.7,1],[0.7,0.7,1],[0.7,0.3,1]], "reflectance": 0, "emission": 10}],
 "cameras": [{"name": "front", "eye": [0.5,-1.2,0.6], "target": [0.5,0.5,0.3], "up": [0,0,1], "fov_deg": 50}]}
JSON
run quads "${SMALL[@]}" --scene quads.json --out quads
expect_rc quads 0 && { [ -s quads/room_front_bilinear.png ] && [ -s quads/index.html ] || fail "quads: pictures or page missing"; }
# A scene named "../up": its pictures stay in --out ("_._up_front_METHOD.png"), none goes up.
sed 's/"name": "room"/"name": "..\/up"/' quads.json >up.json
run named_up "${SMALL[@]}" --scene up.json --out named_up
expect_rc named_up 0 && { [ -s named_up/_._up_front_bilinear.png ] || fail "named_up: pictures not in --out: $(ls named_up)"; }
ls | grep -q '_front_' && fail "named_up: a picture left --out"
# The scene lying in --out under a name the command writes: refused before any work, unchanged.
mkdir -p over && cp quads.json over/solution.json
run over_scene "${SMALL[@]}" --scene over/solution.json --out over
expect_rc over_scene 2 && expect_stderr_has over_scene "is the input file"
cmp -s quads.json over/solution.json || fail "over_scene: the scene was overwritten"

# Two of the files it writes that are one file (a link in an existing --out): refused before any
# work, naming both (the second picture had been written over the first).
mkdir -p linked && ln -s cornell_published_constant.png linked/cornell_published_shepard.png
run linked_outputs "${SMALL[@]}" --out linked
expect_rc linked_outputs 2 && expect_stderr_has linked_outputs "is the same file as --out"
expect_stderr_has linked_outputs "cornell_published_shepard.png"
[ -e linked/index.html ] || [ -e linked/cornell_published_constant.png ] && fail "linked_outputs: wrote into linked/"

# --- bad input: exit 2, a message naming the option, no page ---------------------------------------
run bad_mesh "${SMALL[@]}" --mesh quadtree:10 --out bad1
expect_rc bad_mesh 2 && expect_stderr_has bad_mesh "--mesh"
expect_no_output bad_mesh bad1/index.html
run bad_camera "${SMALL[@]}" --camera nowhere --out bad2
expect_rc bad_camera 2 && expect_stderr_has bad_camera "nowhere"
expect_no_output bad_camera bad2/index.html
# A local patch of fewer than 3 samples: refused before any work (it had aborted on an internal
# check after writing pictures, and left the folder without its page).
run bad_rbf_k "${SMALL[@]}" --rbf-k 2 --out bad_rbf
expect_rc bad_rbf_k 2 && expect_stderr_has bad_rbf_k "--rbf-k: must be 0 (one global system) or an integer from 3"
[ -e bad_rbf ] && fail "bad_rbf_k: left bad_rbf/"
run bad_scene "${SMALL[@]}" --scene missing.json --out bad3
expect_rc bad_scene 2 && expect_stderr_has bad_scene "missing.json"

# --- the folder's earlier run: a refused run leaves it whole; the next run removes its pictures
# (another camera's) and nothing of the user's, and lists its own ---------------------------------
echo mine > blocks/notes.txt
run refused_into_blocks "${SMALL[@]}" --mesh grid:bogus --out blocks
expect_rc refused_into_blocks 2
[ -s blocks/cornell_blocks_bilinear.png ] || fail "refused_into_blocks: the earlier run's pictures went"
run published_into_blocks "${SMALL[@]}" --out blocks
expect_rc published_into_blocks 0
[ -e blocks/cornell_blocks_bilinear.png ] && fail "published_into_blocks: the other camera's pictures stayed"
[ -s blocks/notes.txt ] || fail "published_into_blocks: removed a file of the user's"
[ "$(sort blocks/.radrecon-cornell-files)" = "$(cd blocks && find . -type f ! -name notes.txt ! -name .radrecon-cornell-files | sed 's|^\./||' | sort)" ] ||
  fail "published_into_blocks: the list is not the files written: $(cat blocks/.radrecon-cornell-files)"

# --- pictures larger than the memory: refused before the solve, nothing written (the whole image's
# rays are traced at once; it ran out of memory after the solve, its solution left) ------------
if ! grep -q __asan_init "$RADRECON"; then  # ASan needs address space beyond any ulimit -v
  (
    ulimit -v 3000000
    "$RADRECON" cornell --quiet --width 1024 --height 1024 --samples 8 --out too_big >too_big.stdout 2>too_big.stderr
    echo $? >too_big.rc
  )
  [ "$(cat too_big.rc)" = 2 ] || fail "too_big: exit $(cat too_big.rc), expected 2: $(cat too_big.stderr)"
  grep -q "1024x1024 pixels at 64 rays each need about .* of memory" too_big.stderr ||
    fail "too_big: said $(cat too_big.stderr)"
  [ -e too_big ] && fail "too_big: wrote $(ls too_big)"
fi

finish cornell_test
