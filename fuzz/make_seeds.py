#!/usr/bin/env python3
"""Writes the seed corpora of the fuzz harnesses into fuzz/corpus/<harness>/ (docs/hostile.md, "Fuzzing").

Small valid inputs of every construct each reader knows, so that the fuzzer starts from deep
inside the parsers; the hostile corpus (tests/hostile/inputs) adds the refused ones when
fuzz/run.sh starts. Run it again after changing a seed; the files are committed.
"""
import base64
import json
import pathlib
import struct
import zlib

ROOT = pathlib.Path(__file__).resolve().parent / "corpus"


def put(harness, name, data):
    folder = ROOT / harness
    folder.mkdir(parents=True, exist_ok=True)
    (folder / name).write_bytes(data if isinstance(data, bytes) else data.encode())


def compact(doc):
    return json.dumps(doc, separators=(",", ":"))


# --- scene JSON (docs/formats.md) ---------------------------------------------------------------
floor = {"name": "floor", "corners": [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], "reflectance": 0.5}
light = {"name": "light", "corners": [[0.4, 0.4, 1], [0.4, 0.6, 1], [0.6, 0.6, 1], [0.6, 0.4, 1]],
         "reflectance": [0, 0, 0], "emission": [10, 10, 10], "two_sided": True}
wall = {"name": "wall", "corners": [[0.5, 0, 0], [0.5, 1, 0], [0.5, 1, 0.5]], "reflectance": [0.2, 0.4, 0.6],
        "mesh": {"max_divisions": 4}}
camera = {"name": "view", "eye": [0.5, -1, 0.8], "target": [0.5, 0.5, 0], "up": [0, 0, 1], "fov_deg": 50}
put("scene_json", "quads.json", compact({"name": "s", "surfaces": [floor, light]}))
put("scene_json", "triangle_camera.json", compact({"name": "s", "surfaces": [floor, light, wall], "cameras": [camera]}))
put("scene_json", "mesh_entry.json", compact({"name": "m", "surfaces": [light], "meshes": [
    {"file": "missing.obj", "scale": 2, "translate": [0, 0, 1], "rotate_x_deg": 90, "reflectance": 0.3,
     "emission": [1, 1, 1], "two_sided": False, "merge_triangles": True, "mesh": {"max_divisions": 2}}]}))

# --- solution JSON: written by radrecon itself, not here (compacted with json.dumps):
#   radrecon solve --scene fuzz/corpus/scene_json/triangle_camera.json --mesh grid:2 --out grid2.json
#   radrecon solve --scene fuzz/corpus/scene_json/quads.json --mesh quadtree:4 --out quadtree4.json

# --- samples and queries CSV (io/samples_csv.h) ------------------------------------------------
put("samples_csv", "header.csv", "x,y,v\n0,0,1\n1,0,2\n0,1,3\n1,1,4\n0.5,0.5,2.5\n")
put("samples_csv", "xyz.csv", "# nnbathy\n0 0 1\n1 0 2\n0 1 3\n1 1 4\n")
put("samples_csv", "channels.csv", "\ufeffX,Y,r,g,b\n0,0,1,2,3\n2,0,1,2,3\n0,2,1,2,3\n2,2,3,2,1\n")
put("samples_csv", "quoted.csv", "\"x\",\"y\",\"value\"\r\n5e5,5.4e6,1\r\n500001,5400000,2\r\n500000,5400001,3\r\n")
put("query_csv", "queries.csv", "x,y\n0.25,0.25\n0.5,0.75\n")
put("query_csv", "extra.csv", "id,x,y,note\n1,0,0,a\n2,1e-300,1e300,b\n")

# --- GeoJSON barriers (io/geojson.h) -----------------------------------------------------------
put("geojson", "features.geojson", compact({"type": "FeatureCollection", "features": [
    {"type": "Feature", "properties": {}, "geometry": {"type": "LineString", "coordinates": [[0, 0], [1, 1]]}},
    {"type": "Feature", "geometry": None},
    {"type": "Feature", "geometry": {"type": "Polygon", "coordinates": [[[2, 2], [3, 2], [3, 3], [2, 2]]]}}]}))
put("geojson", "collection.geojson", compact({"type": "GeometryCollection", "geometries": [
    {"type": "MultiLineString", "coordinates": [[[0, 0], [0, 1, 5]], [[1, 0], [1, 1]]]},
    {"type": "MultiPolygon", "coordinates": [[[[0, 0], [1, 0], [1, 1], [0, 0]]]]}]}))

# --- meshes (io/mesh_import.h) -----------------------------------------------------------------
put("mesh_obj", "quad_light.obj", "mtllib none.mtl\no floor\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
    "v 0.4 0.4 1\nv 0.6 0.4 1\nv 0.6 0.6 1\nvn 0 0 1\nvt 0 0\nf 1/1/1 2/1/1 3/1/1 4/1/1\ng light\nf 7 6 5\nf -1 -2 -3\n")
put("mesh_obj", "pentagon.obj", "v 0 0 0\nv 2 0 0\nv 3 1 0\nv 1 2 0\nv -1 1 0\nf 1 2 3 4 5\n")

positions = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
indices = struct.pack("<3H", 0, 1, 2) + b"\0\0"
binary = positions + indices


def gltf_doc(buffer):
    return {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
            "nodes": [{"mesh": 0, "translation": [0, 0, 1]}],
            "meshes": [{"name": "tri", "primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]}],
            "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1]},
                           "emissiveFactor": [1, 1, 1],
                           "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 5}}}],
            "extensionsUsed": ["KHR_materials_emissive_strength"],
            "buffers": [buffer],
            "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
                            {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
            "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                           "min": [0, 0, 0], "max": [1, 1, 0]},
                          {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}]}


uri = "data:application/octet-stream;base64," + base64.b64encode(binary).decode()
put("mesh_gltf", "triangle.gltf", compact(gltf_doc({"byteLength": len(binary), "uri": uri})))

json_chunk = compact(gltf_doc({"byteLength": len(binary)})).encode()
json_chunk += b" " * (-len(json_chunk) % 4)
glb = struct.pack("<II", len(json_chunk), 0x4E4F534A) + json_chunk + struct.pack("<II", len(binary), 0x004E4942) + binary
put("mesh_glb", "triangle.glb", struct.pack("<III", 0x46546C67, 2, 12 + len(glb)) + glb)

ply_header = ("ply\nformat {}\ncomment seed\nelement vertex 4\nproperty float x\nproperty float y\n"
              "property float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
              "element face 1\nproperty list uchar int vertex_indices\nend_header\n")
put("mesh_ply", "ascii.ply", ply_header.format("ascii 1.0") +
    "0 0 0 255 0 0\n1 0 0 0 255 0\n1 1 0 0 0 255\n0 1 0 9 9 9\n4 0 1 2 3\n")
vertices = b"".join(struct.pack("<3f3B", *v) for v in [(0, 0, 0, 255, 0, 0), (1, 0, 0, 0, 255, 0),
                                                       (1, 1, 0, 0, 0, 255), (0, 1, 0, 9, 9, 9)])
put("mesh_ply", "binary.ply", ply_header.format("binary_little_endian 1.0").encode() + vertices +
    struct.pack("<B4i", 4, 0, 1, 2, 3))

# --- pictures (io/image_read.h), as `radrecon compare` reads them -------------------------------
rgb = [0.0, 0.5, 1.0, 2.0, -1.0, 1e-30, 3.5, 0.25, 7.0, 1e30, 0.125, 4.0]  # 2 x 2 pixels, 3 channels
put("picture_pfm", "rgb_little.pfm", b"PF\n2 2\n-1.0\n" + struct.pack("<12f", *rgb))
put("picture_pfm", "grey_big.pfm", b"Pf\n3 1\n1.0\n" + struct.pack(">3f", 0.0, 0.5, 1.0))
put("picture_pfm", "spaces.pfm", b"PF 1\t1 -2.5\n" + struct.pack("<3f", 1, 2, 3))


def png(width, height, depth, colour, rows, palette=None, transparency=None):
    """A PNG of the given rows (bytes each, filter byte included) in one IDAT chunk."""
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    out = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, depth, colour, 0, 0, 0))
    if palette is not None:
        out += chunk(b"PLTE", palette)
    if transparency is not None:
        out += chunk(b"tRNS", transparency)
    return out + chunk(b"IDAT", zlib.compress(b"".join(rows))) + chunk(b"IEND", b"")


put("picture_png", "grey8.png", png(2, 2, 8, 0, [b"\0\x00\x80", b"\1\xff\x01"]))
put("picture_png", "rgb16.png", png(1, 2, 16, 2, [b"\0" + struct.pack(">3H", 0, 32768, 65535),
                                                  b"\2" + struct.pack(">3H", 1, 2, 3)]))
put("picture_png", "rgba8.png", png(2, 1, 8, 6, [b"\4" + bytes([10, 20, 30, 255, 40, 50, 60, 0])]))
put("picture_png", "grey_alpha.png", png(1, 1, 8, 4, [b"\0\x40\x80"]))
put("picture_png", "palette2.png", png(4, 1, 2, 3, [b"\0\x1b"], palette=bytes([0, 0, 0, 255, 0, 0, 0, 255, 0, 0, 0, 255]),
                                       transparency=b"\x80"))
put("picture_png", "grey1.png", png(8, 2, 1, 0, [b"\0\xa5", b"\3\x0f"]))
