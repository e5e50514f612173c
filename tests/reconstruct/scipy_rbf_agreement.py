#!/usr/bin/env python3
"""radrecon's thin-plate spline and multiquadric with a linear polynomial against scipy's
RBFInterpolator (an independent implementation of the same system): `radrecon interpolate
--method thin-plate` against RBFInterpolator(kernel="thin_plate_spline", degree=1), and
`--method multiquadric --param r=R --param poly=1` against RBFInterpolator(kernel="multiquadric",
epsilon=1/R, degree=1). scipy's multiquadric is -sqrt(1 + (eps d)^2) = -(1/R) sqrt(d^2 + R^2): a
constant factor times ours, so the interpolant is the same function. 200 random samples (fixed
seed), two value columns, 600 queries over the samples' box and a quarter of it around (outside
the hull). Prints the measured differences. Exit 0 on agreement, 1 on disagreement, 77 (skipped)
without scipy.

Usage: scipy_rbf_agreement.py RADRECON
"""
import os
import subprocess
import sys
import tempfile

try:
    import numpy as np
    from scipy.interpolate import RBFInterpolator
except ImportError:
    print("scipy is not installed (Debian: python3-scipy): skipped")
    sys.exit(77)

# Both solve the same dense system by partial-pivoting LU in differently scaled frames, so they
# differ by about eps / rcond of the values' size: measured 4e-14 (thin-plate) and 3e-13
# (multiquadric, r = 0.1). 1e-8 leaves room for other LAPACK builds and poorer conditioning (with
# r = 0.3 the multiquadric's reciprocal condition is 2e-13 and the difference 1e-9).
RELATIVE = 1e-8

radrecon = sys.argv[1]
rng = np.random.default_rng(20240610)
points = rng.random((200, 2))
values = np.column_stack([np.sin(6 * points[:, 0]) * np.cos(4 * points[:, 1]),
                          1 + points[:, 0] ** 2 - 0.5 * points[:, 1]])
queries = rng.uniform(-0.25, 1.25, (600, 2))

failed = False
with tempfile.TemporaryDirectory() as work:
    samples_csv, queries_csv, out_csv = (os.path.join(work, n) for n in ("s.csv", "q.csv", "o.csv"))
    np.savetxt(samples_csv, np.column_stack([points, values]), delimiter=",", header="x,y,a,b", comments="",
               fmt="%.17g")
    np.savetxt(queries_csv, queries, delimiter=",", header="x,y", comments="", fmt="%.17g")
    r = 0.1
    for label, args, kw in [
            ("thin-plate", ["--method", "thin-plate"], dict(kernel="thin_plate_spline")),
            ("multiquadric r=0.1 poly=1", ["--method", "multiquadric", "--param", f"r={r}", "--param", "poly=1"],
             dict(kernel="multiquadric", epsilon=1 / r))]:
        subprocess.run([radrecon, "interpolate", "--quiet", "--samples", samples_csv, "--queries", queries_csv,
                        "--out", out_csv] + args, check=True)
        ours = np.loadtxt(out_csv, delimiter=",", skiprows=1)[:, 2:]
        theirs = RBFInterpolator(points, values, degree=1, **kw)(queries)
        difference = np.max(np.abs(ours - theirs)) / np.max(np.abs(theirs))
        ok = difference <= RELATIVE
        failed |= not ok
        print(f"{label}: largest difference from scipy RBFInterpolator {difference:.2e} of the values' size "
              f"(allowed {RELATIVE:g}) {'ok' if ok else 'FAILED'}")
sys.exit(1 if failed else 0)
