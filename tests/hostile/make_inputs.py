"""Writes the hostile corpus's input files (tests/hostile/inputs). Run once by hand when a case
is added; the files are committed, so the corpus does not depend on this script's Python."""
import json, math, os, random

here = os.path.join(os.path.dirname(os.path.abspath(__file__)), "inputs")
os.makedirs(here, exist_ok=True)


def write(name, text):
    with open(os.path.join(here, name), "w") as f:
        f.write(text)


def csv(name, rows, header="x,y,v"):
    write(name, header + "\n" + "".join(",".join(repr(c) if isinstance(c, float) else str(c) for c in r) + "\n" for r in rows))


rng = random.Random(14)
plane = lambda x, y: 3.0 + 2.0 * x - 5.0 * y
good = [(rng.random(), rng.random()) for _ in range(40)]
csv("good.csv", [(x, y, plane(x, y)) for x, y in good])
csv("queries.csv", [(rng.uniform(0.2, 0.8), rng.uniform(0.2, 0.8)) for _ in range(20)], "x,y")
write("empty.csv", "")
write("header_only.csv", "x,y,v\n")
write("nan_value.csv", "x,y,v\n0,0,1\n1,0,nan\n0,1,2\n")
write("inf_value.csv", "x,y,v\n0,0,1\n1,0,inf\n0,1,2\n")
write("nan_coordinate.csv", "x,y,v\n0,0,1\nnan,0,1\n0,1,2\n")
# Found by an outside-in trial: a second x became a value column named x; carriage returns alone
# read as one line ("no data rows").
write("duplicate_header.csv", "x,X,y,v\n0,0,0,1\n1,1,0,2\n0,0,1,3\n")
write("cr_only.csv", "x,y,v\r0,0,1\r1,0,2\r0,1,3\r")
write("text_value.csv", "x,y,v\n0,0,1\n1,0,one\n0,1,2\n")
write("short_row.csv", "x,y,v\n0,0,1\n1,0\n0,1,2\n")
write("truncated.csv", "x,y,v\n0,0,1\n1,0,2\n0,1,")
write("one_sample.csv", "x,y,v\n0.5,0.5,1\n")
write("two_samples.csv", "x,y,v\n0,0,1\n1,1,2\n")
csv("collinear.csv", [(t, 2 * t, t) for t in [i / 9 for i in range(10)]])
# All samples on the border of a rectangle: a linear function, defined inside.
border = [(i / 10, 0.0) for i in range(11)] + [(i / 10, 1.0) for i in range(11)] + \
         [(0.0, j / 10) for j in range(1, 10)] + [(1.0, j / 10) for j in range(1, 10)]
csv("rectangle_border.csv", [(x, y, plane(x, y)) for x, y in border])
# Co-circular samples (a regular 16-gon) and its centre: every Delaunay choice is degenerate.
circle = [(0.5 + 0.5 * math.cos(2 * math.pi * k / 16), 0.5 + 0.5 * math.sin(2 * math.pi * k / 16)) for k in range(16)]
csv("cocircular.csv", [(x, y, plane(x, y)) for x, y in circle + [(0.5, 0.5)]])
# Near-duplicates: pairs 1e-12 apart.
near = good[:20] + [(x + 1e-12, y) for x, y in good[:20]]
csv("near_duplicates.csv", [(x, y, plane(x, y)) for x, y in near])
csv("exact_duplicates.csv", [(x, y, plane(x, y)) for x, y in good] + [(good[0][0], good[0][1], plane(*good[0]) + 2)])
# UTM-sized coordinates, 1 m spacing: a 12 x 12 grid jittered by 0.2 m.
utm = [(500000 + i + 0.2 * rng.random(), 5400000 + j + 0.2 * rng.random()) for i in range(12) for j in range(12)]
csv("utm.csv", [(x, y, 0.01 * (x - 500000) - 0.02 * (y - 5400000)) for x, y in utm])
csv("utm_queries.csv", [(500002.5 + 6 * rng.random(), 5400002.5 + 6 * rng.random()) for _ in range(10)], "x,y")
csv("huge.csv", [(x * 1e300, y * 1e300, plane(x, y)) for x, y in good])
csv("huge_values.csv", [(x, y, 1e308 * (-1) ** k) for k, (x, y) in enumerate(good)])
csv("tiny.csv", [(x * 1e-300, y * 1e-300, plane(x, y)) for x, y in good])
csv("nan_queries.csv", [(0.5, 0.5), (float("nan"), 0.5)], "x,y")
# Queries exactly at the samples, and on the hull's edges (midpoints of the hull of good.csv is
# not known here: the rectangle's corners give a hull of known edges).
square = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)] + good[:10]
csv("square.csv", [(x, y, plane(x, y)) for x, y in square])
csv("on_hull_queries.csv", [(t, 0.0) for t in [0.1, 0.37, 0.9]] + [(1.0, t) for t in [0.25, 0.6]] + [(1 / 3, 1.0)], "x,y")
csv("at_samples_queries.csv", good[:10], "x,y")
write("grid_nodes.csv", "x,y,v\n" + "".join(f"{i},{j},{i - j}\n" for j in range(3) for i in range(4)))
write("grid_missing_node.csv", "x,y,v\n" + "".join(f"{i},{j},{i - j}\n" for j in range(3) for i in range(4) if (i, j) != (2, 1)))
# Barriers
write("barrier_point.geojson", json.dumps({"type": "Point", "coordinates": [0.5, 0.5]}))
write("barrier_malformed.geojson", '{"type": "LineString", "coordinates": [[0, 0], [1, 1]')
write("barrier_short.geojson", json.dumps({"type": "LineString", "coordinates": [[0.5, 0.5]]}))
write("barrier_text.geojson", '{"type": "LineString", "coordinates": [[0, 0], ["a", 1]]}')

# Scenes
light = {"name": "light", "corners": [[0.4, 0.4, 1], [0.4, 0.6, 1], [0.6, 0.6, 1], [0.6, 0.4, 1]],
         "reflectance": [0, 0, 0], "emission": [10, 10, 10]}
floor = {"name": "floor", "corners": [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], "reflectance": [0.5, 0.5, 0.5]}
camera = {"name": "view", "eye": [0.5, -1, 0.8], "target": [0.5, 0.5, 0], "up": [0, 0, 1], "fov_deg": 50}


def scene(name, surfaces, cameras=(camera,)):
    write(name, json.dumps({"name": "hostile", "surfaces": surfaces, "cameras": list(cameras)}, indent=1))


scene("scene_good.json", [floor, light])
write("scene_not_json.json", "surfaces: floor\n")
write("scene_truncated.json", json.dumps({"name": "hostile", "surfaces": [floor, light]})[:90])
scene("scene_two_corners.json", [dict(floor, corners=[[0, 0, 0], [1, 0, 0]]), light])
write("scene_nan.json", json.dumps({"name": "hostile", "surfaces": [floor, light]}).replace("0.5, 0.5, 0.5", "NaN, 0.5, 0.5", 1))
write("scene_overflow.json", json.dumps({"name": "hostile", "surfaces": [floor, light]}).replace("[1, 0, 0]", "[1e400, 0, 0]", 1))
scene("scene_degenerate.json", [dict(floor, corners=[[0, 0, 0]] * 4), light])
scene("scene_collinear_quad.json", [dict(floor, corners=[[0, 0, 0], [1, 0, 0], [2, 0, 0], [3, 0, 0]]), light])
scene("scene_reflectance.json", [dict(floor, reflectance=[1.5, 0.5, 0.5]), light])
scene("scene_negative_emission.json", [floor, dict(light, emission=[-1, 0, 0])])
scene("scene_no_light.json", [floor])
scene("scene_duplicate_names.json", [floor, dict(light, name="floor")])
scene("scene_huge.json", [dict(floor, corners=[[c * 1e300 for c in p] for p in floor["corners"]]), light])
scene("scene_tiny.json", [dict(floor, corners=[[c * 1e-300 for c in p] for p in floor["corners"]]),
                          dict(light, corners=[[c * 1e-300 for c in p] for p in light["corners"]])])
scene("scene_bad_camera.json", [floor, light], [dict(camera, fov_deg=190)])
# Solutions
write("solution_not_json.json", "{ this is not json")
write("solution_truncated.json", '{"scene": "hostile", "mesh": "grid:2", "surfaces": [{"name": "floor", "elements": [')
# Meshes
write("obj_bad_index.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 7\n")
write("obj_inf.obj", "v 0 0 0\nv inf 0 0\nv 1 1 0\nf 1 2 3\n")
write("obj_no_light.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\n")
write("gltf_bad_json.gltf", '{"asset": {"version": "2.0"}, "meshes": [')
write("glb_truncated.glb", "glTF\x02\x00\x00\x00")
# Read by assimp 5.2 as something else with exit 0 (an outside-in trial): integer positions as
# floats (a floor of 3e-89 m^2), a rotation of length 2.83 as a scale of 8; an MTL colour of two
# values refused naming the OBJ alone.
write("gltf_required_ext.gltf", '{"asset": {"version": "2.0"}, "extensionsRequired": ["KHR_mesh_quantization"]}')
write("gltf_rotation_2.gltf", '{"asset": {"version": "2.0"}, "nodes": [{"rotation": [2, 0, 0, 2]}]}')
write("obj_mtl_two_values.mtl", "newmtl m\nKd 0.2 0.4\n")
write("obj_mtl_two_values.obj", "mtllib obj_mtl_two_values.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nusemtl m\nf 1 2 3\n")
# assimp 5.2 corrupted its heap after the first (a second format line) and allocated for 10^44
# vertices on the second (an element named by digits): found by fuzz_mesh_ply, refused before it.
write("ply_two_formats.ply", "ply\nformat ascii 1.0\nelement vertex 1\nformat binary_little_endian 1.0\nproperty float x\nend_header\n0\n")
write("ply_digit_element.ply", "ply\nformat ascii 1.0\nelement 1111111111vertex 3\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n1 0 0\n0 1 0\n")
write("ply_truncated.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n")
# Pictures for compare
write("tiny_a.pfm", "PF\n2 1\n-1.0\n" + "\0" * 24)
write("tiny_b.pfm", "PF\n1 1\n-1.0\n" + "\0" * 12)
write("broken.pfm", "PF\n2 2\n-1.0\n" + "\0" * 7)
print("wrote", len(os.listdir(here)), "files")
