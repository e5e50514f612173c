#!/usr/bin/env python3
"""interpolate's samples from OGR vector sources as a gdal_grid user brings them (an outside-in
trial's findings): a CSV's columns through a VRT (text to OGR), the points' z as the values,
MultiPoints, a shapefile's FID and Boolean fields left out, the layer's CRS carried to the
GeoTIFF, a barrier layer in another CRS, an empty layer, the bands named after their value
columns. Values are checked against the closed
form of a linear function, which `linear` reproduces exactly inside the samples' hull.

Usage: gdal_vector_check.py /path/to/radrecon   (exit 77: python3-gdal or gdalinfo missing)
"""
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gdal_check_support import check, f, finish, gdal, osr, run, write_samples  # noqa: E402
from osgeo import ogr  # noqa: E402


def layer(path, points, fields, srs_epsg=None, geom_type=ogr.wkbPoint, driver="GPKG"):
    """A vector source of one layer: `points` a list of (WKT, {field: value}), `fields` (name, OGR type)."""
    srs = None
    if srs_epsg is not None:
        srs = osr.SpatialReference()
        srs.ImportFromEPSG(srs_epsg)
    ds = ogr.GetDriverByName(driver).CreateDataSource(path)
    lay = ds.CreateLayer("pts", srs=srs, geom_type=geom_type)
    for name, kind in fields:
        definition = ogr.FieldDefn(name, kind[0] if isinstance(kind, tuple) else kind)
        if isinstance(kind, tuple):
            definition.SetSubType(kind[1])
        lay.CreateField(definition)
    for wkt, values in points:
        feature = ogr.Feature(lay.GetLayerDefn())
        feature.SetGeometry(ogr.CreateGeometryFromWkt(wkt))
        for name, value in values.items():
            feature.SetField(name, value)
        lay.CreateFeature(feature)
    ds = None
    return path


def values_of(csv_path):
    """The rows of an output CSV as (x, y, v...) tuples."""
    rows = open(csv_path).read().split()[1:]
    return [tuple(map(float, row.split(","))) for row in rows]


def exact(csv_path, g, what):
    """Every row's value equals g(x, y) to rounding."""
    rows = values_of(csv_path)
    check(len(rows) > 0 and all(abs(v[2] - g(v[0], v[1])) <= 1e-9 * (1 + abs(g(v[0], v[1]))) for v in rows),
          f"{what}: values against the closed form ({rows[:2]})")


GRID = [(i, j) for j in range(4) for i in range(5)]

with tempfile.TemporaryDirectory() as tmp:
    def path(name):
        return os.path.join(tmp, name)

    # A CSV through a VRT, gdal_grid's recipe: every column is text to OGR. It was refused
    # ("has no numeric field ... name one with --value", then "field mag is not numeric").
    with open(path("quake.csv"), "w") as out:
        out.write("long,lat,mag\n" + "".join(f"{i},{j},{f(i, j)!r}\n" for i, j in GRID))
    with open(path("quake.vrt"), "w") as out:
        out.write('<OGRVRTDataSource><OGRVRTLayer name="quake"><SrcDataSource relativeToVRT="1">quake.csv</SrcDataSource>'
                  '<GeometryType>wkbPoint</GeometryType><GeometryField encoding="PointFromColumns" x="long" y="lat"/>'
                  '</OGRVRTLayer></OGRVRTDataSource>')
    for extra in ([], ["--value", "mag"]):
        out = path(f"vrt{len(extra)}.csv")
        r = run("--samples", path("quake.vrt"), *extra, "--method", "linear", "--raster", "8x6", "--domain", "0,0,4,3",
                "--out", out)
        check(r.returncode == 0, f"a VRT's text columns {extra}: exit {r.returncode}, {r.stderr.strip()}")
        if r.returncode == 0:
            check(open(out).readline().strip() == "x,y,mag", f"the value column is mag ({open(out).readline().strip()})")
            exact(out, f, f"VRT {extra}")

    # Text that is not a number in one feature: the refusal names that feature, not the first.
    mixed = layer(path("mixed.gpkg"), [(f"POINT ({i} {j})", {"depth": "n/a" if (i, j) == (2, 1) else str(f(i, j))})
                                       for i, j in GRID], [("depth", ogr.OFTString)])
    bad_fid = 1 + GRID.index((2, 1))  # a GeoPackage counts its features from 1
    r = run("--samples", mixed, "--method", "linear", "--raster", "4x3", "--domain", "0,0,4,3", "--out", path("m.csv"))
    check(r.returncode == 2 and f"depth (String: feature {bad_fid} holds 'n/a')" in r.stderr and not os.path.exists(path("m.csv")),
          f"mixed text, default: exit {r.returncode}, {r.stderr.strip()}")
    r = run("--samples", mixed, "--value", "depth", "--method", "linear", "--raster", "4x3", "--domain", "0,0,4,3",
            "--out", path("m.csv"))
    check(r.returncode == 2 and f"feature {bad_fid}: field depth: 'n/a' is not a finite number" in r.stderr,
          f"mixed text, --value: exit {r.returncode}, {r.stderr.strip()}")

    # Points with z, as gdal_grid reads them: z is the value by default; a numeric field beside it
    # is not interpolated (a note says so); --value names a field instead, --value z the z.
    z = layer(path("z.gpkg"), [(f"POINT Z ({500000 + 100 * i} {5500000 + 100 * j} {f(i, j)!r})", {"depth": 10.0 + i})
                               for i, j in GRID],
              [("depth", ogr.OFTReal)], srs_epsg=32633, geom_type=ogr.wkbPoint25D)
    domain = "500000,5500000,500400,5500300"
    def utm(x, y):
        return f((x - 500000) / 100, (y - 5500000) / 100)
    r = run("--samples", z, "--method", "linear", "--raster", "8x6", "--domain", domain, "--out", path("z.csv"))
    check(r.returncode == 0 and "the values are the points' z" in r.stderr and "fields depth are not interpolated" in r.stderr,
          f"z by default: exit {r.returncode}, {r.stderr.strip()}")
    if r.returncode == 0:
        check(open(path("z.csv")).readline().strip() == "x,y,z", "the value column is z")
        exact(path("z.csv"), utm, "z")
    r = run("--samples", z, "--value", "depth", "--method", "linear", "--raster", "8x6", "--domain", domain, "--out", path("d.csv"))
    check(r.returncode == 0, f"--value depth beside z: exit {r.returncode}, {r.stderr.strip()}")
    if r.returncode == 0:
        exact(path("d.csv"), lambda x, y: 10 + (x - 500000) / 100, "--value depth")
    r = run("--samples", z, "--value", "z,depth", "--method", "linear", "--raster", "8x6", "--domain", domain, "--out", path("zd.csv"))
    check(r.returncode == 0 and open(path("zd.csv")).readline().strip() == "x,y,z,depth", f"--value z,depth: exit {r.returncode}, {r.stderr.strip()}")

    # The layer's CRS goes to the GeoTIFF (it had none), read back by GDAL; --crs overrides it.
    r = run("--samples", z, "--method", "linear", "--raster", "8x6", "--domain", domain, "--out", path("z.tif"))
    if check(r.returncode == 0, f"z to GeoTIFF: exit {r.returncode}, {r.stderr.strip()}") is None and r.returncode == 0:
        srs = osr.SpatialReference(wkt=gdal.Open(path("z.tif")).GetProjection())
        check(srs.GetAuthorityCode(None) == "32633", f"the samples' CRS carried: {srs.GetAuthorityCode(None)}")
    r = run("--samples", z, "--method", "linear", "--raster", "8x6", "--domain", domain, "--crs", "EPSG:2193",
            "--out", path("z2193.tif"))
    check(r.returncode == 0 and osr.SpatialReference(wkt=gdal.Open(path("z2193.tif")).GetProjection()).GetAuthorityCode(None) == "2193",
          f"--crs over the layer's: exit {r.returncode}")

    # Every z the same (a PointZ shapefile of z = 0, as exporters write them) beside a numeric field:
    # the field is interpolated, with a warning (the z made a flat raster: a review).
    flat = layer(path("flat.gpkg"), [(f"POINT Z ({i} {j} 0)", {"depth": f(i, j)}) for i, j in GRID],
                 [("depth", ogr.OFTReal)], geom_type=ogr.wkbPoint25D)
    r = run("--samples", flat, "--method", "linear", "--raster", "8x6", "--domain", "0,0,4,3", "--out", path("flat.csv"))
    check(r.returncode == 0 and "every point's z is 0: the numeric fields depth are interpolated instead" in r.stderr,
          f"flat z: exit {r.returncode}, {r.stderr.strip()}")
    if r.returncode == 0:
        exact(path("flat.csv"), f, "flat z: depth")
    # A text field of numbers but in one feature, beside a numeric field: said not to be interpolated.
    both = layer(path("both.gpkg"), [(f"POINT ({i} {j})", {"mag": f(i, j), "depth": "n/a" if (i, j) == (1, 1) else "3"})
                                     for i, j in GRID], [("mag", ogr.OFTReal), ("depth", ogr.OFTString)])
    r = run("--samples", both, "--method", "linear", "--raster", "8x6", "--domain", "0,0,4,3", "--out", path("both.csv"))
    check(r.returncode == 0 and "the text field depth is not interpolated: feature" in r.stderr,
          f"a text field of numbers but one: exit {r.returncode}, {r.stderr.strip()}")

    # Points from fields (--x, --y): the layer's CRS is its geometry's, not theirs; none is carried.
    xyf = layer(path("xyf.gpkg"), [(f"POINT ({15 + 0.001 * i} {49 + 0.001 * j})", {"e": 500000.0 + 100 * i, "n": 5500000.0 + 100 * j,
                                                                                 "mag": f(i, j)}) for i, j in GRID],
                [("e", ogr.OFTReal), ("n", ogr.OFTReal), ("mag", ogr.OFTReal)], srs_epsg=4326)
    r = run("--samples", xyf, "--x", "e", "--y", "n", "--value", "mag", "--method", "linear", "--raster", "8x6",
            "--domain", domain, "--out", path("xyf.tif"))
    check(r.returncode == 0 and gdal.Open(path("xyf.tif")).GetProjection() == "",
          f"--x/--y fields: no CRS carried: exit {r.returncode}, {r.stderr.strip()}")

    # GeoJSON: a "crs" member it names is carried; without one (GDAL's implicit WGS 84), none.
    for name, crs_member, want in [("named.geojson", ', "crs": {"type": "name", "properties": {"name": "urn:ogc:def:crs:EPSG::32633"}}', "32633"),
                                   ("plain.geojson", "", None)]:
        features = ", ".join(f'{{"type": "Feature", "properties": {{"mag": {f(i, j)!r}}}, "geometry": {{"type": "Point", '
                             f'"coordinates": [{500000 + 100 * i}, {5500000 + 100 * j}]}}}}' for i, j in GRID)
        with open(path(name), "w") as out:
            out.write('{"type": "FeatureCollection"' + crs_member + ', "features": [' + features + "]}")
        tif = path(name + ".tif")
        r = run("--samples", path(name), "--method", "linear", "--raster", "8x6", "--domain", domain, "--out", tif)
        got = osr.SpatialReference(wkt=gdal.Open(tif).GetProjection()).GetAuthorityCode(None) if r.returncode == 0 else "failed"
        check(got == want, f"{name}: CRS {got}, expected {want} ({r.stderr.strip()})")

    # A barrier layer in another CRS than the samples': a warning (coordinates are not reprojected).
    wall = layer(path("wall.gpkg"), [("LINESTRING (500250 5499000, 500250 5501000)", {})], [], srs_epsg=4326,
                 geom_type=ogr.wkbLineString)
    r = run("--samples", z, "--method", "natural-neighbour", "--barriers", wall, "--raster", "8x6", "--domain", domain,
            "--out", path("w.csv"))
    check(r.returncode == 0 and "declare different CRSs" in r.stderr, f"barriers in another CRS: exit {r.returncode}, {r.stderr.strip()}")
    same = layer(path("same.gpkg"), [("LINESTRING (500250 5499000, 500250 5501000)", {})], [], srs_epsg=32633,
                 geom_type=ogr.wkbLineString)
    r = run("--samples", z, "--method", "natural-neighbour", "--barriers", same, "--raster", "8x6", "--domain", domain,
            "--out", path("w2.csv"))
    check(r.returncode == 0 and "different CRSs" not in r.stderr, f"barriers in the same CRS: {r.stderr.strip()}")

    # A shapefile with the FID field ogr2ogr adds: the FID was interpolated, in silence.
    shp = layer(path("fid.shp"), [(f"POINT ({i} {j})", {"FID": k, "mag": f(i, j)}) for k, (i, j) in enumerate(GRID)],
                [("FID", ogr.OFTInteger), ("mag", ogr.OFTReal)], driver="ESRI Shapefile")
    r = run("--samples", shp, "--method", "linear", "--raster", "8x6", "--domain", "0,0,4,3", "--out", path("fid.csv"))
    check(r.returncode == 0 and open(path("fid.csv")).readline().strip() == "x,y,mag"
          and "the field FID is not interpolated: numbering the features" in r.stderr, f"FID: exit {r.returncode}, {r.stderr.strip()}")
    if r.returncode == 0:
        exact(path("fid.csv"), f, "a shapefile with an FID")

    # A GeoPackage's id and a Boolean field are not interpolated, with a warning naming them.
    flags = layer(path("flags.gpkg"), [(f"POINT ({i} {j})", {"id": k, "wet": k % 2, "mag": f(i, j)}) for k, (i, j) in enumerate(GRID)],
                  [("id", ogr.OFTInteger), ("wet", (ogr.OFTInteger, ogr.OFSTBoolean)), ("mag", ogr.OFTReal)])
    r = run("--samples", flags, "--method", "linear", "--raster", "8x6", "--domain", "0,0,4,3", "--out", path("flags.csv"))
    check(r.returncode == 0 and open(path("flags.csv")).readline().strip() == "x,y,mag"
          and "the field id is not interpolated: numbering the features" in r.stderr
          and "the field wet is not interpolated: Boolean" in r.stderr, f"id and Boolean: exit {r.returncode}, {r.stderr.strip()}")

    # MultiPoints: each point a sample (they were refused).
    multi = layer(path("multi.gpkg"), [(f"MULTIPOINT (({i} {j}), ({i + 0.5} {j + 0.5}))", {"v": 0.0}) for i, j in GRID],
                  [("v", ogr.OFTReal)], geom_type=ogr.wkbMultiPoint)
    r = run("--samples", multi, "--method", "constant", "--queries", multi, "--out", path("multi.csv"))
    check(r.returncode == 0 and len(values_of(path("multi.csv"))) == 2 * len(GRID),
          f"MultiPoint: exit {r.returncode}, {r.stderr.strip()}")

    # An empty layer is said to be empty, GeoJSON as GeoPackage (GeoJSON's read "has no numeric field").
    with open(path("empty.geojson"), "w") as out:
        out.write('{"type": "FeatureCollection", "features": []}')
    empty = layer(path("empty.gpkg"), [], [("v", ogr.OFTReal)])
    for source in (path("empty.geojson"), empty):
        r = run("--samples", source, "--method", "linear", "--raster", "4x3", "--domain", "0,0,4,3", "--out", path("e.csv"))
        check(r.returncode == 2 and "has no features" in r.stderr, f"{os.path.basename(source)}: exit {r.returncode}, {r.stderr.strip()}")

    # A CSV whose coordinates are named lat and lon, lat first: x is lon (it was lat).
    with open(path("ll.csv"), "w") as out:
        out.write("lat,lon,elev\n" + "".join(f"{j!r},{i!r},{f(i, j)!r}\n" for i, j in GRID))
    r = run("--samples", path("ll.csv"), "--method", "linear", "--raster", "8x6", "--domain", "0,0,4,3", "--out", path("ll_out.csv"))
    check(r.returncode == 0, f"lat,lon: exit {r.returncode}, {r.stderr.strip()}")
    if r.returncode == 0:
        exact(path("ll_out.csv"), f, "lat,lon columns")

    # Each band named after its value column (they had no description: an outside-in trial), by
    # radrecon's own GeoTIFF writer (no CRS) and by GDAL's (a PROJ string; ERDAS .img).
    samples = write_samples(tmp)
    for name, extra in [("both.tif", []), ("both_proj.tif", ["--crs", "+proj=utm +zone=33 +datum=WGS84"]), ("both.img", [])]:
        out = os.path.join(tmp, name)
        r = run("--samples", samples, "--method", "linear", "--raster", "5x4", "--domain", "0,0,4,3", *extra, "--out", out)
        opened = gdal.Open(out) if r.returncode == 0 else None  # held: its bands die with it
        names = [opened.GetRasterBand(b).GetDescription() for b in (1, 2)] if opened else None
        check(names == ["mag", "depth"], f"{name}: band descriptions {names} ({r.stderr.strip()})")

finish()
