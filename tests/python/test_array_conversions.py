"""Arrays the module refuses, naming the argument: not finite, of the wrong shape, beyond the
coordinates' and values' bounds, and what NumPy would convert with a loss the caller would not
see: complex numbers (their imaginary parts dropped with only NumPy's ComplexWarning), masked
arrays (their hidden entries used), text and dates (parsed or counted). Outside-in trials found
each taken silently."""

import warnings

import numpy as np
import pytest

import radrecon

P = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]])
V = np.array([1.0, 2.0, 3.0, 4.0])
Q = np.array([[0.5, 0.25]])


def samples(n=50, seed=1):
    rng = np.random.default_rng(seed)
    p = rng.random((n, 2))
    return p, np.sin(6 * p[:, 0]) * np.cos(4 * p[:, 1])


@pytest.mark.parametrize(
    "points, values, queries, named",
    [
        (P.astype(complex), V, Q, "points"),
        (P, V + 0j, Q, "values"),
        (P, V, Q + 0j, "queries"),
        ([[0, 0], [1, 0], [0, 1j], [1, 1]], V, Q, "points"),  # a list holding one complex number
    ],
)
def test_complex_numbers_are_refused(points, values, queries, named):
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no ComplexWarning on the way to the refusal
        with pytest.raises(radrecon.Error, match=rf"^{named}: complex numbers are not taken"):
            radrecon.interpolate(points, values, queries=queries, method="linear")


def test_masked_arrays_are_refused():
    masked = np.ma.masked_array(V, mask=[False, False, True, False])
    with pytest.raises(radrecon.Error, match=r"^values: a masked array: its mask would be ignored"):
        radrecon.interpolate(P, masked, queries=Q, method="linear")
    with pytest.raises(radrecon.Error, match=r"^points: a masked array"):
        radrecon.interpolate(np.ma.masked_array(P), V, queries=Q, method="linear")


def test_real_arrays_of_any_dtype_are_still_taken():
    # The linear interpolant of v = 1 + x + 2y at (0.5, 0.25): 2.0 whatever the input's dtype.
    for dtype in (np.float64, np.float32, np.int64, np.int16):
        got = radrecon.interpolate(P.astype(dtype), V.astype(dtype), queries=Q, method="linear")
        assert got.tolist() == [2.0], dtype
    assert radrecon.interpolate(P.tolist(), V.tolist(), queries=Q.tolist(), method="linear").tolist() == [2.0]


def test_samples_merged_across_a_barrier_are_refused_counting_from_0():
    # Within 1e-9 of the extent, on either side of the wall x = 0.5: merged, their mean would be
    # seen from both sides. Named as Python indexes them, as the module's other messages are.
    points = np.array([[0, 0], [1, 0], [0, 1], [1, 1], [0.5 - 1e-10, 0.3], [0.5 + 1e-10, 0.3]])
    values = np.array([0.0, 100, 0, 100, 0, 100])
    with pytest.raises(radrecon.Error, match=r"^points: points\[4\] and points\[5\], at .* lie on either side of a barrier"):
        radrecon.interpolate(points, values, queries=Q, method="shepard", barriers=[np.array([[0.5, -1], [0.5, 2]])])


def test_bad_arrays_are_named():
    p, v = samples(50)
    bad = p.copy()
    bad[7, 1] = np.nan
    with pytest.raises(radrecon.Error, match=r"points\[7\]: not a finite number"):
        radrecon.interpolate(bad, v, queries=p)
    with pytest.raises(radrecon.Error, match=r"values: an array of shape \(50,\)"):
        radrecon.interpolate(p, v[:10], queries=p)
    with pytest.raises(radrecon.Error, match=r"points: an array of shape \(n, 2\)"):
        radrecon.interpolate(np.zeros((5, 3)), np.zeros(5), queries=p)
    with pytest.raises(radrecon.Error, match="give the query points"):
        radrecon.interpolate(p, v)
    with pytest.raises(radrecon.Error, match="raster needs domain"):
        radrecon.interpolate(p, v, raster=(10, 10))
    # The command line's bounds: beyond them distances and sums overflow (a query at 1e200 had
    # aborted the interpreter in the k-d tree, values near 1e308 gave inf or NaN).
    far = p.copy()
    far[3, 0] = 1e200
    with pytest.raises(radrecon.Error, match=r"points\[3\]: 1e\+200 is beyond the largest coordinate, 1e\+100"):
        radrecon.interpolate(far, v, queries=p)
    with pytest.raises(radrecon.Error, match=r"queries\[3\]: 1e\+200 is beyond the largest coordinate"):
        radrecon.interpolate(p, v, queries=far)
    with pytest.raises(radrecon.Error, match="domain: .*magnitude at most 1e\\+100"):
        radrecon.interpolate(p, v, raster=(2, 2), domain=(0, 0, 1e200, 1))
    big = v.copy()
    big[5] = -1e308
    with pytest.raises(radrecon.Error, match=r"values\[5\]: -1e\+308 is beyond the largest value, 1e\+100"):
        radrecon.interpolate(p, big, queries=p)
    # Arguments of the wrong kind, named, in a message of one line (pybind's TypeError printed
    # every argument's whole array and named none; an outside-in trial).
    for kwargs, pattern in [(dict(queries="abc"), r"^queries: an array of numbers is expected, got 'abc' \(str\)$"),
                            (dict(queries=[["a", "b"]]), r"^queries: an array of numbers is expected"),
                            (dict(queries=p, method=None), r"^method: a method's name is expected .* got None$"),
                            (dict(queries=p, barriers=5), r"^barriers: a file name .* is expected, got 5$")]:
        with pytest.raises(radrecon.Error, match=pattern) as e:
            radrecon.interpolate(p, v, **kwargs)
        assert len(str(e.value)) < 200
    with pytest.raises(radrecon.Error, match=r"^points: an array of numbers is expected, got None"):
        radrecon.interpolate(None, v, queries=p)
    # Text and dates NumPy would have parsed or counted in silence (an outside-in trial).
    for kwargs, pattern in [(dict(queries=[["0.5", "0.5"]]), r"^queries: an array of numbers is expected, got one of <U3 \(text\)"),
                            (dict(queries=p.astype("datetime64[s]")), r"^queries: .* \(dates or times\)")]:
        with pytest.raises(radrecon.Error, match=pattern):
            radrecon.interpolate(p, v, **kwargs)
    with pytest.raises(radrecon.Error, match=r"^values: .* \(text\)"):
        radrecon.interpolate(p, v.astype(str), queries=p)
    # An object array (a pandas column) holding text, refused; one holding numbers, taken.
    with pytest.raises(radrecon.Error, match=r"^values: .* an object array holding text"):
        radrecon.interpolate(p, v.astype(str).astype(object), queries=p)
    assert np.array_equal(radrecon.interpolate(p, v.astype(object), queries=p[:5]), radrecon.interpolate(p, v, queries=p[:5]))
