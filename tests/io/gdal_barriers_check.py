"""Barriers from GDAL vector sources (GeoPackage, shapefile) are held to the rules of GeoJSON's
(core/barrier_line.h): an unclosed ring, a ring of fewer than 4 points, a line of fewer than 2, a
segment of zero length and an empty Polygon are refused, exit 2, naming the file, the layer, the
feature and the part. (An unclosed ring was read as an open line, GDAL's warning aside: the region
it encloses leaked; the others were named "barrier N", a count of lines, not of features.)
Run as `gdal_barriers_check.py RADRECON`; exit 77 without python3-gdal."""
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gdal_check_support import check, finish, run  # noqa: E402 (exits 77 without python3-gdal)
from osgeo import ogr  # noqa: E402

ogr.UseExceptions()


def vector(path, wkts, driver="GPKG", layer_name="walls", geom_type=ogr.wkbUnknown):
    """A vector source of one layer, a feature per WKT (None: a feature without a geometry)."""
    ds = ogr.GetDriverByName(driver).CreateDataSource(path)
    layer = ds.CreateLayer(layer_name, geom_type=geom_type)
    for wkt in wkts:
        feature = ogr.Feature(layer.GetLayerDefn())
        if wkt is not None:
            feature.SetGeometry(ogr.CreateGeometryFromWkt(wkt))
        layer.CreateFeature(feature)
    ds = None
    return path


WALL = "LINESTRING (0 0.5, 0.1 0.5)"  # a valid first feature, so that the bad one is not the first
OPEN_RING = "POLYGON ((0.2 0.2, 0.8 0.2, 0.8 0.8, 0.2 0.8))"  # GDAL reads it unclosed


with tempfile.TemporaryDirectory() as tmp:
    samples = os.path.join(tmp, "samples.csv")
    with open(samples, "w") as out:
        out.write("x,y,v\n")
        for j in range(5):
            for i in range(5):
                out.write(f"{i / 4},{j / 4},{i + 10 * j}\n")
    queries = os.path.join(tmp, "queries.csv")
    with open(queries, "w") as out:
        out.write("x,y\n0.5,0.5\n0.9,0.9\n")

    def interpolate(barriers, out_name):
        out = os.path.join(tmp, out_name)
        r = run("--samples", samples, "--queries", queries, "--method", "shepard", "--barriers", barriers, "--out", out)
        return r, out

    def refused(name, barriers, message):
        """Refused with exit 2 and exactly `message` after the file's name; nothing written."""
        r, out = interpolate(barriers, name + ".csv")
        expected = f"radrecon: error: {barriers}: {message}"
        check(r.returncode == 2 and r.stderr.strip() == expected and not os.path.exists(out),
              f"{name}: exit {r.returncode}, stderr {r.stderr.strip()!r}, expected {expected!r}")

    def geojson(name, geometry):
        path = os.path.join(tmp, name)
        with open(path, "w") as out:
            out.write('{"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {}, '
                      '"geometry": ' + geometry + '}]}')
        return path

    # --- polygon rings ----------------------------------------------------------------------------
    # An unclosed ring: refused as GeoJSON refuses it (it was used as an open line, the square's
    # left side missing).
    refused("open_ring", vector(os.path.join(tmp, "open_ring.gpkg"), [WALL, OPEN_RING]),
            "layer 'walls', feature 2, ring 1: a Polygon ring must be closed: its last point [0.2, 0.8] must "
            "repeat its first [0.2, 0.2]")
    r, _ = interpolate(geojson("open_ring.geojson", '{"type": "Polygon", "coordinates": '
                               '[[[0.2, 0.2], [0.8, 0.2], [0.8, 0.8], [0.2, 0.8]]]}'), "open_ring_geojson.csv")
    check(r.returncode == 2 and "a Polygon ring must be closed" in r.stderr, f"the same ring in GeoJSON: {r.stderr.strip()}")
    # A hole left open; the second polygon of a MultiPolygon: the part is named.
    refused("open_hole", vector(os.path.join(tmp, "open_hole.gpkg"),
                                ["POLYGON ((0 0, 1 0, 1 1, 0 1, 0 0), (0.2 0.2, 0.8 0.2, 0.8 0.8, 0.2 0.8))"]),
            "layer 'walls', feature 1, ring 2: a Polygon ring must be closed: its last point [0.2, 0.8] must "
            "repeat its first [0.2, 0.2]")
    refused("open_multipolygon", vector(os.path.join(tmp, "open_multi.gpkg"),
                                        ["MULTIPOLYGON (((0 0, 0.1 0, 0.1 0.1, 0 0)), ((0.5 0.5, 0.9 0.5, 0.9 0.9, 0.5 0.9)))"]),
            "layer 'walls', feature 1, polygon 2, ring 1: a Polygon ring must be closed: its last point [0.5, 0.9] "
            "must repeat its first [0.5, 0.5]")
    # A closed ring of 3 points (there and back): refused as from GeoJSON.
    refused("ring_of_3", vector(os.path.join(tmp, "ring3.gpkg"), [WALL, "POLYGON ((0.2 0.2, 0.8 0.2, 0.2 0.2))"]),
            "layer 'walls', feature 2, ring 1: a Polygon ring needs at least 4 points (a closed triangle), it has 3")
    r, _ = interpolate(geojson("ring3.geojson", '{"type": "Polygon", "coordinates": [[[0.2, 0.2], [0.8, 0.2], [0.2, 0.2]]]}'),
                       "ring3_geojson.csv")
    check(r.returncode == 2 and "a Polygon ring needs at least 4 positions" in r.stderr, f"the same in GeoJSON: {r.stderr.strip()}")
    # A shapefile keeps the ring unclosed too (its writer reverses it), and GDAL warns as it reads
    # it: only radrecon's refusal is printed, not GDAL's advice to set a configuration option.
    # (A shapefile's features count from 0.)
    refused("open_ring_shp", vector(os.path.join(tmp, "rooms.shp"), [OPEN_RING], "ESRI Shapefile", "rooms", ogr.wkbPolygon),
            "layer 'rooms', feature 0, ring 1: a Polygon ring must be closed: its last point [0.2, 0.2] must repeat "
            "its first [0.2, 0.8]")
    # A Polygon without rings (GeoJSON's "coordinates": [] is refused): not silently nothing.
    refused("empty_polygon", vector(os.path.join(tmp, "empty_polygon.gpkg"), [WALL, "POLYGON EMPTY"]),
            "layer 'walls', feature 2: an empty Polygon (no ring)")
    refused("empty_in_multipolygon", vector(os.path.join(tmp, "empty_in_multi.gpkg"),
                                            ["MULTIPOLYGON (((0 0, 0.1 0, 0.1 0.1, 0 0)), EMPTY)"]),
            "layer 'walls', feature 1, polygon 2: an empty Polygon (no ring)")

    # --- lines: the feature named, not the count of lines read ("barrier 5, points 1 and 2
    # coincide at (0.7, 0.7)") -------------------------------------------------------------------
    refused("zero_length", vector(os.path.join(tmp, "zero.gpkg"), [WALL, "LINESTRING (0 0, 0.7 0.7, 0.7 0.7, 1 1)"]),
            "layer 'walls', feature 2, point 3: repeats the point before it, [0.7, 0.7]: a segment of zero length")
    refused("zero_length_multiline", vector(os.path.join(tmp, "zero_multi.gpkg"),
                                            [WALL, "MULTILINESTRING ((0 0, 1 0), (0 1, 0.5 1, 0.5 1))"]),
            "layer 'walls', feature 2, line 2, point 3: repeats the point before it, [0.5, 1]: a segment of zero length")
    refused("zero_length_ring", vector(os.path.join(tmp, "zero_ring.gpkg"),
                                       ["POLYGON ((0 0, 1 0, 1 0, 1 1, 0 0))"]),
            "layer 'walls', feature 1, ring 1, point 3: repeats the point before it, [1, 0]: a segment of zero length")
    refused("one_point", vector(os.path.join(tmp, "one_point.gpkg"), [WALL, "LINESTRING (0.5 0.5)"]),
            "layer 'walls', feature 2: a LineString needs at least 2 points, it has 1")
    refused("empty_line", vector(os.path.join(tmp, "empty_line.gpkg"), [WALL, WALL, "LINESTRING EMPTY"]),
            "layer 'walls', feature 3: a LineString needs at least 2 points, it has 0")
    refused("one_point_multiline", vector(os.path.join(tmp, "one_point_multi.gpkg"),
                                          ["MULTILINESTRING ((0 0, 1 0), (0.5 0.5))"]),
            "layer 'walls', feature 1, line 2: a LineString needs at least 2 points, it has 1")
    refused("zero_length_shp", vector(os.path.join(tmp, "faults.shp"), [WALL, "LINESTRING (0 0, 0.7 0.7, 0.7 0.7, 1 1)"],
                                      "ESRI Shapefile", "faults", ogr.wkbLineString),
            "layer 'faults', feature 1, point 3: repeats the point before it, [0.7, 0.7]: a segment of zero length")
    refused("one_point_shp", vector(os.path.join(tmp, "short.shp"), [WALL, "LINESTRING (0.5 0.5)"],
                                    "ESRI Shapefile", "short", ogr.wkbLineString),
            "layer 'short', feature 1: a LineString needs at least 2 points, it has 1")
    # A coordinate beyond the largest: the part and point named as above.
    refused("far_point", vector(os.path.join(tmp, "far.gpkg"), ["MULTILINESTRING ((0 0, 1 0), (0 1, 0.5 1e200))"]),
            "layer 'walls', feature 1, line 2, point 2: not finite or beyond the largest coordinate, 1e+100")

    # --- what is accepted: closed rings (a hole too), an empty MultiLineString and a feature
    # without a geometry (none holds a line), giving what the same lines from GeoJSON give ----------
    good = vector(os.path.join(tmp, "good.gpkg"),
                  ["POLYGON ((0.3 0.3, 0.7 0.3, 0.7 0.7, 0.3 0.7, 0.3 0.3), (0.4 0.4, 0.6 0.4, 0.6 0.6, 0.4 0.6, 0.4 0.4))",
                   "MULTILINESTRING EMPTY", None, "LINESTRING (0.8 0, 0.8 1)"])
    same = geojson("good.geojson", '{"type": "GeometryCollection", "geometries": ['
                   '{"type": "Polygon", "coordinates": [[[0.3, 0.3], [0.7, 0.3], [0.7, 0.7], [0.3, 0.7], [0.3, 0.3]], '
                   '[[0.4, 0.4], [0.6, 0.4], [0.6, 0.6], [0.4, 0.6], [0.4, 0.4]]]}, '
                   '{"type": "LineString", "coordinates": [[0.8, 0], [0.8, 1]]}]}')
    r_gpkg, out_gpkg = interpolate(good, "good_gpkg.csv")
    r_json, out_json = interpolate(same, "good_geojson.csv")
    check(r_gpkg.returncode == 0 and r_json.returncode == 0 and r_gpkg.stderr == "" and
          open(out_gpkg).read() == open(out_json).read(),
          f"closed rings: exit {r_gpkg.returncode} ({r_gpkg.stderr.strip()}) and {r_json.returncode} ({r_json.stderr.strip()})")

finish()
