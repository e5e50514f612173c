#!/usr/bin/env python3
"""interpolate to georeferenced rasters, read back by GDAL itself (python3-gdal and gdalinfo -json):
geotransform, north-up row order, CRS, no-data, band type and values against the closed form of a
linear function, which `linear` reproduces exactly inside the samples' hull. GeoTIFFs whose CRS is
an EPSG code (or none) are radrecon's own libtiff writer's; those of any other CRS, and the other
formats, GDAL's: the two must give the same file content.

Usage: gdal_raster_check.py /path/to/radrecon   (exit 77: python3-gdal or gdalinfo missing)
"""
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gdal_check_support import RADRECON, check, f, finish, gdal, osr, run, write_samples  # noqa: E402

with tempfile.TemporaryDirectory() as tmp:
    samples = write_samples(tmp)
    x0, y0, x1, y1, W, H = -1.0, 0.0, 4.0, 3.0, 10, 6
    domain = f"{x0},{y0},{x1},{y1}"
    tif = os.path.join(tmp, "mag.tif")
    r = run("--samples", samples, "--x", "long", "--y", "lat", "--value", "mag", "--method", "linear",
            "--param", "outside=none", "--raster", f"{W}x{H}", "--domain", domain, "--crs", "EPSG:2193",
            "--type", "float64", "--out", tif)
    check(r.returncode == 0, f"GeoTIFF written (exit {r.returncode}: {r.stderr.strip()})")
    if r.returncode == 0:
        d = gdal.Open(tif)
        dx, dy = (x1 - x0) / W, (y1 - y0) / H
        check(d.GetDriver().ShortName == "GTiff", "a GeoTIFF")
        check(d.GetGeoTransform() == (x0, dx, 0.0, y1, 0.0, -dy), f"geotransform {d.GetGeoTransform()}")
        srs = osr.SpatialReference(wkt=d.GetProjection())
        check(srs.GetAuthorityCode(None) == "2193", f"CRS {srs.GetAuthorityName(None)}:{srs.GetAuthorityCode(None)}")
        band = d.GetRasterBand(1)
        check(d.RasterCount == 1, "one band for one --value column")
        check(band.GetNoDataValue() == -9999.0, f"no-data {band.GetNoDataValue()}")
        check(gdal.GetDataTypeName(band.DataType) == "Float64", "Float64 with --type float64")
        a = band.ReadAsArray()
        inside = outside = 0
        for row in range(H):
            y = y1 - (row + 0.5) * dy  # north-up: stored row 0 is the top
            for col in range(W):
                x = x0 + (col + 0.5) * dx
                if 0 <= x <= 4 and 0 <= y <= 3:
                    inside += 1
                    check(abs(a[row, col] - f(x, y)) <= 1e-12 * 20, f"value at ({x}, {y}): {a[row, col]} vs {f(x, y)}")
                else:
                    outside += 1
                    check(a[row, col] == -9999.0, f"no-data outside the hull at ({x}, {y}): {a[row, col]}")
        check(inside > 0 and outside > 0, "cells inside and outside the hull")
        info = json.loads(subprocess.run(["gdalinfo", "-json", tif], capture_output=True, text=True, check=True).stdout)
        check(info["geoTransform"] == [x0, dx, 0.0, y1, 0.0, -dy], f"gdalinfo geotransform {info['geoTransform']}")
        check(info["bands"][0]["noDataValue"] == -9999.0, "gdalinfo no-data")
        check(info["size"] == [W, H], f"gdalinfo size {info['size']}")

    # The same raster written by GDAL (a CRS without an EPSG code: the libtiff writer cannot
    # record it) holds the same pixels, geotransform, no-data value and CRS; and a geographic CRS.
    if r.returncode == 0:
        tmerc = ("+proj=tmerc +lat_0=0 +lon_0=173 +k=0.9996 +x_0=1600000 +y_0=10000000 +ellps=GRS80 "
                 "+towgs84=0,0,0,0,0,0,0 +units=m +no_defs +type=crs")
        for crs, name in [(tmerc, "gdal_written.tif"), ("EPSG:4326", "lonlat.tif")]:
            other = os.path.join(tmp, name)
            r2 = run("--samples", samples, "--x", "long", "--y", "lat", "--value", "mag", "--method", "linear",
                     "--param", "outside=none", "--raster", f"{W}x{H}", "--domain", domain, "--crs", crs,
                     "--type", "float64", "--out", other)
            check(r2.returncode == 0, f"{name} written ({r2.stderr.strip()})")
            if r2.returncode != 0:
                continue
            o = gdal.Open(other)
            check(o.GetGeoTransform() == d.GetGeoTransform(), f"{name}: geotransform {o.GetGeoTransform()}")
            check(o.GetRasterBand(1).GetNoDataValue() == -9999.0, f"{name}: no-data")
            check((o.GetRasterBand(1).ReadAsArray() == a).all(), f"{name}: the same pixels")
            osrs = osr.SpatialReference(wkt=o.GetProjection())
            if name == "lonlat.tif":
                check(osrs.IsGeographic() and osrs.GetAuthorityCode(None) == "4326", f"{name}: CRS EPSG:4326")
            else:
                check(osrs.ExportToProj4() == srs.ExportToProj4() and osrs.GetAuthorityCode(None) is None,
                      f"{name}: GDAL's CRS is EPSG:2193's projection, without the code")

    # Values beyond a float's range: +-infinity in a Float32 band from both writers (GDAL's rule).
    huge = os.path.join(tmp, "huge.csv")
    with open(huge, "w") as out:
        out.write("x,y,v\n0,0,1e39\n1,0,-1e39\n0,1,0.5\n1,1,3e38\n")
    stored = {}
    for crs, name in [("EPSG:2193", "huge_tiff.tif"), ("+proj=longlat +ellps=GRS80 +no_defs +type=crs", "huge_gdal.tif")]:
        out = os.path.join(tmp, name)
        r = run("--samples", huge, "--method", "constant", "--raster", "2x2", "--domain", "0,0,1,1", "--crs", crs,
                "--out", out)
        check(r.returncode == 0, f"{name} written ({r.stderr.strip()})")
        stored[name] = gdal.Open(out).ReadAsArray().tolist() if r.returncode == 0 else None
    check(stored["huge_tiff.tif"] is not None and stored["huge_tiff.tif"] == stored["huge_gdal.tif"],
          f"out-of-range values as GDAL stores them: {stored}")
    check(stored["huge_tiff.tif"] is not None and stored["huge_tiff.tif"][1][0] == float("inf"),
          f"1e39 stored as infinity: {stored['huge_tiff.tif']}")

    # Two value columns: two bands, Float32 by default; another driver by its extension.
    asc = os.path.join(tmp, "both.tif")
    r = run("--samples", samples, "--method", "linear", "--raster", "5x4", "--domain", "0,0,4,3", "--out", asc)
    check(r.returncode == 0, f"two bands written ({r.stderr.strip()})")
    if r.returncode == 0:
        d = gdal.Open(asc)
        check(d.RasterCount == 2, f"{d.RasterCount} bands for mag and depth")
        check(gdal.GetDataTypeName(d.GetRasterBand(1).DataType) == "Float32", "Float32 by default")
        depth = d.GetRasterBand(2).ReadAsArray()
        check(abs(depth[0, 0] - (10 + 0.4)) < 1e-5, f"depth band {depth[0, 0]} (10 + x at x = 0.4)")
        mag = d.GetRasterBand(1).ReadAsArray()
        check(abs(mag[0, 0] - f(0.4, 2.625)) < 1e-5, f"mag band {mag[0, 0]} at the top-left cell")
    grd = os.path.join(tmp, "mag.asc")
    r = run("--samples", samples, "--value", "mag", "--method", "linear", "--raster", "5x4", "--domain", "0,0,4,3",
            "--out", grd)
    check(r.returncode == 0 and gdal.Open(grd).GetDriver().ShortName == "AAIGrid", "Arc/Info ASCII grid by its extension")

    # Samples from a GeoPackage of points (OGR), with a barrier line from a GeoPackage and the
    # same line from GeoJSON: the two barrier readers agree, and the values match f.
    from osgeo import ogr, osr

    def point_layer(path, driver, layer_name, nx, ny, fields, srs=None):
        """A vector source of the nx x ny points (i, j), each with fields {name: (OGR type, value(i, j))}."""
        ds = ogr.GetDriverByName(driver).CreateDataSource(path)
        layer = ds.CreateLayer(layer_name, srs=srs, geom_type=ogr.wkbPoint)
        for name, (kind, _) in fields.items():
            layer.CreateField(ogr.FieldDefn(name, kind))
        for j in range(ny):
            for i in range(nx):
                feature = ogr.Feature(layer.GetLayerDefn())
                feature.SetGeometry(ogr.CreateGeometryFromWkt(f"POINT ({i} {j})"))
                for name, (_, value) in fields.items():
                    feature.SetField(name, value(i, j))
                layer.CreateFeature(feature)
        ds = None
        return path

    gpkg = point_layer(os.path.join(tmp, "points.gpkg"), "GPKG", "soundings", 5, 4,
                       {"mag": (ogr.OFTReal, f), "name": (ogr.OFTString, lambda i, j: f"p{i}{j}")})
    def line_layer(name, wkt):
        """A GeoPackage of one line feature, for --barriers."""
        path = os.path.join(tmp, name)
        ds = ogr.GetDriverByName("GPKG").CreateDataSource(path)
        layer = ds.CreateLayer("faults", geom_type=ogr.wkbLineString)
        feature = ogr.Feature(layer.GetLayerDefn())
        feature.SetGeometry(ogr.CreateGeometryFromWkt(wkt))
        layer.CreateFeature(feature)
        ds = None
        return path

    lines = line_layer("fault.gpkg", "LINESTRING (2.2 -1, 2.2 4)")
    geojson = os.path.join(tmp, "fault.geojson")
    with open(geojson, "w") as out:
        out.write('{"type": "LineString", "coordinates": [[2.2, -1], [2.2, 4]]}')
    outputs = {}
    for name, barrier in [("gpkg", lines), ("geojson", geojson)]:
        out = os.path.join(tmp, f"nn_{name}.csv")
        r = run("--samples", gpkg, "--method", "natural-neighbour", "--raster", "8x6", "--domain", "0,0,4,3",
                "--barriers", barrier, "--out", out)
        check(r.returncode == 0, f"GeoPackage samples with {name} barriers ({r.stderr.strip()})")
        outputs[name] = open(out).read() if r.returncode == 0 else None
    check(outputs["gpkg"] is not None and outputs["gpkg"] == outputs["geojson"], "OGR and GeoJSON barriers agree")
    # A source of several layers: the first is read, and a warning says so (it was silent).
    two = line_layer("two.gpkg", "LINESTRING (2.2 -1, 2.2 4)")
    ds = ogr.Open(two, 1)
    ds.CreateLayer("more", geom_type=ogr.wkbLineString)
    ds = None
    out = os.path.join(tmp, "nn_two.csv")
    r = run("--samples", gpkg, "--method", "natural-neighbour", "--raster", "8x6", "--domain", "0,0,4,3",
            "--barriers", two, "--out", out)
    check(r.returncode == 0 and "2 layers; the first, 'faults', is read" in r.stderr
          and open(out).read() == outputs["gpkg"], f"two layers: exit {r.returncode}, {r.stderr.strip()}")
    # A barrier beyond the largest coordinate is refused through OGR as through GeoJSON.
    far = line_layer("far.gpkg", "LINESTRING (2.2 -1, 2.2 1e200)")
    out = os.path.join(tmp, "nn_far.csv")
    r = run("--samples", gpkg, "--method", "natural-neighbour", "--raster", "8x6", "--domain", "0,0,4,3",
            "--barriers", far, "--out", out)
    check(r.returncode == 2 and "beyond the largest coordinate" in r.stderr and not os.path.exists(out),
          f"a barrier at 1e200 through OGR: exit {r.returncode}, {r.stderr.strip()}")
    out = os.path.join(tmp, "gpkg_linear.csv")
    r = run("--samples", gpkg, "--method", "linear", "--raster", "8x6", "--domain", "0,0,4,3", "--out", out)
    if check(r.returncode == 0, f"GeoPackage samples ({r.stderr.strip()})") is None and r.returncode == 0:
        rows = open(out).read().split()[1:]
        check(len(rows) == 48, f"{len(rows)} rows")
        for row in rows:
            x, y, v = map(float, row.split(","))
            check(abs(v - f(x, y)) < 1e-12 * 20, f"GeoPackage samples: value at ({x}, {y}) {v} vs {f(x, y)}")

    # A point layer that keeps x and y as fields beside its geometry (ogr2ogr from a CSV): those
    # fields are not interpolated (they would repeat the output's x, y columns), with a warning.
    xy = point_layer(os.path.join(tmp, "xy.gpkg"), "GPKG", "pts", 4, 3,
                     {"x": (ogr.OFTReal, lambda i, j: i), "y": (ogr.OFTReal, lambda i, j: j), "mag": (ogr.OFTReal, f)})
    out = os.path.join(tmp, "xy_linear.csv")
    r = subprocess.run([RADRECON, "interpolate", "--samples", xy, "--method", "linear", "--raster", "4x3", "--domain",
                        "0,0,3,2", "--out", out], capture_output=True, text=True)
    check(r.returncode == 0 and open(out).readline().strip() == "x,y,mag" and "the fields x, y are not interpolated" in r.stderr,
          f"x, y fields: exit {r.returncode}, {r.stderr.strip()}")

    # A WKT as gdalsrsinfo prints it, a new line first, and an EPSG code after a space: the white
    # space at the ends of --crs is dropped (both were refused).
    r = run("--samples", samples, "--value", "mag", "--method", "linear", "--raster", "4x3", "--domain", "0,0,4,3",
            "--crs", " EPSG:2193", "--out", os.path.join(tmp, "spaced.tif"))
    check(r.returncode == 0, f"--crs ' EPSG:2193': exit {r.returncode}, {r.stderr.strip()}")
    nztm = osr.SpatialReference()
    nztm.ImportFromEPSG(2193)
    wkt = "\n" + nztm.ExportToPrettyWkt() + "\n"
    out = os.path.join(tmp, "wkt.img")
    r = run("--samples", samples, "--value", "mag", "--method", "linear", "--raster", "4x3", "--domain", "0,0,4,3",
            "--crs", wkt, "--out", out)
    check(r.returncode == 0 and "New Zealand" in gdal.Open(out).GetProjection(), f"--crs '\\n WKT': exit {r.returncode}, {r.stderr.strip()}")

    # Refusals: exit 2, a message naming the option, nothing written.
    for args, words, name in [
        (["--crs", "EPSG:999999999"], "--crs", "bad.tif"),
        (["--nodata", "5"], "--nodata", "clash.tif"),  # f takes the value 5 at a cell centre
        (["--format", "NoSuchDriver"], "--format", "x.tif"),
        (["--type", "int8"], "--type", "t.tif"),
        ([], "unknown output extension", "x.nosuchext"),
        ([], "CALS driver writes bands of integers only", "x.cal"),  # lists no band types: it crashed the message
    ]:
        out = os.path.join(tmp, name)
        r = run("--samples", samples, "--value", "mag", "--method", "linear", "--raster", "4x3", "--domain",
                "0,0,4,3", "--out", out, *args)
        check(r.returncode == 2 and words in r.stderr, f"{args}: exit {r.returncode}, {r.stderr.strip()}")
        check(not os.path.exists(out), f"{args}: nothing written")
    # The extensions an unknown one is told of are those that write floats: not radrecon's own .png
    # again, nor .vrt, .jpg, .kml or .cal, each refused.
    r = run("--samples", samples, "--value", "mag", "--method", "linear", "--raster", "4x3", "--domain", "0,0,4,3",
            "--out", os.path.join(tmp, "x.nosuchext"))
    offered = r.stderr.split("through GDAL")[-1]
    check(all(f" {e}," not in offered and f" {e} " not in offered for e in [".png", ".vrt", ".jpg", ".kml", ".cal"])
          and " .tif," in offered and " .xyz," in offered, f"offered extensions: {offered.strip()}")
    # Nor the formats that fail for a raster of floats georeferenced by a geotransform (an outside
    # tester's trial: each was offered, and failed after the work), nor those that keep no
    # georeferencing. Every one offered writes such a raster, of 6 x 5 cells not square, without a
    # CRS: of two bands those offered for several, of one those offered for one value column.
    import re
    several, _, single = offered.partition("; of one value column also")
    several_exts = re.findall(r"\.[a-z0-9-]+", several.split("(or name")[0])
    single_exts = re.findall(r"\.[a-z0-9-]+", single.split("(or name")[0])
    check(not [e for e in [".ntf", ".ter", ".grb2", ".gsb", ".gvb", ".bag", ".sigdem", ".sg-grd-z", ".hf2", ".fits", ".xml",
                           ".lbl", ".cub", ".sdat", ".map", ".hdr"] if e in several_exts + single_exts]
          and ".asc" in single_exts and ".img" in several_exts, f"offered extensions: {offered.strip()}")
    two = os.path.join(tmp, "two_columns.csv")
    with open(two, "w") as out:
        out.write("x,y,a,b\n")
        for j in range(4):
            for i in range(5):
                out.write(f"{i},{j},{f(i, j)!r},{f(j, i)!r}\n")
    offered_dir = os.path.join(tmp, "offered")
    os.mkdir(offered_dir)
    for exts, source in [(several_exts, two), (single_exts, samples)]:
        for e in exts:
            out = os.path.join(offered_dir, "o" + e)
            r = run("--samples", source, *([] if source == two else ["--value", "mag"]), "--method", "linear",
                    "--raster", "6x5", "--domain", "0,0,4,3", "--out", out)
            check(r.returncode == 0 and "keeps no georeferencing" not in r.stderr,
                  f"offered {e}: exit {r.returncode}, {r.stderr.strip()}")
            if r.returncode == 0:
                d = gdal.Open(out)
                check(d.RasterCount == (2 if source == two else 1) and abs(d.GetGeoTransform()[0]) < 1e-9,
                      f"offered {e}: {d.RasterCount} bands, geotransform {d.GetGeoTransform()}")
    # A format known to fail for the run's raster is refused before the work (naming --out, not
    # the file GDAL failed on after it), saying why.
    for name, args, words in [
        ("o.hf2", [], "rounds the values"), ("o.sigdem", [], "integers of a fixed step"),
        ("o.gsb", [], "grid-shift files"), ("o.sg-grd-z", [], "does not write them"), ("o.ter", [], "MINUSERPIXELVALUE"),
        ("o.ntf", ["--crs", "EPSG:2193"], "geographic coordinates only"), ("o.grb2", [], "give --crs"),
        ("o.bag", ["--crs", "EPSG:4326"], "2 bands exactly"), ("o.sdat", [], "square pixels only"),
        ("o.asc", ["--value", "mag,depth"], "one band at most"), ("o.nc", ["--value", "mag,depth"], "separate variables"),
        ("o.x", ["--format", "hf2"], "rounds the values"),
    ]:
        out = os.path.join(offered_dir, "refused_" + name)
        r = run("--samples", samples, *([] if "--value" in args else ["--value", "mag"]), "--method", "linear",
                "--raster", "6x5", "--domain", "0,0,4,3", *args, "--out", out)
        check(r.returncode == 2 and "radrecon: error: --out" in r.stderr.replace("--format", "--out") and words in r.stderr
              and not os.path.exists(out), f"{name} {args}: exit {r.returncode}, {r.stderr.strip()}")
    # The same formats where they do write: NITF with a geographic CRS, SAGA of square pixels.
    for name, args in [("o.ntf", ["--crs", "EPSG:4326"]), ("o.sdat", [])]:
        out = os.path.join(offered_dir, "written_" + name)
        r = run("--samples", samples, "--value", "mag", "--method", "linear", "--raster", "8x6", "--domain", "0,0,4,3",
                *args, "--out", out)
        check(r.returncode == 0, f"{name} {args}: exit {r.returncode}, {r.stderr.strip()}")
    # A CRS that PROJ reads but GDAL refuses (a bare name) is refused for a GeoTIFF as for any format.
    for crs in ["WGS 84"]:
        out = os.path.join(tmp, "named.tif")
        r = run("--samples", samples, "--value", "mag", "--method", "linear", "--raster", "4x3", "--domain",
                "0,0,4,3", "--crs", crs, "--out", out)
        check(r.returncode == 2 and "--crs" in r.stderr and not os.path.exists(out),
              f"--crs '{crs}': exit {r.returncode}, {r.stderr.strip()}")
    # A value that only a Float32 band's rounding makes the no-data value is refused too.
    near = os.path.join(tmp, "near.csv")
    with open(near, "w") as out:
        out.write("x,y,v\n0,0,-9999.0001\n1,1,3\n")
    out = os.path.join(tmp, "near.tif")
    r = run("--samples", near, "--method", "constant", "--raster", "2x2", "--domain", "0,0,1,1", "--out", out)
    check(r.returncode == 2 and "--nodata" in r.stderr and not os.path.exists(out),
          f"-9999.0001 in a Float32 band: exit {r.returncode}, {r.stderr.strip()}")
    r = run("--samples", near, "--method", "constant", "--raster", "2x2", "--domain", "0,0,1,1", "--type", "float64",
            "--out", out)
    check(r.returncode == 0, f"-9999.0001 in a Float64 band is no clash ({r.stderr.strip()})")

    # Drivers of integer bands only would round the values without a word (GDAL converts): refused
    # before any work, nothing written.
    for name, extra, words in [("g.gif", [], "GIF driver writes bands of Byte only"),
                               ("g.xpm", [], "XPM driver writes bands of Byte only"),
                               ("g.data", ["--format", "PNG"], "PNG driver writes bands of Byte UInt16 only")]:
        out = os.path.join(tmp, name)
        r = run("--samples", samples, "--value", "mag", "--method", "linear", "--raster", "4x3", "--domain", "0,0,4,3",
                *extra, "--out", out)
        check(r.returncode == 2 and words in r.stderr and not os.path.exists(out),
              f"{name} {extra}: exit {r.returncode}, {r.stderr.strip()}")

    # Drivers that write no file of values, refused before any work (found by an outside-in
    # trial: each exited 0): MEM writes nothing, a VRT describes other rasters, KML super-overlays
    # are 8-bit colour tiles.
    for name, extra, words in [("m.tif", ["--format", "MEM"], "MEM driver keeps the raster in memory"),
                               ("v.vrt", [], "VRT driver writes a description of other rasters"),
                               ("k.kmz", [], "KMLSUPEROVERLAY driver writes 8-bit colour tiles")]:
        out = os.path.join(tmp, name)
        r = run("--samples", samples, "--value", "mag", "--method", "linear", "--raster", "4x3", "--domain", "0,0,4,3",
                *extra, "--out", out)
        check(r.returncode == 2 and words in r.stderr and not os.path.exists(out),
              f"{name} {extra}: exit {r.returncode}, {r.stderr.strip()}")

    # Read back before it is moved into place: a format that keeps no georeferencing (FITS) or
    # declares no no-data value (XYZ) is written with a warning saying so; one whose no-data value
    # is its own (Golden Software's ASCII grid) too. The values read back are what was written.
    for name, words in [("w.fits", "FITS driver keeps no georeferencing"),
                        ("w.xyz", "XYZ driver declares no no-data value"),
                        ("w.grd", "GSAG driver writes its own no-data value")]:
        out = os.path.join(tmp, name)
        r = run("--samples", samples, "--value", "mag", "--method", "linear", "--param", "outside=none", "--raster", "5x4",
                "--domain", "-1,-1,5,4", "--out", out)
        check(r.returncode == 0 and words in r.stderr and os.path.exists(out), f"{name}: exit {r.returncode}, {r.stderr.strip()}")

    # MRF compresses by PNG unless told otherwise, which refuses floating-point bands ("Can't
    # create"): written with DEFLATE, its values read back as written.
    out = os.path.join(tmp, "w.mrf")
    r = run("--samples", samples, "--value", "mag", "--method", "linear", "--raster", "5x4", "--domain", "0,0,4,3",
            "--out", out)
    check(r.returncode == 0 and os.path.exists(out), f"w.mrf: exit {r.returncode}, {r.stderr.strip()}")
    if r.returncode == 0:
        b = gdal.Open(out).ReadAsArray()
        check(abs(b[0, 0] - f(0.4, 2.625)) < 1e-5, f"w.mrf: the top-left cell {b[0, 0]}")

    # A --nodata that a 32-bit float cannot hold (0.1) is looked for as the band holds it. A GSAG
    # grid then writes the holes as the value 0.1 (not as its own no-data value), which would read
    # as data: refused, nothing written (it passed with exit 0).
    out = os.path.join(tmp, "n.grd")
    r = run("--samples", samples, "--value", "mag", "--method", "linear", "--param", "outside=none", "--raster", "5x4",
            "--domain", "-1,-1,5,4", "--nodata", "0.1", "--out", out)
    check(r.returncode == 2 and "does not keep the points without a value" in r.stderr and not os.path.exists(out),
          f"n.grd --nodata 0.1: exit {r.returncode}, {r.stderr.strip()}")

    # --nodata nan: the holes stay NaN and each band declares NaN, by radrecon's own GeoTIFF
    # writer and through GDAL alike; the values inside the hull are f's. A driver that cannot read
    # its own NaN back (XYZ) is refused with nothing written.
    for name, crs in [("nan.tif", "EPSG:2193"), ("nan_gdal.tif", "+proj=longlat +ellps=GRS80 +no_defs +type=crs"),
                      ("nan.nc", ""), ("nan.asc", "")]:
        out = os.path.join(tmp, name)
        r = run("--samples", samples, "--x", "long", "--y", "lat", "--value", "mag", "--method", "linear",
                "--param", "outside=none", "--raster", f"{W}x{H}", "--domain", domain, "--nodata", "nan",
                *(["--crs", crs] if crs else []), "--out", out)
        check(r.returncode == 0, f"{name} --nodata nan: exit {r.returncode}, {r.stderr.strip()}")
        if r.returncode != 0:
            continue
        o = gdal.Open(out)
        nd = o.GetRasterBand(1).GetNoDataValue()
        check(nd is not None and math.isnan(nd), f"{name}: declared no-data {nd}")
        b = o.GetRasterBand(1).ReadAsArray()
        holes = 0
        for row in range(H):
            y = y1 - (row + 0.5) * (y1 - y0) / H
            for col in range(W):
                x = x0 + (col + 0.5) * (x1 - x0) / W
                if 0 <= x <= 4 and 0 <= y <= 3:
                    check(abs(b[row, col] - f(x, y)) <= 1e-5 * 20, f"{name}: value at ({x}, {y}): {b[row, col]}")
                else:
                    holes += 1
                    check(math.isnan(b[row, col]), f"{name}: NaN outside the hull at ({x}, {y}): {b[row, col]}")
        check(holes > 0, f"{name}: holes")
    out = os.path.join(tmp, "nan.xyz")
    r = run("--samples", samples, "--value", "mag", "--method", "linear", "--param", "outside=none", "--raster", "5x4",
            "--domain", "-1,-1,5,4", "--nodata", "nan", "--out", out)
    check(r.returncode == 2 and "it may not read NaN" in r.stderr and not os.path.exists(out),
          f"nan.xyz: exit {r.returncode}, {r.stderr.strip()}")
    for bad in ["inf", "-inf"]:
        r = run("--samples", samples, "--value", "mag", "--method", "linear", "--raster", "4x3", "--domain", "0,0,4,3",
                "--nodata", bad, "--out", os.path.join(tmp, "inf.tif"))
        check(r.returncode == 2 and "--nodata: must be a finite number or nan" in r.stderr, f"--nodata {bad}: {r.stderr.strip()}")

    # A format's side file may not land on an input: ERS writes its data as the output's name
    # without the extension, here the samples' own file. Refused after the work, nothing moved,
    # the samples intact.
    bare = os.path.join(tmp, "survey")
    shutil.copyfile(samples, bare)
    before = open(bare, "rb").read()
    r = run("--samples", bare, "--value", "mag", "--method", "linear", "--raster", "4x3", "--domain", "0,0,4,3",
            "--out", bare + ".ers")
    check(r.returncode == 2 and "is the input file" in r.stderr and not os.path.exists(bare + ".ers")
          and open(bare, "rb").read() == before, f"survey.ers: exit {r.returncode}, {r.stderr.strip()}")

    # Nor on a file of a vector source: a shapefile's .prj beside the .shp, which the EHdr (.bil)
    # driver writes under the output's name when given a CRS. Refused, the .prj intact.
    wgs84 = osr.SpatialReference()
    wgs84.ImportFromEPSG(4326)
    shp = point_layer(os.path.join(tmp, "pts.shp"), "ESRI Shapefile", "pts", 4, 3, {"mag": (ogr.OFTReal, f)}, wgs84)
    prj = os.path.join(tmp, "pts.prj")
    before = open(prj, "rb").read()
    r = run("--samples", shp, "--value", "mag", "--method", "linear", "--raster", "4x3", "--domain", "0,0,3,2",
            "--crs", "EPSG:2193", "--out", os.path.join(tmp, "pts.bil"))
    check(r.returncode == 2 and "pts.prj" in r.stderr and not os.path.exists(os.path.join(tmp, "pts.bil"))
          and open(prj, "rb").read() == before, f"pts.bil beside pts.shp: exit {r.returncode}, {r.stderr.strip()}")

    # netCDF stores two value columns as two variables, not two bands of one raster: refused with
    # formats that keep several bands as the advice, nothing written.
    out = os.path.join(tmp, "two.nc")
    r = run("--samples", samples, "--x", "long", "--y", "lat", "--method", "linear", "--raster", "4x3", "--domain",
            "0,0,4,3", "--out", out)
    check(r.returncode == 2 and "separate variables" in r.stderr and "write .tif, .img" in r.stderr
          and not os.path.exists(out), f"two.nc: exit {r.returncode}, {r.stderr.strip()}")
    # Beyond the range of 32-bit floats a float32 band holds infinity (kept above): a --nodata
    # there would be infinity too, and is refused before the work; a format that cannot hold
    # infinity (the Arc/Info grid writes the largest float) is refused saying so, with the formats
    # that can. --type float64 keeps the value in a GeoTIFF.
    r = run("--samples", samples, "--value", "mag", "--method", "linear", "--raster", "4x3", "--domain", "0,0,4,3",
            "--nodata", "1e39", "--out", os.path.join(tmp, "n39.tif"))
    check(r.returncode == 2 and "--nodata: 1e+39 is beyond the range of 32-bit floats" in r.stderr,
          f"--nodata 1e39: exit {r.returncode}, {r.stderr.strip()}")
    r = run("--samples", huge, "--method", "constant", "--raster", "2x2", "--domain", "0,0,1,1",
            "--out", os.path.join(tmp, "huge.asc"))
    check(r.returncode == 2 and "beyond a 32-bit float's range is infinity" in r.stderr and "write .tif, .nc" in r.stderr
          and not os.path.exists(os.path.join(tmp, "huge.asc")), f"huge.asc: exit {r.returncode}, {r.stderr.strip()}")
    r = run("--samples", huge, "--method", "constant", "--raster", "2x2", "--domain", "0,0,1,1", "--type", "float64",
            "--crs", "EPSG:2193", "--out", os.path.join(tmp, "huge64.tif"))
    check(r.returncode == 0 and gdal.Open(os.path.join(tmp, "huge64.tif")).ReadAsArray()[1][0] == 1e39,
          f"huge64.tif: exit {r.returncode}, {r.stderr.strip()}")

    # The lowest float as numpy prints it rounds to the lowest float, no infinity: accepted.
    r = run("--samples", samples, "--value", "mag", "--method", "linear", "--raster", "4x3", "--domain", "0,0,4,3",
            "--nodata", "-3.4028235e38", "--out", os.path.join(tmp, "lowest.tif"))
    check(r.returncode == 0, f"--nodata -3.4028235e38: exit {r.returncode}, {r.stderr.strip()}")
    # An Arc/Info grid lists no Float64 band among its creation types, yet writes a Float64 band's
    # values in full: --type float64 is no refusal there.
    out = os.path.join(tmp, "g64.asc")
    r = run("--samples", samples, "--value", "mag", "--method", "linear", "--raster", "4x3", "--domain", "0,0,4,3",
            "--type", "float64", "--out", out)
    check(r.returncode == 0 and os.path.exists(out), f"g64.asc --type float64: exit {r.returncode}, {r.stderr.strip()}")

finish()
