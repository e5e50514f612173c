#!/usr/bin/env bash
# `--scene model.obj` and "meshes" in a scene JSON, end to end: a model without an emitter is
# refused (exit 2, saying so and what to write instead, after the import's warnings); a closed box of quads with a Ke lamp
# solves, to the same radiosities as the same box typed into a scene JSON by hand; a malformed
# model is refused naming the file, with no output left; a solution whose surface has moved since
# is refused by render and export.
# Usage: mesh_import_test.sh /path/to/radrecon
set -u

RADRECON=${1:?usage: mesh_import_test.sh /path/to/radrecon}
TMP=$(mktemp -d "${TMPDIR:-/tmp}/radrecon_mesh_import_test.XXXXXX")
trap 'rm -rf "$TMP"' EXIT
RADRECON_COMMAND=()
# shellcheck source=harness.sh
source "$(dirname "$0")/harness.sh"

# The unit box [0,1]^3, its six quads facing in, and a 0.2 x 0.2 m lamp 1 cm under the ceiling,
# facing down.
cat >"$TMP/box.mtl" <<'EOF2'
newmtl wall
Kd 0.5 0.5 0.5
newmtl lamp
Kd 0 0 0
Ke 10 10 10
EOF2
box_geometry() {
  printf 'v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n'
  printf 'v 0.4 0.4 0.99\nv 0.6 0.4 0.99\nv 0.6 0.6 0.99\nv 0.4 0.6 0.99\n'
  printf 'o room\nusemtl wall\nf 1 2 3 4\nf 5 8 7 6\nf 1 5 6 2\nf 4 3 7 8\nf 1 4 8 5\nf 2 6 7 3\n'
}
{ printf 'mtllib box.mtl\n'; box_geometry; printf 'o lamp\nusemtl lamp\nf 9 12 11 10\n'; } >"$TMP/box.obj"
{ printf 'mtllib box.mtl\n'; box_geometry; } >"$TMP/dark.obj"

# --- no emitter: refused, with the way out --------------------------------------------------
run dark solve --scene "$TMP/dark.obj" --mesh grid:2 --out "$TMP/dark_out.json" --quiet
expect_rc dark 2
expect_stderr_has dark "dark.obj"
expect_stderr_has dark "no emitting face"
expect_stderr_has dark '"meshes"'
expect_no_output dark "$TMP/dark_out.json"

# The import's warnings come first: they may say why there is no emitter (its MTL file missing).
{ printf 'mtllib absent.mtl\n'; box_geometry; printf 'o lamp\nusemtl lamp\nf 9 12 11 10\n'; } >"$TMP/nomtl.obj"
run nomtl solve --scene "$TMP/nomtl.obj" --mesh grid:2 --out "$TMP/nomtl_out.json" --quiet
expect_rc nomtl 2
expect_stderr_has nomtl "mtllib 'absent.mtl' not found"
expect_stderr_has nomtl "no emitting face"

# --- with its lamp: solved, as the hand-typed box is ---------------------------------------
# Both with a far-field bound far below the default: the far field's decisions (a block shot
# whole or split) are not continuous in the geometry, and the corners' rounding flips some of
# them at the default, moving radiosities by 3e-5 relative here; at 1e-6 none moves.
run box solve --scene "$TMP/box.obj" --mesh grid:4 --far-field-error 1e-6 --out "$TMP/box_out.json" --quiet
expect_rc box 0
cat >"$TMP/box_by_hand.json" <<'EOF2'
{"name": "box", "surfaces": [
  {"name": "room:0", "corners": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]], "reflectance": 0.5},
  {"name": "room:1", "corners": [[0,0,1],[0,1,1],[1,1,1],[1,0,1]], "reflectance": 0.5},
  {"name": "room:2", "corners": [[0,0,0],[0,0,1],[1,0,1],[1,0,0]], "reflectance": 0.5},
  {"name": "room:3", "corners": [[0,1,0],[1,1,0],[1,1,1],[0,1,1]], "reflectance": 0.5},
  {"name": "room:4", "corners": [[0,0,0],[0,1,0],[0,1,1],[0,0,1]], "reflectance": 0.5},
  {"name": "room:5", "corners": [[1,0,0],[1,0,1],[1,1,1],[1,1,0]], "reflectance": 0.5},
  {"name": "lamp:0", "corners": [[0.4,0.4,0.99],[0.4,0.6,0.99],[0.6,0.6,0.99],[0.6,0.4,0.99]], "reflectance": 0, "emission": 10}]}
EOF2
run by_hand solve --scene "$TMP/box_by_hand.json" --mesh grid:4 --far-field-error 1e-6 --out "$TMP/by_hand_out.json" --quiet
expect_rc by_hand 0
# The two solutions agree number for number to 1e-5 relative: the model's corners are read as
# floats (0.99 and 0.4 are off by up to 3e-8 m), which moves the radiosities by some 2e-6
# relative here (as measured: the largest difference is printed).
if [ "$(rc box)" = 0 ] && [ "$(rc by_hand)" = 0 ]; then
  python3 - "$TMP/box_out.json" "$TMP/by_hand_out.json" <<'EOF2' || fail "box: the model's solution differs from the hand-typed box's"
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
def numbers(x, path=""):
    if isinstance(x, dict):
        for k in sorted(x):
            if k not in ("name", "scene", "source", "seconds", "elapsed_s", "command"):
                yield from numbers(x[k], path + "." + k)
    elif isinstance(x, list):
        for i, v in enumerate(x):
            yield from numbers(v, path + f"[{i}]")
    elif isinstance(x, (int, float)) and not isinstance(x, bool):
        yield path, float(x)
na, nb = list(numbers(a)), list(numbers(b))
assert len(na) == len(nb) and len(na) > 50, (len(na), len(nb))
worst = max(abs(x - y) / max(1.0, abs(y)) for (_, x), (_, y) in zip(na, nb))
print(f"box: {len(na)} numbers, largest relative difference {worst:.2e}")
assert worst < 1e-5, worst
EOF2
fi

# --- "meshes" in a scene JSON: the dark box with a light typed in -------------------------------
cat >"$TMP/lit.json" <<'EOF2'
{"name": "lit", "meshes": [{"file": "dark.obj", "scale": 2}],
 "surfaces": [{"name": "light", "corners": [[0.8,0.8,1.98],[0.8,1.2,1.98],[1.2,1.2,1.98],[1.2,0.8,1.98]], "reflectance": 0, "emission": 10}]}
EOF2
run lit solve --scene "$TMP/lit.json" --mesh grid:2 --out "$TMP/lit_out.json" --quiet
expect_rc lit 0
# A scene of meshes without cameras gets the camera "default" (scene/default_camera.h).
run lit_render render --scene "$TMP/lit.json" --solution "$TMP/lit_out.json" --method constant --camera default \
  --size 16x12 --out "$TMP/lit.png" --quiet
expect_rc lit_render 0
# The light moved 0.1 m since the solve, its size kept: its solution is no longer its own.
sed 's/\[0.8,0.8,1.98\],\[0.8,1.2,1.98\],\[1.2,1.2,1.98\],\[1.2,0.8,1.98\]/[0.9,0.8,1.98],[0.9,1.2,1.98],[1.3,1.2,1.98],[1.3,0.8,1.98]/' \
  "$TMP/lit.json" >"$TMP/moved.json"
grep -q '0.9,0.8,1.98' "$TMP/moved.json" || fail "moved: the light was not moved"
run moved_render render --scene "$TMP/moved.json" --solution "$TMP/lit_out.json" --method constant --camera default \
  --size 16x12 --out "$TMP/moved.png" --quiet
expect_rc moved_render 2
expect_stderr_has moved_render "surface 'light' has an element centred at"
expect_stderr_has moved_render "has moved since the solve"
expect_no_output moved_render "$TMP/moved.png"
run moved_export export --scene "$TMP/moved.json" --solution "$TMP/lit_out.json" --out "$TMP/moved.glb" --quiet
expect_rc moved_export 2
expect_stderr_has moved_export "has moved since the solve"
expect_no_output moved_export "$TMP/moved.glb"
# --scene left out: the default scene is read, and the refusal says which scene was solved (it
# said only "the scene's side 'ground' is not in the solution ... solve the scene again").
run default_scene_render render --solution "$TMP/lit_out.json" --method constant --camera default --size 16x12 \
  --out "$TMP/default_scene.png" --quiet
expect_rc default_scene_render 2
expect_stderr_has default_scene_render "no camera 'default'"
expect_stderr_has default_scene_render "the solution was solved from scene 'lit', and --scene paper is scene 'paper'"
run default_scene_export export --solution "$TMP/lit_out.json" --out "$TMP/default_scene.glb" --quiet
expect_rc default_scene_export 2
expect_stderr_has default_scene_export "is not in the solution"
expect_stderr_has default_scene_export "the solution was solved from scene 'lit'"
expect_no_output default_scene_export "$TMP/default_scene.glb"

# --- a malformed model: refused, naming it ----------------------------------------------------
printf 'v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 9\n' >"$TMP/broken.obj"
run broken solve --scene "$TMP/broken.obj" --mesh grid:2 --out "$TMP/broken_out.json" --quiet
expect_rc broken 2
expect_stderr_has broken "broken.obj"
expect_stderr_has broken "out of range"
expect_no_output broken "$TMP/broken_out.json"
# Each once read with exit 0 and wrong values: a glTF index accessor at byteOffset -2 (read from
# 0), an OBJ vertex of weight w = 2 (divided by it).
python3 - "$TMP/offset.glb" <<'EOF2' || fail "offset: the model was not written"
import json, struct, sys
buf = struct.pack('<12f', 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0) + struct.pack('<6H', 0, 1, 2, 0, 2, 3)
g = {"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
     "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
     "buffers": [{"byteLength": 60}],
     "bufferViews": [{"buffer": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 12}],
     "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3"},
                   {"bufferView": 1, "byteOffset": -2, "componentType": 5123, "count": 6, "type": "SCALAR"}]}
text = json.dumps(g).encode()
text += b' ' * (-len(text) % 4)
body = struct.pack('<II', len(text), 0x4E4F534A) + text + struct.pack('<II', len(buf), 0x004E4942) + buf
open(sys.argv[1], 'wb').write(b'glTF' + struct.pack('<II', 2, 12 + len(body)) + body)
EOF2
printf 'v 0 0 0 2\nv 1 0 0 2\nv 1 1 0 2\nf 1 2 3\n' >"$TMP/weight.obj"
for model in offset.glb weight.obj; do
  printf '{"meshes": [{"file": "%s"}], "surfaces": [{"name": "light", "corners": [[0,0,2],[0,1,2],[1,1,2],[1,0,2]], "reflectance": 0, "emission": 10}]}\n' \
    "$model" >"$TMP/$model.json"
  run "$model" solve --scene "$TMP/$model.json" --mesh grid:2 --out "$TMP/$model.out.json" --quiet
  expect_rc "$model" 2
  expect_no_output "$model" "$TMP/$model.out.json"
done
expect_stderr_has offset.glb "offset.glb: accessors[1].byteOffset: must be an integer >= 0"
expect_stderr_has weight.obj "weight.obj:1: vertex weight w = 2: only 1 is supported"

printf 'solid x\nendsolid x\n' >"$TMP/model.stl"
cat >"$TMP/stl.json" <<'EOF2'
{"meshes": [{"file": "model.stl"}]}
EOF2
run stl solve --scene "$TMP/stl.json" --mesh grid:2 --out "$TMP/stl_out.json" --quiet
expect_rc stl 2
expect_stderr_has stl "meshes[0].file"
expect_stderr_has stl "unknown mesh format"

# The same model as the whole scene: said to be no scene, not a JSON syntax error at its first byte.
printf 'solid x\nendsolid x\n' >"$TMP/model.stl"
run stl_scene solve --scene "$TMP/model.stl" --mesh grid:2 --out "$TMP/stl_scene.json" --quiet
expect_rc stl_scene 2
expect_stderr_has stl_scene "model.stl: not a scene"
expect_stderr_lacks stl_scene "JSON:"
# A scene file of another extension that holds JSON is read as one.
printf '{"surfaces": [{"name": "floor", "corners": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]], "reflectance": 0.5}, {"name": "lamp", "corners": [[0.4,0.4,1],[0.4,0.6,1],[0.6,0.6,1],[0.6,0.4,1]], "reflectance": 0, "emission": 10}]}\n' >"$TMP/room.scene"
run json_other solve --scene "$TMP/room.scene" --mesh grid:2 --out "$TMP/room_out.json" --quiet
expect_rc json_other 0

finish mesh_import_test
