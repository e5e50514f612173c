#!/usr/bin/env python3
"""Where interpolate's georeferenced rasters land: never on an input (a VRT's table), nowhere that
cannot be made; a raster whose files cannot all be moved into place is moved not at all; the
modes of the files replaced are kept; an earlier raster's side files are removed, never a
product's metadata or an input; a run terminated while GDAL writes leaves nothing. Read back by
GDAL itself (python3-gdal).

Usage: gdal_replace_check.py /path/to/radrecon   (exit 77: python3-gdal or gdalinfo missing)
"""
import os
import shutil
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gdal_check_support import check, finish, gdal, osr, run, write_samples, RADRECON  # noqa: E402

with tempfile.TemporaryDirectory() as tmp:
    samples = write_samples(tmp)

    # An OGR VRT over a CSV: the CSV is a file of the source, and --out may not replace it.
    table = os.path.join(tmp, "vrt_table.csv")
    shutil.copyfile(samples, table)
    before = open(table, "rb").read()
    vrt = os.path.join(tmp, "pts.vrt")
    with open(vrt, "w") as v:
        v.write('<OGRVRTDataSource><OGRVRTLayer name="vrt_table"><SrcDataSource relativeToVRT="1">vrt_table.csv</SrcDataSource>'
                '<GeometryType>wkbPoint</GeometryType><GeometryField encoding="PointFromColumns" x="long" y="lat"/>'
                '<Field name="mag" type="Real"/></OGRVRTLayer></OGRVRTDataSource>')
    r = run("--samples", vrt, "--value", "mag", "--method", "linear", "--queries", samples, "--out", table)
    check(r.returncode == 2 and "refusing to overwrite" in r.stderr and open(table, "rb").read() == before,
          f"--out over a VRT's table: exit {r.returncode}, {r.stderr.strip()}")

    # An output that cannot be created (its folder is a file): exit 2 naming it, nothing left behind.
    blocker = os.path.join(tmp, "not_a_folder")
    open(blocker, "w").close()
    r = run("--samples", samples, "--value", "mag", "--method", "linear", "--raster", "4x3", "--domain", "0,0,4,3",
            "--out", os.path.join(blocker, "x.tif"))
    check(r.returncode == 2 and "not_a_folder" in r.stderr, f"unwritable GeoTIFF: exit {r.returncode}, {r.stderr.strip()}")
    check([e for e in os.listdir(tmp) if e.startswith(".radrecon-gdal") or ".tmp" in e] == [],
          "no temporary file or folder left behind")

    # A file GDAL wrote that cannot be moved into place: a folder where the EHdr driver's header
    # goes is refused before any file is moved, naming it; a rename the system refuses (an
    # immutable file, where chattr can make one) says the system's reason, naming the output and
    # not the temporary folder (it was an exit 1 "filesystem error" naming both). Exit 2, the
    # temporary folder removed.
    moved = os.path.join(tmp, "moved")
    os.mkdir(moved)
    os.makedirs(os.path.join(moved, "m.hdr", "inside"))
    r = run("--samples", samples, "--value", "mag", "--method", "linear", "--raster", "4x3", "--domain", "0,0,4,3",
            "--out", os.path.join(moved, "m.bil"))
    check(r.returncode == 2 and os.path.join(moved, "m.hdr") + ": is a folder" in r.stderr
          and not os.path.exists(os.path.join(moved, "m.bil")) and ".radrecon-gdal" not in r.stderr,
          f"m.bil beside a folder m.hdr: exit {r.returncode}, {r.stderr.strip()}")
    immutable = os.path.join(moved, "imm.asc")
    open(immutable, "w").write("earlier\n")
    if shutil.which("chattr") and subprocess.run(["chattr", "+i", immutable], capture_output=True).returncode == 0:
        try:
            r = run("--samples", samples, "--value", "mag", "--method", "linear", "--raster", "4x3", "--domain",
                    "0,0,4,3", "--out", immutable)
        finally:
            subprocess.run(["chattr", "-i", immutable])
        check(r.returncode == 2 and f"radrecon: error: {immutable}: cannot write: Operation not permitted" in r.stderr
              and ".radrecon-gdal" not in r.stderr and open(immutable).read() == "earlier\n",
              f"imm.asc immutable: exit {r.returncode}, {r.stderr.strip()}")
        # A raster of two files whose header cannot be replaced: the data file, moved first, goes
        # back (the review found 3 x 3 values under the earlier 6 x 5 header, unreadable).
        pair = os.path.join(moved, "pair.bil")
        r = run("--samples", samples, "--value", "mag", "--method", "linear", "--raster", "6x5", "--domain", "0,0,4,3",
                "--out", pair)
        check(r.returncode == 0, f"pair.bil: exit {r.returncode}, {r.stderr.strip()}")
        before = {n: open(os.path.join(moved, n), "rb").read() for n in os.listdir(moved) if n.startswith("pair.")}
        header = os.path.join(moved, "pair.hdr")
        subprocess.run(["chattr", "+i", header])
        try:
            r = run("--samples", samples, "--value", "mag", "--method", "linear", "--raster", "3x3", "--domain",
                    "0,0,4,3", "--out", pair)
        finally:
            subprocess.run(["chattr", "-i", header])
        after = {n: open(os.path.join(moved, n), "rb").read() for n in os.listdir(moved) if n.startswith("pair.")}
        check(r.returncode == 2 and "pair.hdr: cannot write" in r.stderr and after == before,
              f"pair.bil, its header immutable: exit {r.returncode}, {r.stderr.strip()}; files changed: "
              f"{sorted(n for n in set(before) | set(after) if before.get(n) != after.get(n))}")
    check([e for e in os.listdir(moved) if e.startswith(".radrecon-gdal")] == [],
          f"a temporary folder left beside m.bil or imm.asc: {os.listdir(moved)}")

    # Replacing a GDAL raster keeps the mode of each file it replaces (the raster 0600, its .prj
    # 0640): they became the new files' 0644.
    kept = os.path.join(tmp, "kept.asc")
    for attempt in range(2):
        r = run("--samples", samples, "--value", "mag", "--method", "linear", "--raster", "4x3", "--domain",
                "0,0,4,3", "--crs", "EPSG:2193", "--out", kept)
        check(r.returncode == 0, f"kept.asc: exit {r.returncode}, {r.stderr.strip()}")
        if attempt == 0:
            os.chmod(kept, 0o600)
            os.chmod(os.path.join(tmp, "kept.prj"), 0o640)
    modes = (oct(os.stat(kept).st_mode & 0o777), oct(os.stat(os.path.join(tmp, "kept.prj")).st_mode & 0o777))
    check(modes == ("0o600", "0o640"), f"kept.asc, kept.prj replaced: modes {modes}")

    # A raster replaced takes its files along: of the earlier raster (as GDAL lists them), those
    # the new one does not write are removed. An older .prj stayed beside a raster written without
    # --crs, and GIS read the old CRS; an older .aux.xml beside a GeoTIFF of radrecon's own writer
    # gave GDAL its CRS. Files of the user's beside them stay, and so does an input of the run
    # that GDAL lists among the earlier raster's files (a GeoTIFF's _rpc.txt).
    stale = os.path.join(tmp, "stale")
    os.mkdir(stale)
    at = lambda name: os.path.join(stale, name)
    open(at("notes.txt"), "w").write("mine\n")
    for name, side in [("o.bil", "o.prj"), ("o.asc", "o.prj")]:
        for crs in (["--crs", "EPSG:2193"], []):
            r = run("--samples", samples, "--value", "mag", "--method", "linear", "--raster", "4x3", "--domain",
                    "0,0,4,3", *crs, "--out", at(name))
            check(r.returncode == 0, f"stale {name} {crs}: exit {r.returncode}, {r.stderr.strip()}")
            if crs:
                check(os.path.exists(at(side)), f"stale {name}: no {side} written with --crs")
        check(not os.path.exists(at(side)), f"stale {name}: the earlier {side} stayed: {sorted(os.listdir(stale))}")
        check(gdal.Open(at(name)).GetProjection() == "", f"stale {name}: GDAL reads a CRS: {gdal.Open(at(name)).GetProjection()[:60]}")
        for e in os.listdir(stale):
            if e.startswith("o."):
                os.remove(at(e))
    # radrecon's own GeoTIFF writer (an EPSG code) over a GeoTIFF with an .aux.xml of another CRS.
    r = run("--samples", samples, "--value", "mag", "--method", "linear", "--raster", "4x3", "--domain", "0,0,4,3",
            "--crs", "EPSG:2193", "--out", at("g.tif"))
    open(at("g.tif.aux.xml"), "w").write("<PAMDataset><SRS>EPSG:4326</SRS></PAMDataset>\n")
    shutil.copyfile(samples, at("g_rpc.txt"))  # listed by GDAL with g.tif, and read as samples below
    r = run("--samples", at("g_rpc.txt"), "--value", "mag", "--method", "linear", "--raster", "4x3", "--domain",
            "0,0,4,3", "--crs", "EPSG:2193", "--out", at("g.tif"))
    check(r.returncode == 0, f"stale g.tif: exit {r.returncode}, {r.stderr.strip()}")
    check(not os.path.exists(at("g.tif.aux.xml")), "stale g.tif: the earlier .aux.xml stayed")
    check(osr.SpatialReference(wkt=gdal.Open(at("g.tif")).GetProjection()).GetAuthorityCode(None) == "2193",
          "stale g.tif: GDAL does not read EPSG:2193")
    check(os.path.exists(at("g_rpc.txt")) and open(at("notes.txt")).read() == "mine\n",
          f"stale: an input or a file of the user's was removed: {sorted(os.listdir(stale))}")
    # GDAL also lists a satellite product's metadata with a GeoTIFF, named after the folder or
    # shared by its rasters (ALOS summary.txt, SPOT METADATA.DIM, Landsat X_MTL.txt, X.RPB): the
    # review found each removed with exit 0. Only side files named after the raster go.
    for name in ("summary.txt", "METADATA.DIM", "site_MTL.txt", "site_b.RPB", "site_b.IMD"):
        open(at(name), "w").write("product metadata\n")
    for attempt in range(2):
        r = run("--samples", samples, "--value", "mag", "--method", "linear", "--raster", "4x3", "--domain",
                "0,0,4,3", "--crs", "EPSG:2193", "--out", at("site_b.tif"))
        check(r.returncode == 0, f"site_b.tif: exit {r.returncode}, {r.stderr.strip()}")
    kept_all = [n for n in ("summary.txt", "METADATA.DIM", "site_MTL.txt", "site_b.RPB", "site_b.IMD") if os.path.exists(at(n))]
    check(len(kept_all) == 5, f"site_b.tif replaced: a product's metadata was removed: {sorted(os.listdir(stale))}")

    # Terminated while GDAL writes (an MRF of 9 million DEFLATE-compressed points takes seconds):
    # exit by SIGTERM, said, and neither the output, its side files nor the temporary folder left.
    sig_dir = os.path.join(tmp, "terminated")
    os.mkdir(sig_dir)
    proc = subprocess.Popen([RADRECON, "interpolate", "--samples", samples, "--value", "mag", "--method", "shepard",
                             "--raster", "3000x3000", "--domain", "0,0,4,3", "--out", os.path.join(sig_dir, "big.mrf"),
                             "--quiet"], stderr=subprocess.PIPE, text=True)
    seen = []
    for _ in range(3000):  # up to a minute for the values, then for the folder's first file
        seen = [e for e in os.listdir(sig_dir) if e.startswith(".radrecon-gdal")]
        if (seen and os.listdir(os.path.join(sig_dir, seen[0]))) or proc.poll() is not None:
            break
        time.sleep(0.02)
    proc.terminate()
    err = proc.communicate()[1]
    check(bool(seen) and proc.returncode == -15, f"terminated MRF: exit {proc.returncode}, folder seen: {seen}; {err.strip()}")
    check("radrecon: terminated (SIGTERM); no output was left half-written under its name" in err,
          f"terminated MRF said: {err.strip()}")
    check(os.listdir(sig_dir) == [], f"terminated MRF left {os.listdir(sig_dir)}")

    # The same command twice writes the same bytes: netCDF's "history" attribute held the time and
    # the staging folder's random name (a thread-count audit found the files differing in it).
    written = []
    for k in range(2):
        out = os.path.join(tmp, f"again{k}.nc")
        r = run("--samples", samples, "--value", "mag", "--method", "linear", "--raster", "4x3", "--domain", "0,0,4,3",
                "--out", out)
        check(r.returncode == 0, f"again{k}.nc: exit {r.returncode}, {r.stderr.strip()}")
        written.append(open(out, "rb").read() if r.returncode == 0 else b"")
        time.sleep(1.1)  # the history's time is in seconds
    check(written[0] == written[1] and b".radrecon-gdal" not in written[0],
          "two runs of one command wrote different netCDF files (or named the staging folder)")

finish()
