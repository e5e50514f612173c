#!/usr/bin/env bash
# `radrecon render` as a user meets it: pictures of every format and size, its refusals (exit 2,
# nothing written), solutions that do not fit the scene, and the rays drawn black where a method
# has no value, counted.
# Usage: render_test.sh /path/to/radrecon
set -u

RADRECON=${1:?usage: render_test.sh /path/to/radrecon}
TMP=$(mktemp -d "${TMPDIR:-/tmp}/radrecon_render_test.XXXXXX")
trap 'rm -rf "$TMP"' EXIT
RADRECON_COMMAND=()
# shellcheck source=harness.sh
source "$(dirname "$0")/harness.sh"

"$RADRECON" solve --scene paper --mesh grid:4 --out "$TMP/solution.json" --quiet || fail "solve: exit code $?"

# --- render --------------------------------------------------------------------------------
run render_png render --scene paper --solution "$TMP/solution.json" --method bilinear --camera view --size 64x48 --out "$TMP/view.png" --quiet
expect_rc render_png 0
[ -s "$TMP/view.png" ] || fail "render: view.png was not written"
run render_pfm render --scene paper --solution "$TMP/solution.json" --camera closeup --size 32x24 --out "$TMP/view.pfm" --quiet
expect_rc render_pfm 0
head -c 12 "$TMP/view.pfm" | grep -q "^PF" || fail "render: view.pfm has no PFM header"
run render_exr render --scene paper --solution "$TMP/solution.json" --camera view --size 16x12 --out "$TMP/view.exr" --quiet
expect_rc render_exr 0
[ -s "$TMP/view.exr" ] || fail "render: view.exr was not written"
run render_cam render --scene paper --solution "$TMP/solution.json" --camera nosuch --out "$TMP/bad.png"
expect_rc render_cam 2
expect_stderr_has render_cam "closeup"
expect_no_output render_cam "$TMP/bad.png"
printf '{"surfaces": [{"name": "ground", "elements": 3}]}' > "$TMP/badsol.json"
run render_sol render --scene paper --solution "$TMP/badsol.json" --camera view --out "$TMP/bad.png"
expect_rc render_sol 2
expect_stderr_has render_sol "badsol.json"
expect_no_output render_sol "$TMP/bad.png"

# Without --scene, the solution's own built-in scene (a Cornell box solution was refused as the
# paper's: an outside-in trial).
"$RADRECON" solve --scene cornell --mesh grid:4 --out "$TMP/cornell.json" --quiet || fail "solve cornell: exit code $?"
run cornell_default render --solution "$TMP/cornell.json" --camera published --size 32x24 --out "$TMP/cornell.png" --quiet
expect_rc cornell_default 0
run cornell_default_export export --solution "$TMP/cornell.json" --texels 32 --out "$TMP/cornell.glb" --quiet
expect_rc cornell_default_export 0
run cornell_as_paper render --scene paper --solution "$TMP/cornell.json" --camera view --size 32x24 --out "$TMP/cp.png"
expect_rc cornell_as_paper 2
expect_stderr_has cornell_as_paper "the solution was solved from scene 'cornell'"

# The white point: by default the 99th percentile of the lit surfaces in sight, said on stderr.
run render_white render --scene paper --solution "$TMP/solution.json" --camera view --size 32x24 --out "$TMP/white.png"
expect_rc render_white 0
expect_stderr_has render_white "99th percentile"
run render_white_set render --scene paper --solution "$TMP/solution.json" --camera view --size 32x24 --white 3 --out "$TMP/white3.png"
expect_rc render_white_set 0
expect_stderr_has render_white_set "white 3 W/m^2 (--white)"
# A white of zero would divide by zero: refused, not read as the default (render, export, compare).
run render_white_zero render --scene paper --solution "$TMP/solution.json" --camera view --size 32x24 --white 0 --out "$TMP/white0.png"
expect_rc render_white_zero 2
expect_stderr_has render_white_zero "--white: must be positive"
expect_no_output render_white_zero "$TMP/white0.png"
run export_white_zero export --scene paper --solution "$TMP/solution.json" --white 0 --out "$TMP/white0.glb"
expect_rc export_white_zero 2
expect_stderr_has export_white_zero "--white: must be positive"
expect_no_output export_white_zero "$TMP/white0.glb"
run compare_white_zero compare "$TMP/white.png" "$TMP/white3.png" --white 0
expect_rc compare_white_zero 2
expect_stderr_has compare_white_zero "--white: must be positive"
# A light in the ceiling's plane, solved and rendered from below: drawn (the emitter wins the tie).
cat >"$TMP/coplanar.json" <<'EOF'
{"name": "coplanar", "surfaces": [
 {"name": "ceiling", "corners": [[0,0,2.5], [0,4,2.5], [4,4,2.5], [4,0,2.5]], "reflectance": 0.5},
 {"name": "light", "corners": [[1.5,1.5,2.5], [1.5,2.5,2.5], [2.5,2.5,2.5], [2.5,1.5,2.5]], "reflectance": 0, "emission": 40},
 {"name": "floor", "corners": [[0,0,0], [4,0,0], [4,4,0], [0,4,0]], "reflectance": 0.5}],
 "cameras": [{"name": "up", "eye": [2,2,0.5], "target": [2,2,2.5], "up": [0,1,0], "fov_deg": 60}]}
EOF
run coplanar_solve solve --scene "$TMP/coplanar.json" --mesh grid:8 --out "$TMP/coplanar_s.json" --quiet
expect_rc coplanar_solve 0
run coplanar_render render --scene "$TMP/coplanar.json" --solution "$TMP/coplanar_s.json" --camera up --size 60x60 \
  --out "$TMP/coplanar.pfm" --quiet
expect_rc coplanar_render 0
# The light spans 2 x 12.99 of the 60 pixels across: 24 x 24 pixels wholly inside it, 26 x 26 touched.
python3 - "$TMP/coplanar.pfm" <<'PY' || fail "render: the light in the ceiling's plane is not drawn"
import struct, sys
magic, size, scale, body = open(sys.argv[1], "rb").read().split(b"\n", 3)
w, h = map(int, size.split())
red = [struct.unpack_from("<f", body, 12 * k)[0] for k in range(w * h)]
bright = sum(1 for v in red if v > 20)
assert red[30 * w + 30] == 40.0 and 24 * 24 <= bright <= 26 * 26, (red[30 * w + 30], bright)
PY
# A side of one value (the paper's lamp, one leaf) is drawn piecewise constant with no warning:
# any method gives it that (every render of a quadtree solution warned of it).
run quadtree_lamp_solve solve --scene paper --mesh quadtree:49 --out "$TMP/q49.json"
expect_rc quadtree_lamp_solve 0
run quadtree_lamp render --scene paper --solution "$TMP/q49.json" --camera view --size 40x30 --method natural-neighbour \
  --out "$TMP/q49.png" --quiet
expect_rc quadtree_lamp 0
expect_stderr_lacks quadtree_lamp "light"
# A method without barriers warns that it reconstructs across them only for sides it reconstructs:
# gouraud draws triangles' sides piecewise constant, and said so after a warning that it drew
# the floor across its barriers.
cat >"$TMP/tri_floor.json" <<'EOF'
{"surfaces": [{"name": "floor", "corners": [[0, 0, 0], [4, 0, 0], [0, 4, 0]], "reflectance": 0.5},
 {"name": "wall", "corners": [[1, 0.5, 0], [1, 0.5, 1], [1, 2.5, 1], [1, 2.5, 0]], "reflectance": 0.5, "two_sided": true},
 {"name": "light", "corners": [[0.2, 0.2, 2], [0.2, 1.2, 2], [1.2, 1.2, 2], [1.2, 0.2, 2]], "reflectance": 0, "emission": 40}],
 "cameras": [{"name": "c", "eye": [2, -3, 3], "target": [1, 1, 0]}]}
EOF
run tri_floor_solve solve --scene "$TMP/tri_floor.json" --mesh grid:8 --out "$TMP/tri_floor_s.json" --quiet
expect_rc tri_floor_solve 0
run tri_floor_gouraud render --scene "$TMP/tri_floor.json" --solution "$TMP/tri_floor_s.json" --camera c --size 40x30 \
  --method gouraud --out "$TMP/tri_floor.png" --quiet
expect_rc tri_floor_gouraud 0
expect_stderr_has tri_floor_gouraud "gouraud cannot reconstruct side floor"
expect_stderr_lacks tri_floor_gouraud "takes no barriers"
# A lamp facing away from the floor: exit 0 (a scene may be meant so) with a warning that no
# light reaches any surface, and the render says its white point is no lit surface's.
cat >"$TMP/away.json" <<'EOF'
{"surfaces": [{"name": "floor", "corners": [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], "reflectance": 0.5},
 {"name": "lamp", "corners": [[0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]], "reflectance": 0, "emission": 10}],
 "cameras": [{"name": "c", "eye": [0.5, -2, 2], "target": [0.5, 0.5, 0]}]}
EOF
run away solve --scene "$TMP/away.json" --mesh grid:4 --out "$TMP/away_s.json" --quiet
expect_rc away 0
expect_stderr_has away "warning: no light reaches any surface: all 10 W emitted left the scene"
expect_stderr_lacks away "lights no surface"  # the warning of a scene with no surface lit says it all
# Beside a lamp that works, a second one facing the sky: a warning naming it, exit 0.
cat >"$TMP/one_away.json" <<'EOF'
{"surfaces": [{"name": "floor", "corners": [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], "reflectance": 0.5},
 {"name": "lamp", "corners": [[0, 0, 1], [0, 1, 1], [1, 1, 1], [1, 0, 1]], "reflectance": 0, "emission": 10},
 {"name": "skylamp", "corners": [[0, 0, 2], [1, 0, 2], [1, 1, 2], [0, 1, 2]], "reflectance": 0, "emission": 5}]}
EOF
run one_away solve --scene "$TMP/one_away.json" --mesh grid:4 --out "$TMP/one_away_s.json" --quiet
expect_rc one_away 0
expect_stderr_has one_away "warning: light 'skylamp' lights no surface: every other surface lies behind its plane, so its 5 W leave the scene"
expect_stderr_lacks one_away "light 'lamp'"
run away_render render --scene "$TMP/away.json" --solution "$TMP/away_s.json" --camera c --size 40x30 --out "$TMP/away.png"
expect_rc away_render 0
expect_stderr_has away_render "no surface of the solution is lit"
expect_stderr_lacks quadtree_lamp_solve "no light reaches"
# A coarse quadtree's one ceiling leaf centred under the lamp lying on it: no sample outside the
# lamp, so Shepard falls back to piecewise constant (the leaf's value) instead of failing.
run coplanar_coarse solve --scene "$TMP/coplanar.json" --mesh quadtree-eps:10 --out "$TMP/coplanar_q.json" --quiet
expect_rc coplanar_coarse 0
run coplanar_coarse_render render --scene "$TMP/coplanar.json" --solution "$TMP/coplanar_q.json" --camera up \
  --size 60x60 --method shepard --out "$TMP/coplanar_q.pfm" --quiet
expect_rc coplanar_coarse_render 0
expect_stderr_lacks coplanar_coarse_render "cannot reconstruct side ceiling"  # one leaf, one value: exact
python3 - "$TMP/coplanar_q.pfm" "$TMP/coplanar_q.json" <<'PY' || fail "render: the coarse ceiling is not its leaf's value"
import json, struct, sys
magic, size, scale, body = open(sys.argv[1], "rb").read().split(b"\n", 3)
w, h = map(int, size.split())
red = [struct.unpack_from("<f", body, 12 * k)[0] for k in range(w * h)]
ceiling = [s for s in json.load(open(sys.argv[2]))["surfaces"] if s["name"] == "ceiling"][0]["elements"]
assert len(ceiling) == 1, len(ceiling)
value = ceiling[0]["radiosity"][0]
assert red[30 * w + 30] == 40.0, red[30 * w + 30]  # the lamp
assert abs(red[2 * w + 2] - value) <= 1e-6 * value, (red[2 * w + 2], value)  # the ceiling beside it
PY
# Too many rays, or more memory than there is: refused before any work, with advice.
run render_rays render --scene paper --solution "$TMP/solution.json" --camera view --size 8192x8192 --samples 16 --out "$TMP/huge.png"
expect_rc render_rays 2
expect_stderr_has render_rays "--samples 1"
expect_no_output render_rays "$TMP/huge.png"
if ! grep -q __asan_init "$RADRECON"; then  # ASan needs address space beyond any ulimit -v
  (ulimit -v 1000000 && exec "$RADRECON" render --scene paper --solution "$TMP/solution.json" --camera view \
    --size 8000x8000 --samples 1 --out "$TMP/huge.pfm") >"$TMP/render_mem.stdout" 2>"$TMP/render_mem.stderr"
  echo $? >"$TMP/render_mem.rc"
  expect_rc render_mem 2
  expect_stderr_has render_mem "of memory"
  expect_stderr_has render_mem "smaller --size"
  expect_no_output render_mem "$TMP/huge.pfm"
fi

# --- rays that meet points where the method has no value are drawn black, with a warning that
# counts them (they were drawn black in silence) ---------------------------------------------
# One ray a pixel: the count must be the pixels black in the first picture and lit in the second.
run no_value_render render --scene paper --solution "$TMP/solution.json" --camera view --method natural-neighbour \
  --param outside=none --size 32x24 --samples 1 --out "$TMP/nv.pfm" --quiet
expect_rc no_value_render 0 && expect_stderr_has no_value_render "where natural-neighbour gives no value"
run value_render render --scene paper --solution "$TMP/solution.json" --camera view --method natural-neighbour \
  --size 32x24 --samples 1 --out "$TMP/v.pfm" --quiet
expect_rc value_render 0 && expect_stderr_lacks value_render "gives no value"
python3 - "$TMP/nv.pfm" "$TMP/v.pfm" "$TMP/no_value_render.stderr" <<'EOF' || fail "no_value_render: the warning's count is not the pixels it drew black"
import re, struct, sys
def pixels(path):
    data = open(path, "rb").read()
    header = data.split(b"\n", 3)
    w, h = map(int, header[1].split())
    body = header[3]
    n = w * h * (3 if header[0] == b"PF" else 1)
    return [struct.unpack_from("<" + "f" * 3, body, 12 * p) for p in range(w * h)] if n == 3 * w * h else None
nv, v = pixels(sys.argv[1]), pixels(sys.argv[2])
black = sum(1 for a, b in zip(nv, v) if all(c == 0 for c in a) and any(c > 0 for c in b))
said = re.search(r"warning: (\d+) of the (\d+) rays", open(sys.argv[3]).read())
sys.exit(0 if said and int(said.group(1)) == black > 0 and int(said.group(2)) == 32 * 24 else 1)
EOF

# --- radiosity below 0 where a method overshoots (clough-tocher across the walls' feet of a
# quadtree solution): said with the count of such pixels, which the PFM holds as they are -------
run overshoot_solve solve --scene paper --mesh quadtree:286 --out "$TMP/q286.json" --quiet
run overshoot_render render --scene paper --solution "$TMP/q286.json" --camera view --method clough-tocher \
  --size 80x60 --samples 1 --out "$TMP/ct.pfm" --quiet
expect_rc overshoot_render 0 && expect_stderr_has overshoot_render "overshoots the samples there"
python3 - "$TMP/ct.pfm" "$TMP/overshoot_render.stderr" <<'EOF' || fail "overshoot_render: the warning's count is not the pixels below 0"
import re, struct, sys
magic, size, scale, body = open(sys.argv[1], "rb").read().split(b"\n", 3)
w, h = map(int, size.split())
below = sum(1 for p in range(w * h) if min(struct.unpack_from("<fff", body, 12 * p)) < 0)
said = re.search(r"warning: (\d+) pixels hold radiosity below 0", open(sys.argv[2]).read())
sys.exit(0 if said and int(said.group(1)) == below > 0 else 1)
EOF
run no_overshoot_render render --scene paper --solution "$TMP/q286.json" --camera view --method constant \
  --size 80x60 --samples 1 --out "$TMP/c.pfm" --quiet
expect_rc no_overshoot_render 0 && expect_stderr_lacks no_overshoot_render "below 0"

finish render_test
