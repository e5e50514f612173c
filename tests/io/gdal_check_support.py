"""What the GDAL checks share (gdal_raster_check.py, gdal_replace_check.py, gdal_barriers_check.py):
GDAL's Python bindings (exit 77 without them or gdalinfo), radrecon's path from argv[1], a failure list,
the linear function the samples hold, and a run of `radrecon interpolate`."""
import os
import shutil
import subprocess
import sys

try:
    from osgeo import gdal, osr  # noqa: F401 (osr: for the checks that import it from here)
except ImportError:
    print(os.path.basename(sys.argv[0]) + ": skipped: no python3-gdal")
    sys.exit(77)
if shutil.which("gdalinfo") is None:
    print(os.path.basename(sys.argv[0]) + ": skipped: no gdalinfo")
    sys.exit(77)
gdal.UseExceptions()

RADRECON = sys.argv[1]
failures = []


def check(condition, what):
    if not condition:
        failures.append(what)
        print("FAIL:", what)


def f(x, y):
    return 2 + 3 * x - y


def run(*args):
    return subprocess.run([RADRECON, "interpolate", *args, "--quiet"], capture_output=True, text=True)


def write_samples(folder):
    """Samples of f on a 5 x 4 grid over [0, 4] x [0, 3], columns named as a real file would."""
    samples = os.path.join(folder, "quake.csv")
    with open(samples, "w") as out:
        out.write("long,lat,mag,depth\n")
        for j in range(4):
            for i in range(5):
                out.write(f"{i},{j},{f(i, j)!r},{10 + i}\n")
    return samples


def finish():
    name = os.path.splitext(os.path.basename(sys.argv[0]))[0]
    print(name + ":", "FAILED" if failures else "passed", f"({len(failures)} failures)")
    sys.exit(1 if failures else 0)
