"""Arrays NumPy would convert with a loss the caller would not see are refused, naming the
argument: complex numbers (their imaginary parts dropped with only NumPy's ComplexWarning) and
masked arrays (their hidden entries used). An outside-in trial found both taken silently."""

import warnings

import numpy as np
import pytest

import radrecon

P = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]])
V = np.array([1.0, 2.0, 3.0, 4.0])
Q = np.array([[0.5, 0.25]])


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
