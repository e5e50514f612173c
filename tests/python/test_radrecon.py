"""The Python module against independent answers: scipy where it has the same method, defining
properties (exact at the samples, linear functions reproduced, no influence across a barrier),
and the command line for the same input (same values, same messages). Run by ctest
(python.pytest) with PYTHONPATH=build/python and RADRECON_BIN=build/radrecon."""

import json
import os
import pathlib
import subprocess
import threading
import warnings

import numpy as np
import pytest

import radrecon



def scipy_interpolate():
    """scipy.interpolate, or a skip of the test that compares with it."""
    return pytest.importorskip("scipy.interpolate")

RADRECON_BIN = os.environ.get("RADRECON_BIN", "radrecon")


def samples(n=300, seed=1, f=lambda x, y: np.sin(6 * x) * np.cos(4 * y)):
    rng = np.random.default_rng(seed)
    p = rng.random((n, 2))
    return p, f(p[:, 0], p[:, 1])


def queries(m=500, seed=2, lo=0.0, hi=1.0):
    return np.random.default_rng(seed).uniform(lo, hi, (m, 2))


def cli_error(tmp_path, points, values, *args):
    """The reason radrecon interpolate gives for refusing the same input (after 'where: ')."""
    csv = tmp_path / "s.csv"
    np.savetxt(csv, np.column_stack([points, values]), delimiter=",", header="x,y,v", comments="", fmt="%.17g")
    r = subprocess.run([RADRECON_BIN, "interpolate", "--samples", str(csv), "--queries", str(csv),
                        "--out", str(tmp_path / "o.csv"), "--quiet", *args], capture_output=True, text=True)
    assert r.returncode == 2, r.stderr
    assert not (tmp_path / "o.csv").exists()
    line = r.stderr.strip().splitlines()[-1]
    return line.split(": ", 3)[-1]  # "radrecon: error: WHERE: REASON"


def test_linear_matches_scipy_griddata():
    p, v = samples()
    q = queries(lo=-0.1, hi=1.1)
    ours = radrecon.interpolate(p, v, queries=q, method="linear", outside="none")
    theirs = scipy_interpolate().griddata(p, v, q, method="linear")
    assert np.array_equal(np.isnan(ours), np.isnan(theirs))
    inside = ~np.isnan(theirs)
    assert inside.sum() > 300
    assert np.max(np.abs(ours[inside] - theirs[inside])) < 1e-12


def test_clough_tocher_matches_scipy():
    p, v = samples()
    q = queries()
    ours = radrecon.interpolate(p, v, queries=q, method="clough-tocher", outside="none")
    theirs = scipy_interpolate().CloughTocher2DInterpolator(p, v, tol=1e-12)(q)
    inside = ~np.isnan(theirs)
    assert np.array_equal(np.isnan(ours), ~inside)
    assert np.max(np.abs(ours[inside] - theirs[inside])) < 1e-9


def test_thin_plate_matches_scipy_rbf():
    p, v = samples(200)
    q = queries()
    ours = radrecon.interpolate(p, v, queries=q, method="thin-plate")
    theirs = scipy_interpolate().RBFInterpolator(p, v, kernel="thin_plate_spline")(q)
    assert np.max(np.abs(ours - theirs)) < 1e-9


def test_constant_is_the_nearest_sample_as_scipy():
    p, v = samples()
    q = queries()
    ours = radrecon.interpolate(p, v, queries=q, method="constant")
    theirs = scipy_interpolate().NearestNDInterpolator(p, v)(q)
    assert np.array_equal(ours, theirs)


@pytest.mark.parametrize("method", ["natural-neighbour", "laplace", "sibson-c1", "linear", "clough-tocher",
                                    "thin-plate"])
def test_linear_functions_reproduced_and_exact_at_samples(method):
    p, _ = samples()
    v = 3.0 + 2.0 * p[:, 0] - 5.0 * p[:, 1]
    q = queries(lo=0.2, hi=0.8)
    got = radrecon.interpolate(p, v, queries=q, method=method)
    assert np.max(np.abs(got - (3.0 + 2.0 * q[:, 0] - 5.0 * q[:, 1]))) < 1e-10
    assert np.max(np.abs(radrecon.interpolate(p, v, queries=p, method=method) - v)) < 1e-10


def test_channels_and_raster_layout():
    p, v = samples()
    three = np.column_stack([v, 2 * v, -v])
    got = radrecon.interpolate(p, three, raster=(40, 30), domain=(0, 0, 1, 1), method="natural-neighbour")
    assert got.shape == (30, 40, 3)
    # Row 0 is the y0 row: the cells' centres, as explicit queries.
    xs = (np.arange(40) + 0.5) / 40
    ys = (np.arange(30) + 0.5) / 30
    grid = np.array([(x, y) for y in ys for x in xs])
    one = radrecon.interpolate(p, v, queries=grid, method="natural-neighbour")
    assert np.max(np.abs(got[:, :, 0].ravel() - one)) < 1e-12  # the centres' rounding may differ
    assert np.array_equal(got[:, :, 1], 2 * got[:, :, 0])


def test_same_values_as_the_command_line(tmp_path):
    p, v = samples()
    q = queries()
    np.savetxt(tmp_path / "s.csv", np.column_stack([p, v]), delimiter=",", header="x,y,v", comments="", fmt="%.17g")
    np.savetxt(tmp_path / "q.csv", q, delimiter=",", header="x,y", comments="", fmt="%.17g")
    subprocess.run([RADRECON_BIN, "interpolate", "--samples", str(tmp_path / "s.csv"), "--queries",
                    str(tmp_path / "q.csv"), "--method", "shepard", "--param", "k=12", "--out",
                    str(tmp_path / "o.csv"), "--quiet"], check=True)
    cli = np.loadtxt(tmp_path / "o.csv", delimiter=",", skiprows=1)[:, 2]
    ours = radrecon.interpolate(p, v, queries=q, method="shepard", k=12)
    assert np.max(np.abs(ours - cli)) <= 1e-15 * np.max(np.abs(cli))  # the CSV keeps 17 digits


def test_border_samples_as_the_command_line_reproduce_a_plane_to_the_domains_edge(tmp_path):
    # Samples inside [0.2, 0.8]^2 of a plane: without border samples natural-neighbour takes the
    # nearest hull point's value beyond the hull (1.7 off at the corners); with them, planes
    # fitted at the border of the domain, the plane everywhere. The command line's
    # --border-samples gives the same values (Python had no such keyword; an outside-in trial).
    rng = np.random.default_rng(3)
    p = rng.uniform(0.2, 0.8, (60, 2))
    v = 3 + 2 * p[:, 0] - 5 * p[:, 1]
    ours = radrecon.interpolate(p, v, raster=(20, 20), domain=(0, 0, 1, 1), method="natural-neighbour",
                                border_samples=True)
    x, y = np.meshgrid((np.arange(20) + 0.5) / 20, (np.arange(20) + 0.5) / 20)
    assert np.max(np.abs(ours - (3 + 2 * x - 5 * y))) < 1e-12
    plain = radrecon.interpolate(p, v, raster=(20, 20), domain=(0, 0, 1, 1), method="natural-neighbour")
    assert np.max(np.abs(plain - (3 + 2 * x - 5 * y))) > 0.5
    np.savetxt(tmp_path / "s.csv", np.column_stack([p, v]), delimiter=",", header="x,y,v", comments="", fmt="%.17g")
    subprocess.run([RADRECON_BIN, "interpolate", "--samples", str(tmp_path / "s.csv"), "--raster", "20x20", "--domain",
                    "0,0,1,1", "--method", "natural-neighbour", "--border-samples", "--out", str(tmp_path / "o.csv"),
                    "--quiet"], check=True)
    cli = np.loadtxt(tmp_path / "o.csv", delimiter=",", skiprows=1)[:, 2].reshape(20, 20)
    assert np.array_equal(cli, ours)
    # With queries, on the domain given (as --domain with --queries): the plane there too (the
    # raster's own evaluation sums in another order: equal to rounding).
    q = np.column_stack([x.ravel(), y.ravel()])
    at_queries = radrecon.interpolate(p, v, queries=q, domain=(0, 0, 1, 1), method="natural-neighbour", border_samples=True)
    assert np.max(np.abs(at_queries - (3 + 2 * q[:, 0] - 5 * q[:, 1]))) < 1e-12
    with pytest.raises(radrecon.Error, match="^domain: domain goes with raster"):
        radrecon.interpolate(p, v, queries=q, domain=(0, 0, 1, 1))
    with pytest.raises(radrecon.Error, match="^border_samples: applies to the scattered methods that interpolate"):
        radrecon.interpolate(p, v, queries=p, method="constant", border_samples=True)


def test_no_influence_across_a_barrier():
    rng = np.random.default_rng(5)
    p = rng.random((400, 2))
    v = np.where(p[:, 0] < 0.5, 0.0, 1.0)
    wall = [np.array([[0.5, -1.0], [0.5, 2.0]])]
    q = np.column_stack([np.full(50, 0.49), np.linspace(0.05, 0.95, 50)])
    for method in ["shepard", "natural-neighbour", "multiquadric"]:
        got = radrecon.interpolate(p, v, queries=q, method=method, barriers=wall)
        assert np.max(np.abs(got)) < 1e-12, method


def test_a_count_that_includes_border_samples_says_so():
    # 7,990 samples are within one global system's 8,000; with the border samples added they are
    # not, and the refusal said "8,2xx samples are too many" of samples the user never passed.
    p, v = samples(7990, seed=5)  # refused before any system is built
    with pytest.raises(radrecon.Error, match=r"too many .* border samples added\)"):
        radrecon.interpolate(p, v, queries=p[:3], method="thin-plate", border_samples=True)


def test_barrier_samples_keyword():
    # barrier_samples=False is --param barrier-samples=off: without the samples along the wall a
    # query beside it takes its natural neighbours from farther away, so the values differ.
    rng = np.random.default_rng(6)
    p = rng.random((200, 2))
    v = p[:, 0] + p[:, 1] ** 2
    wall = [np.array([[0.5, 0.2], [0.5, 0.8]])]
    q = np.column_stack([np.full(20, 0.49), np.linspace(0.25, 0.75, 20)])
    on = radrecon.interpolate(p, v, queries=q, barriers=wall)
    off = radrecon.interpolate(p, v, queries=q, barriers=wall, barrier_samples=False)
    assert np.all(np.isfinite(on)) and np.all(np.isfinite(off))
    assert np.max(np.abs(on - off)) > 1e-6
    with pytest.raises(radrecon.Error, match="barrier-samples"):
        radrecon.interpolate(p, v, queries=q, barriers=wall, barrier_samples="maybe")
    # A NumPy bool as a Python one (it was refused: "got 'False'").
    assert np.array_equal(radrecon.interpolate(p, v, queries=q, barriers=wall, barrier_samples=np.bool_(False)), off)
    # Refusals name the argument at fault, counting from 0 as Python does.
    with pytest.raises(radrecon.Error, match=r"^barriers: linear does not take barriers"):
        radrecon.interpolate(p, v, queries=q, barriers=wall, method="linear")
    with pytest.raises(radrecon.Error, match=r"^method: gouraud reconstructs cells"):
        radrecon.interpolate(p, v, queries=q, method="gouraud")
    with pytest.raises(radrecon.Error, match=r"^barriers\[1\]: a line needs 2 points, got 1"):
        radrecon.interpolate(p, v, queries=q, barriers=[wall[0], np.array([[0.1, 0.1]])])
    with pytest.raises(radrecon.Error, match=r"^barriers\[0\]\[2\]: repeats the point before it"):
        radrecon.interpolate(p, v, queries=q, barriers=[np.array([[0, 0], [1, 1], [1, 1]])])


def test_refusals_carry_the_command_lines_messages(tmp_path):
    p, v = samples(50)
    with pytest.raises(radrecon.Error) as e:
        radrecon.interpolate(p, v, queries=p, method="shepard", mu=-1)
    assert str(e.value).endswith(cli_error(tmp_path, p, v, "--method", "shepard", "--param", "mu=-1"))
    line = np.column_stack([np.linspace(0, 1, 20), np.linspace(0, 2, 20)])
    with pytest.raises(radrecon.Error) as e:
        radrecon.interpolate(line, line[:, 0], queries=line, method="natural-neighbour")
    assert str(e.value).endswith(cli_error(tmp_path, line, line[:, 0], "--method", "natural-neighbour"))
    # A bool given to a number is refused as Python wrote it (it read 'on').
    with pytest.raises(radrecon.Error, match="params mu: expected a finite number, got 'True'"):
        radrecon.interpolate(p, v, queries=p, method="shepard", mu=True)
    with pytest.raises(radrecon.Error, match="unknown method 'kriging'"):
        radrecon.interpolate(p, v, queries=p, method="kriging")
    assert issubclass(radrecon.Error, ValueError)


def test_raster_and_domain_of_the_wrong_shape_or_kind_are_named(tmp_path):
    # pybind's own TypeError ("incompatible function arguments") before: found by an outside-in
    # trial. Arrays and lists serve as well as tuples; a path-like object names a barrier file.
    rng = np.random.default_rng(7)
    points = rng.uniform(0, 1, (40, 2))
    values = 3 + 2 * points[:, 0] - 5 * points[:, 1]
    for raster, domain, field in [((2.5, 3), (0, 0, 1, 1), "raster"), ((4, 3, 1), (0, 0, 1, 1), "raster"),
                                  ("4x3", (0, 0, 1, 1), "raster"), ((True, 3), (0, 0, 1, 1), "raster"),
                                  (5, (0, 0, 1, 1), "raster"), ((4, 3), (0, 0, 1, 1, 1), "domain"),
                                  ((4, 3), (0, 0, "1", 1), "domain")]:
        with pytest.raises(radrecon.Error, match="^" + field + ": "):
            radrecon.interpolate(points, values, raster=raster, domain=domain, method="linear")
    grid = radrecon.interpolate(points, values, raster=np.array([4, 3]), domain=[0.2, 0.2, 0.8, 0.8], method="linear")
    x = 0.2 + 0.15 * (np.arange(4) + 0.5)
    y = 0.2 + 0.2 * (np.arange(3) + 0.5)
    assert np.allclose(grid, 3 + 2 * x[None, :] - 5 * y[:, None], atol=1e-12)
    fault = tmp_path / "fault.geojson"
    fault.write_text('{"type": "LineString", "coordinates": [[0.5, -1], [0.5, 2]]}')
    as_path = radrecon.interpolate(points, values, queries=np.array([[0.2, 0.5]]), barriers=fault)
    as_text = radrecon.interpolate(points, values, queries=np.array([[0.2, 0.5]]), barriers=str(fault))
    assert as_path[0] == as_text[0]


def test_flags_and_an_empty_barrier_file_name_are_named():
    # pybind's TypeError printed the arrays whole and named no argument for border_samples="yes";
    # barriers="" said "no such file" without naming the argument (an outside-in trial).
    rng = np.random.default_rng(8)
    points = rng.uniform(0, 1, (30, 2))
    values = points[:, 0] + points[:, 1]
    for kwargs, field in [({"border_samples": "yes"}, "border_samples"), ({"border_samples": 1}, "border_samples"),
                          ({"barriers": ""}, "barriers"), ({"barriers": pathlib.Path("")}, "barriers")]:
        with pytest.raises(radrecon.Error, match="^" + field + ": ") as caught:
            radrecon.interpolate(points, values, queries=points[:3], method="natural-neighbour", **kwargs)
        assert len(str(caught.value)) < 200
    with pytest.raises(radrecon.Error, match="^shadow_barriers: True or False"):
        radrecon.solve("paper", "grid:4", shadow_barriers="yes")
    with pytest.raises(radrecon.Error, match="^clusters: True or False"):
        radrecon.solve("paper", "grid:4", clusters=1)
    # numpy's bool is a flag as Python's is: the same values.
    q = rng.uniform(0.1, 0.9, (5, 2))
    a = radrecon.interpolate(points, values, queries=q, domain=(0, 0, 1, 1), border_samples=np.bool_(True))
    b = radrecon.interpolate(points, values, queries=q, domain=(0, 0, 1, 1), border_samples=True)
    assert np.array_equal(a, b)


def test_duplicates_are_merged_with_a_warning():
    p = np.array([[0, 0], [1, 0], [0, 1], [1, 1], [1, 1]], dtype=float)
    v = np.array([0, 1, 1, 2, 4], dtype=float)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        got = radrecon.interpolate(p, v, queries=np.array([[1.0, 1.0]]), method="linear")
    assert any("merged" in str(w.message) for w in caught)
    assert got[0] == 3.0


def test_a_poorly_conditioned_system_is_a_python_warning():
    # It went to stderr past Python's warnings (an outside-in trial). A multiquadric of a large
    # radius over close samples: the reciprocal condition falls below 1e-12.
    rng = np.random.default_rng(9)
    points = rng.uniform(0, 1, (60, 2))
    values = np.sin(points[:, 0])
    with pytest.warns(UserWarning, match="poorly conditioned"):
        radrecon.interpolate(points, values, queries=np.array([[0.5, 0.5]]), method="multiquadric", r=50)


def test_a_models_warnings_are_python_warnings(tmp_path):
    # A model's clamped colour went to stderr past Python's warnings (the review). An OBJ of a lamp
    # over a floor of Kd 1 (clamped to 0.999).
    (tmp_path / "m.mtl").write_text("newmtl white\nKd 1 1 1\nnewmtl lamp\nKd 0\nKe 10\n")
    (tmp_path / "m.obj").write_text("mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                                    "v 0 0 1\nv 0 1 1\nv 1 1 1\nv 1 0 1\n"
                                    "usemtl white\nf 1 2 3 4\nusemtl lamp\nf 5 6 7 8\n")
    with pytest.warns(UserWarning, match="clamped"):
        radrecon.solve(str(tmp_path / "m.obj"), "grid:2")


def test_the_gil_is_released_during_the_work():
    # While one thread interpolates, another must be able to run Python code: a call that held
    # the GIL would leave the counter at (almost) nothing until it returned.
    p, v = samples(20000, seed=3)
    q = queries(200000, seed=4)
    started, done = threading.Event(), threading.Event()

    def work():
        started.set()
        radrecon.interpolate(p, v, queries=q, method="shepard")  # global: all 20,000 samples per query
        done.set()

    t = threading.Thread(target=work)
    t.start()
    started.wait()
    count = 0
    while not done.is_set():
        count += 1
    t.join()
    assert count > 10000


def test_solve_gives_the_command_lines_solution(tmp_path):
    sol = radrecon.solve("paper", "grid:8")
    out = tmp_path / "s.json"
    subprocess.run([RADRECON_BIN, "solve", "--scene", "paper", "--mesh", "grid:8", "--out", str(out), "--quiet"],
                   check=True)
    cli = json.load(open(out))
    assert sol.stats["method"] == "progressive" and sol.stats["converged"]
    assert [s["name"] for s in sol.surfaces] == [s["name"] for s in cli["surfaces"]]
    for ours, theirs in zip(sol.surfaces, cli["surfaces"]):
        b = np.array([e["radiosity"] for e in theirs["elements"]])
        assert ours["radiosity"].shape == b.shape
        assert np.max(np.abs(ours["radiosity"] - b)) <= 1e-8 * max(1.0, np.max(np.abs(b)))  # the file's 9 digits
    # The elements tile each side: their areas add up to its area (ground: 4 m x 4 m in the paper).
    ground = next(s for s in sol.surfaces if s["name"] == "ground")
    assert abs(ground["area"].sum() - 16.0) < 1e-12
    sol.save(str(tmp_path / "again.json"))
    assert json.load(open(tmp_path / "again.json"))["mesh"] == "grid:8"


def test_solve_refusals():
    with pytest.raises(radrecon.Error, match="mesh"):
        radrecon.solve("paper", "grid:banana")
    with pytest.raises(radrecon.Error, match="nothing.json"):
        radrecon.solve("nothing.json")
    # Out of range or NaN: refused by name, as the command line refuses them (no abort).
    for keywords, name in [({"residual": -1.0}, "residual"), ({"residual": 2.0}, "residual"),
                           ({"residual": float("nan")}, "residual"), ({"far_field_error": 0.6}, "far_field_error"),
                           ({"far_field_error": 1e-7}, "far_field_error"), ({"patches": 10**6}, "patches"),
                           ({"patches": 0}, "patches: must be a count from 1")]:
        with pytest.raises(radrecon.Error, match=name):
            radrecon.solve("paper", "grid:4", **keywords)
    # Options the mesh does not use are refused, as the command line refuses them, not ignored.
    for mesh, keywords, name in [("quadtree:49", {"far_field_error": 0.3}, "far_field_error"),
                                 ("quadtree:49", {"patches": 7}, "patches"),
                                 ("quadtree-eps:0.01", {"residual": 1e-3}, "residual"),
                                 ("grid:4", {"leaves_on": "ground"}, "leaves_on")]:
        with pytest.raises(radrecon.Error, match=name + ": applies to"):
            radrecon.solve("paper", mesh, **keywords)


def test_solution_arrays_hold_what_the_file_holds(tmp_path):
    # Each side's frame, barriers, excluded regions and each element's cell shape, as the saved
    # file (read here by Python's json) has them: a triangle's two halves of one cell were told
    # apart only by their centres.
    sol = radrecon.solve("cornell", "grid:4")
    path = tmp_path / "cornell.json"
    sol.save(str(path))
    doc = json.load(open(path))
    assert sol.stats["patches"] == doc["stats"]["patches"] > 0
    # The statistics' keys are the file's (a grid solve has no links, a hierarchical one its epsilon).
    for solution in (sol, radrecon.solve("paper", "quadtree:49")):
        solution.save(tmp_path / "stats.json")
        assert set(solution.stats) == set(json.load(open(tmp_path / "stats.json"))["stats"])
    by_name = {s["name"]: s for s in doc["surfaces"]}
    for side in sol.surfaces:
        saved = by_name[side["name"]]
        for key in ("length_u_m", "length_v_m"):
            assert side[key] == saved[key]
        assert side["shear_m"] == saved.get("shear_m", 0.0)
        assert [line.tolist() for line in side["barriers"]] == saved.get("barriers", [])
        assert [poly.tolist() for poly in side["excluded"]] == saved.get("excluded", [])
        assert side["shape"] == [e.get("shape", "box") for e in saved["elements"]]
    red = next(s for s in sol.surfaces if s["name"] == "red_wall.a")
    assert set(red["shape"]) == {"lower", "upper"}
    floor = next(s for s in sol.surfaces if s["name"] == "floor")
    assert len(floor["barriers"]) > 0 and len(floor["excluded"]) == 2  # the blocks' feet, their covered floor


def test_a_solution_does_not_overwrite_its_scene(tmp_path):
    # As the command line refuses --out naming an input: the scene file, or a model it includes.
    scene = tmp_path / "scene.json"
    scene.write_text(json.dumps({"name": "s", "surfaces": [
        {"name": "floor", "corners": [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], "reflectance": 0.5},
        {"name": "light", "corners": [[0.4, 0.4, 1], [0.4, 0.6, 1], [0.6, 0.6, 1], [0.6, 0.4, 1]],
         "reflectance": 0, "emission": 10}]}))
    before = scene.read_bytes()
    solution = radrecon.solve(str(scene), "grid:2")
    with pytest.raises(radrecon.Error, match="is the input file"):
        solution.save(str(scene))
    # The scene named relative to the working folder, which then changes: still refused.
    here = os.getcwd()
    try:
        os.chdir(tmp_path)
        relative = radrecon.solve("scene.json", "grid:2")
        os.chdir(here)
        with pytest.raises(radrecon.Error, match="is the input file"):
            relative.save(str(scene))
    finally:
        os.chdir(here)
    assert scene.read_bytes() == before
    solution.save(str(tmp_path / "solution.json"))
    # A pathlib.Path for the scene and for save() (both took a str only), the same solution.
    by_path = radrecon.solve(scene, "grid:2")
    with pytest.raises(radrecon.Error, match="is the input file"):
        by_path.save(scene)
    by_path.save(tmp_path / "by_path.json")
    assert json.load(open(tmp_path / "by_path.json"))["surfaces"] == json.load(open(tmp_path / "solution.json"))["surfaces"]
    with pytest.raises(radrecon.Error, match=r"^scene: expected a file name \(str or os.PathLike\)"):
        radrecon.solve(3)
    with pytest.raises(radrecon.Error, match=r"^path: expected a file name"):
        by_path.save(None)


def test_solve_takes_the_far_field_bound_and_shadow_barriers_as_the_command_line(tmp_path):
    # Each keyword reaches the solver: the saved solution is the command line's with the same
    # option, timing aside, and not the default's.
    def without_timing(path):
        doc = json.load(open(path))
        doc["stats"].pop("seconds")
        return doc

    default = tmp_path / "default.json"
    radrecon.solve("paper", "grid:8").save(str(default))
    for keywords, options in [({"far_field_error": 0.0}, ["--far-field-error", "0"]),
                              ({"shadow_barriers": True}, ["--shadow-barriers"])]:
        ours, theirs = tmp_path / "ours.json", tmp_path / "theirs.json"
        radrecon.solve("paper", "grid:8", **keywords).save(str(ours))
        subprocess.run([RADRECON_BIN, "solve", "--scene", "paper", "--mesh", "grid:8", "--out", str(theirs), "--quiet",
                        *options], check=True)
        assert without_timing(ours) == without_timing(theirs), options
        assert without_timing(ours) != without_timing(default), options


def test_a_raster_apart_from_the_samples_is_a_warning():
    # As the command line warns: a domain in another unit or CRS, or with x and y swapped.
    points, values = np.array([[0, 0], [1, 0], [0, 1]]), np.array([1.0, 2.0, 3.0])
    with pytest.warns(UserWarning, match=r"the domain \[5, 5, 6, 6\] does not meet the samples' bounding box"):
        radrecon.interpolate(points, values, raster=(2, 2), domain=(5, 5, 6, 6), method="linear")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        radrecon.interpolate(points, values, raster=(2, 2), domain=(0.5, 0.5, 6, 6), method="linear")
