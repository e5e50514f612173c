#!/usr/bin/env python3
"""Writes the benchmark scenes of docs/benchmarks.md ("Visibility at scale"):

  cornell_quads.json  a quad-only approximation of the Cornell box (room 0.556 x 0.559 x 0.549 m,
                      the light 0.13 x 0.105 m just under the ceiling, the short and the tall block
                      rotated as in the published data, without their bottoms)
  boxes_N.json        a room 10 x 10 x 3 m with an N x N grid of boxes (5 faces each) on the
                      floor and a light under the ceiling: 6 + 5 N^2 quads

Usage: make_scenes.py OUTDIR [N ...]   (default N: 20, i.e. 2,006 quads)
"""
import json, math, sys


def quad(name, c, rho, emission=None, max_div=None):
    s = {"name": name, "corners": [list(map(float, p)) for p in c], "reflectance": rho}
    if emission is not None:
        s["emission"] = emission
    if max_div is not None:
        s["mesh"] = {"max_divisions": max_div}
    return s


def box(prefix, cx, cy, hx, hy, h, angle, rho):
    """Four sides and the top of a box standing on z = 0, rotated by `angle` about z; faces out."""
    ca, sa = math.cos(angle), math.sin(angle)
    def p(x, y, z):
        return [cx + ca * x - sa * y, cy + sa * x + ca * y, z]
    b = [p(-hx, -hy, 0), p(hx, -hy, 0), p(hx, hy, 0), p(-hx, hy, 0)]
    t = [p(-hx, -hy, h), p(hx, -hy, h), p(hx, hy, h), p(-hx, hy, h)]
    out = [quad(prefix + "top", [t[0], t[1], t[2], t[3]], rho)]
    for k in range(4):
        a, c = k, (k + 1) % 4
        out.append(quad(prefix + "side%d" % k, [b[a], b[c], t[c], t[a]], rho))
    return out


def room(w, d, h, rho):
    """Floor, ceiling and four walls of [0,w]x[0,d]x[0,h], facing in."""
    return [
        quad("floor", [[0, 0, 0], [w, 0, 0], [w, d, 0], [0, d, 0]], rho),
        quad("ceiling", [[0, 0, h], [0, d, h], [w, d, h], [w, 0, h]], rho),
        quad("back", [[0, d, 0], [w, d, 0], [w, d, h], [0, d, h]], rho),
        quad("front", [[0, 0, 0], [0, 0, h], [w, 0, h], [w, 0, 0]], rho),
        quad("left", [[0, 0, 0], [0, d, 0], [0, d, h], [0, 0, h]], rho),
        quad("right", [[w, 0, 0], [w, 0, h], [w, d, h], [w, d, 0]], rho),
    ]


def cornell():
    w, d, h = 0.556, 0.559, 0.549
    s = room(w, d, h, 0.7)
    s = [x for x in s if x["name"] != "front"]  # open towards the camera
    s[3]["reflectance"] = [0.63, 0.06, 0.04]  # left: red
    s[4]["reflectance"] = [0.14, 0.45, 0.09]  # right: green
    z = h - 0.001
    s.append(quad("light", [[0.213, 0.227, z], [0.213, 0.332, z], [0.343, 0.332, z], [0.343, 0.227, z]],
                  0.78, emission=[40, 40, 40]))
    s += box("short_", 0.186, 0.169, 0.0825, 0.0825, 0.165, math.radians(-17), 0.7)
    s += box("tall_", 0.368, 0.351, 0.0825, 0.0825, 0.330, math.radians(17), 0.7)
    return {"name": "cornell_quads", "surfaces": s,
            "cameras": [{"name": "front", "eye": [0.278, -0.8, 0.273], "target": [0.278, 0.28, 0.273],
                         "up": [0, 0, 1], "fov_deg": 40}]}


def boxes(n):
    w, d, h = 10.0, 10.0, 3.0
    s = room(w, d, h, 0.5)
    s.append(quad("light", [[4, 4, h - 0.01], [4, 6, h - 0.01], [6, 6, h - 0.01], [6, 4, h - 0.01]],
                  0.0, emission=[40, 40, 40]))
    pitch = 9.0 / n
    for i in range(n):
        for j in range(n):
            cx, cy = 0.5 + (i + 0.5) * pitch, 0.5 + (j + 0.5) * pitch
            hgt = 0.3 + 1.2 * (((i * 7 + j * 13) % 10) / 10.0)
            s += box("b%d_%d_" % (i, j), cx, cy, 0.3 * pitch, 0.3 * pitch, hgt, 0.3 * ((i + j) % 3), 0.5)
    return {"name": "boxes_%d" % n, "surfaces": s}


if __name__ == "__main__":
    out = sys.argv[1]
    ns = [int(a) for a in sys.argv[2:]] or [20]
    with open(out + "/cornell_quads.json", "w") as f:
        json.dump(cornell(), f, indent=1)
    for n in ns:
        with open(out + "/boxes_%d.json" % n, "w") as f:
            json.dump(boxes(n), f)
