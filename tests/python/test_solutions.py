"""Solutions in Python: read back from their files, and each side reconstructed as `radrecon
render` reconstructs it, against independent answers (scipy's bilinear interpolation on a regular
grid, the element under a point by brute force, exactness at the samples, no influence across a
barrier that cuts a side in two) and the side's outline. Run by ctest (python.pytest)."""

import json
import warnings

import numpy as np
import pytest

import radrecon


@pytest.fixture(scope="module")
def cornell(tmp_path_factory):
    """The Cornell box at grid:8, solved and saved: (solution, its file)."""
    path = tmp_path_factory.mktemp("cornell") / "cornell.json"
    sol = radrecon.solve("cornell", "grid:8")
    sol.save(path)
    return sol, path


def side(sol, name):
    return next(s for s in sol.surfaces if s["name"] == name)


def test_a_loaded_solution_holds_what_was_saved(cornell):
    sol, path = cornell
    back = radrecon.load_solution(path)
    assert (back.scene, back.mesh) == (sol.scene, sol.mesh)
    # The file holds 9 significant digits of each number.
    for key, value in sol.stats.items():
        if isinstance(value, tuple):
            np.testing.assert_allclose(back.stats[key], value, rtol=1e-8)
        elif isinstance(value, float):
            assert back.stats[key] == pytest.approx(value, rel=1e-5)
        else:
            assert back.stats[key] == value, key
    assert back.stats["shots"] > 0
    assert [s["name"] for s in back.surfaces] == [s["name"] for s in sol.surfaces]
    for a, b in zip(sol.surfaces, back.surfaces):
        np.testing.assert_allclose(b["radiosity"], a["radiosity"], rtol=1e-8, atol=1e-300)
        np.testing.assert_array_equal(b["cell"], a["cell"])
        # st: each cell's centroid in (s, t) = (u length_u + v shear, v length_v), computed here
        # from its (u, v) corners (a triangle's lower half from its right angle at (u0, v0), its
        # upper from (u1, v1)).
        u0, v0, u1, v1 = b["cell"].T
        shape = np.array(b["shape"])
        u = np.where(shape == "box", (u0 + u1) / 2, np.where(shape == "lower", (2 * u0 + u1) / 3, (u0 + 2 * u1) / 3))
        v = np.where(shape == "box", (v0 + v1) / 2, np.where(shape == "lower", (2 * v0 + v1) / 3, (v0 + 2 * v1) / 3))
        expected = np.column_stack([u * b["length_u_m"] + v * b["shear_m"], v * b["length_v_m"]])
        np.testing.assert_allclose(b["st"], expected, rtol=1e-12, atol=1e-15)
    # A loaded file is an input: save() does not overwrite it.
    before = path.read_bytes()
    with pytest.raises(radrecon.Error, match="is the input file"):
        back.save(path)
    assert path.read_bytes() == before


def test_a_loaded_solutions_stats_are_the_files(tmp_path):
    # As the file has them: none, or some (a file without them seemed to hold 0 shots, converged).
    two_regions_solution(tmp_path / "plate.json")
    assert radrecon.load_solution(tmp_path / "plate.json").stats == {}
    doc = json.loads((tmp_path / "plate.json").read_text())
    doc["stats"] = {"shots": 408.0, "note": "rewritten by a tool"}
    (tmp_path / "with.json").write_text(json.dumps(doc))
    assert radrecon.load_solution(tmp_path / "with.json").stats == {"shots": 408.0, "note": "rewritten by a tool"}


def test_load_solution_refusals(tmp_path):
    with pytest.raises(radrecon.Error, match="missing.json"):
        radrecon.load_solution(tmp_path / "missing.json")
    bad = tmp_path / "bad.json"
    bad.write_text('{"surfaces": []}')
    with pytest.raises(radrecon.Error, match=r"bad.json.*surfaces: must be a non-empty array"):
        radrecon.load_solution(bad)
    with pytest.raises(radrecon.Error, match=r"^path: expected a file name"):
        radrecon.load_solution(3)


def test_bilinear_is_scipys_on_the_nodal_averages(cornell):
    # The back wall: a 6 x 6 grid with no barriers. Bilinear interpolates nodal values, each the
    # mean of the elements sharing the node (docs/method.md, "Nodal rule"), over the grid's
    # corners in (s, t): scipy's interpolator on those nodes is an independent answer.
    interpolate = pytest.importorskip("scipy.interpolate")
    sol, _ = cornell
    wall = side(sol, "back_wall")
    nu, nv = wall["grid"]
    values = wall["radiosity"].reshape(nv, nu, 3)
    padded = np.pad(values, ((1, 1), (1, 1), (0, 0)))
    weight = np.pad(np.ones((nv, nu)), 1)
    sums = padded[:-1, :-1] + padded[1:, :-1] + padded[:-1, 1:] + padded[1:, 1:]
    counts = weight[:-1, :-1] + weight[1:, :-1] + weight[:-1, 1:] + weight[1:, 1:]
    nodes = sums / counts[:, :, None]  # (nv + 1, nu + 1, 3)
    s_axis = np.linspace(0, wall["length_u_m"], nu + 1)
    t_axis = np.linspace(0, wall["length_v_m"], nv + 1)
    reference = interpolate.RegularGridInterpolator((t_axis, s_axis), nodes, method="linear")
    rng = np.random.default_rng(7)
    q = np.column_stack([rng.uniform(0, s_axis[-1], 400), rng.uniform(0, t_axis[-1], 400)])
    got = sol.reconstruct("back_wall", queries=q, method="bilinear")
    np.testing.assert_allclose(got, reference(q[:, ::-1]), rtol=1e-12, atol=1e-12 * values.max())


def test_constant_is_the_element_under_the_point(cornell):
    # Brute force: the element whose (s, t) rectangle holds the point, away from its edges.
    sol, _ = cornell
    wall = side(sol, "green_wall")
    cells = wall["cell"] * np.array([wall["length_u_m"], wall["length_v_m"]] * 2)
    rng = np.random.default_rng(3)
    k = rng.integers(0, len(cells), 300)
    frac = rng.uniform(0.05, 0.95, (300, 2))
    q = cells[k, :2] + frac * (cells[k, 2:] - cells[k, :2])
    got = sol.reconstruct("green_wall", queries=q, method="constant")
    np.testing.assert_array_equal(got, wall["radiosity"][k])


def inside_any(polygons, p):
    """Whether p lies inside one of the polygons (even-odd rule)."""
    for poly in polygons:
        x, y = poly[:, 0], poly[:, 1]
        xn, yn = np.roll(x, -1), np.roll(y, -1)
        crossing = ((y > p[1]) != (yn > p[1])) & (p[0] < x + (p[1] - y) * (xn - x) / (yn - y + 1e-300))
        if crossing.sum() % 2 == 1:
            return True
    return False


def test_natural_neighbour_is_exact_at_the_samples_with_barriers(cornell):
    # The floor: the blocks' feet as barriers, the floor under them excluded.
    sol, _ = cornell
    floor = side(sol, "floor")
    assert len(floor["barriers"]) > 0 and len(floor["excluded"]) > 0
    outside = np.array([not inside_any(floor["excluded"], p) for p in floor["st"]])
    got = sol.reconstruct("floor", queries=floor["st"][outside])
    np.testing.assert_allclose(got, floor["radiosity"][outside], rtol=1e-9, atol=1e-12)
    # Under a block: no value (its centroid lies in its excluded region).
    under = np.array([poly.mean(axis=0) for poly in floor["excluded"]])
    assert np.isnan(sol.reconstruct("floor", queries=under)).all()


def test_no_value_off_the_side(cornell):
    sol, _ = cornell
    tri = side(sol, "red_wall.a")
    assert tri["triangle"].all() and len(tri["outline"]) == 3
    w, h = 40, 30
    img = sol.reconstruct("red_wall.a", raster=(w, h), method="linear")
    assert img.shape == (h, w, 3)
    # The raster covers the outline's bounding box, row 0 at the lowest t; the triangle's
    # (u, v) by its corners (0, 0), (length_u, 0), (shear, length_v).
    (s0, t0), (s1, t1) = tri["outline"].min(axis=0), tri["outline"].max(axis=0)
    s = s0 + (np.arange(w) + 0.5) * (s1 - s0) / w
    t = t0 + (np.arange(h) + 0.5) * (t1 - t0) / h
    S, T = np.meshgrid(s, t)
    v = T / tri["length_v_m"]
    u = (S - v * tri["shear_m"]) / tri["length_u_m"]
    margin = 1e-6  # cells this near the hypotenuse are left out: on it within rounding
    off = (u < -margin) | (v < -margin) | (u + v > 1 + margin)
    on = (u > margin) & (v > margin) & (u + v < 1 - margin)
    assert off.any() and on.any()
    assert np.isnan(img[off]).all()
    assert np.isfinite(img[on]).all()
    # Outside the outline by rounding (1e-10 m, within 1e-9 of the parameters): on it, for every
    # method (constant, drawing the triangle's cells, gave it none).
    corner = [[tri["shear_m"], tri["length_v_m"] + 1e-10], [tri["length_u_m"] / 2, -1e-12]]
    for method in ("constant", "shepard", "natural-neighbour"):
        assert np.isfinite(sol.reconstruct("red_wall.a", queries=corner, method=method)).all(), method
    # A query beyond a quad's rectangle: no value either.
    wall = side(sol, "back_wall")
    q = np.array([[-0.01, 0.2], [wall["length_u_m"] + 0.01, 0.2], [0.2, wall["length_v_m"] * 1.01], [0.2, 0.2]])
    got = sol.reconstruct("back_wall", queries=q, method="shepard")
    assert np.isnan(got[:3]).all() and np.isfinite(got[3]).all()


def two_regions_solution(path):
    """A hand-written solution of one 1 m x 1 m side, 4 x 4 elements, cut in two by a barrier
    at s = 0.5: radiosity 1 on its left, 5 on its right."""
    elements = []
    for j in range(4):
        for i in range(4):
            left = i < 2
            elements.append({"u0": i / 4, "v0": j / 4, "u1": (i + 1) / 4, "v1": (j + 1) / 4,
                             "center": [(i + 0.5) / 4, (j + 0.5) / 4, 0], "area": 1 / 16,
                             "radiosity": [1, 1, 1] if left else [5, 5, 5]})
    path.write_text(json.dumps({"scene": "hand", "mesh": "grid:4", "surfaces": [
        {"name": "plate", "length_u_m": 1, "length_v_m": 1, "grid": [4, 4],
         "barriers": [[[0.5, 0], [0.5, 1]]], "elements": elements}]}))


@pytest.mark.parametrize("method", ["natural-neighbour", "shepard", "laplace", "sibson-c1", "constant"])
def test_no_influence_across_a_barrier(tmp_path, method):
    two_regions_solution(tmp_path / "plate.json")
    sol = radrecon.load_solution(tmp_path / "plate.json")
    rng = np.random.default_rng(11)
    left = np.column_stack([rng.uniform(0.13, 0.49, 100), rng.uniform(0.13, 0.87, 100)])
    right = left + [0.5, 0]
    np.testing.assert_allclose(sol.reconstruct("plate", queries=left, method=method), 1, rtol=1e-12)
    np.testing.assert_allclose(sol.reconstruct("plate", queries=right, method=method), 5, rtol=1e-12)
    # Without the barrier each side sees the other's samples.
    mixed = sol.reconstruct("plate", queries=left, method=method, barriers=False)
    assert (mixed > 1 + 1e-6).any() or method == "constant"


def test_a_method_that_takes_no_barriers_says_so(tmp_path):
    # As render warns: linear reconstructs across the side's barriers.
    two_regions_solution(tmp_path / "plate.json")
    sol = radrecon.load_solution(tmp_path / "plate.json")
    with pytest.warns(UserWarning, match="linear takes no barriers: side 'plate' is reconstructed across them"):
        sol.reconstruct("plate", queries=[[0.3, 0.5]], method="linear")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        sol.reconstruct("plate", queries=[[0.3, 0.5]], method="linear", barriers=False)


def test_border_samples_on_a_grid_side_with_an_excluded_region(tmp_path):
    # A 1 m side of 8 x 8 elements holding 1 + 2 s + 3 t, a block's foot excluded in its middle:
    # border samples (planes fitted to the samples each sees) carry the linear function out to the
    # side's border, where without them natural-neighbour takes the hull's nearest point. They
    # were skipped on grid sides with excluded regions (an outside-in trial).
    elements = []
    for j in range(8):
        for i in range(8):
            s, t = (i + 0.5) / 8, (j + 0.5) / 8
            b = 1 + 2 * s + 3 * t
            elements.append({"u0": i / 8, "v0": j / 8, "u1": (i + 1) / 8, "v1": (j + 1) / 8, "center": [s, t, 0],
                             "area": 1 / 64, "radiosity": [b, b, b]})
    doc = {"surfaces": [{"name": "floor", "length_u_m": 1, "length_v_m": 1, "grid": [8, 8], "elements": elements,
                         "excluded": [[[0.4, 0.4], [0.6, 0.4], [0.6, 0.6], [0.4, 0.6]]]}]}
    (tmp_path / "floor.json").write_text(json.dumps(doc))
    sol = radrecon.load_solution(tmp_path / "floor.json")
    q = np.array([[0.02, 0.5], [0.5, 0.98], [0.97, 0.03], [0.01, 0.99]])
    f = 1 + 2 * q[:, 0] + 3 * q[:, 1]
    with_border = sol.reconstruct("floor", queries=q, border_samples=True)[:, 0]
    np.testing.assert_allclose(with_border, f, rtol=1e-9)
    without = sol.reconstruct("floor", queries=q)[:, 0]
    assert np.abs(without - f).max() > 1e-2


def test_a_side_the_method_cannot_serve_is_drawn_piecewise_constant_as_render_draws_it(cornell):
    # A grid method on a triangle's side: piecewise constant, with a warning (it was refused,
    # and render drew it so; an outside-in trial).
    sol, _ = cornell
    q = side(sol, "red_wall.a")["st"][:5]
    with pytest.warns(UserWarning, match=r"bilinear cannot reconstruct side 'red_wall.a' \(bilinear needs grid data"):
        got = sol.reconstruct("red_wall.a", queries=q, method="bilinear")
    np.testing.assert_array_equal(got, sol.reconstruct("red_wall.a", queries=q, method="constant", barriers=False))


def test_solve_and_load_refuse_wrong_types_naming_the_argument(tmp_path):
    # pybind's own TypeError named no argument; a NUL in a file name cut it short in silence.
    for kwargs, field in [({"residual": "1e-3"}, "residual"), ({"patches": 2.5}, "patches"), ({"patches": True}, "patches"),
                          ({"mesh": 16}, "mesh"), ({"leaves_on": 3, "mesh": "quadtree:10"}, "leaves_on")]:
        with pytest.raises(radrecon.Error, match="^" + field + ": "):
            radrecon.solve("cornell", **({"mesh": "grid:2"} | kwargs))
    with pytest.raises(radrecon.Error, match=r"^path: the file name .* holds a NUL character"):
        radrecon.load_solution(str(tmp_path / "a.json") + "\0x")
    assert radrecon.solve("cornell", "grid:2", residual=np.float64(1e-3), patches=np.int64(2)).stats["patches"] > 0


def test_reconstruct_refusals(cornell):
    sol, _ = cornell
    with pytest.raises(radrecon.Error, match=r"^side: the solution has no side 'flor'; its sides: floor, light"):
        sol.reconstruct("flor", raster=(4, 4))
    with pytest.raises(radrecon.Error, match=r"^queries/raster: give the query points"):
        sol.reconstruct("floor")
    with pytest.raises(radrecon.Error, match=r"^queries/raster: give either"):
        sol.reconstruct("floor", queries=[[0.1, 0.1]], raster=(4, 4))
    for side in (None, 0, b"floor"):
        with pytest.raises(radrecon.Error, match=r"^side: a side's name \(str"):
            sol.reconstruct(side, raster=(4, 4))
    with pytest.raises(radrecon.Error, match=r"^method: "):
        sol.reconstruct("floor", raster=(4, 4), method="kriging")
    with pytest.raises(radrecon.Error, match=r"^border_samples: "):
        sol.reconstruct("floor", raster=(4, 4), method="constant", border_samples=True)
    with pytest.raises(radrecon.Error, match=r"^params bogus: unknown parameter"):
        sol.reconstruct("floor", raster=(4, 4), method="shepard", bogus=1)
    with pytest.raises(radrecon.Error, match=r"^raster: "):
        sol.reconstruct("floor", raster=(0, 4))
    with pytest.raises(radrecon.Error, match=r"^queries"):
        sol.reconstruct("floor", queries=[[0.1, np.nan]])
    with pytest.raises(radrecon.Error, match=r"^barriers: "):
        sol.reconstruct("floor", raster=(4, 4), barriers=1)
