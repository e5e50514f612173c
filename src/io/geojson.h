#pragma once
// Barrier files (docs/formats.md): the barrier lines of `interpolate --barriers`, read from a
// GeoJSON file (RFC 7946).

#include <string>
#include <vector>

#include "core/vec.h"
#include "reconstruct/barriers.h"

namespace radrecon {

/// The barrier polylines of a GeoJSON file (RFC 7946), in document order: the file holds one
/// geometry, a Feature or a FeatureCollection; the geometries are LineString (one polyline),
/// MultiLineString (one per line), Polygon and MultiPolygon (one closed polyline per ring, its
/// first point repeated at its end as in the file, holes included) or GeometryCollection (its
/// members, recursively). Positions are [x, y] or longer ([x, y, z, ...]): only x and y are
/// read, as metres of the sample domain ("crs", "bbox" and other members are ignored). A
/// Feature whose geometry is null contributes no line.
///
/// Refused with a UserError naming the file and the field path
/// ("b.geojson: features[3].geometry.coordinates[0][2]: expected a position [x, y]"), or the
/// line for invalid JSON: a file that cannot be read, is empty or holds no barrier line; an
/// object without "type" or of a type not listed above; a Point or MultiPoint (a point cannot
/// be a barrier); a LineString of fewer than 2 positions; a Polygon without rings, or a ring of
/// fewer than 4 positions or not closed; a position repeating the one before it (a segment of
/// zero length); a coordinate that is not a number, or beyond tol::kMaxSampleCoordinate. The
/// rules of one line are barrier_line_defect()'s (core/barrier_line.h), shared with GDAL's sources.
/// What is returned therefore always passes Barriers::from_polylines().
std::vector<Polyline> read_geojson_barriers(const std::string& path);

/// Barrier lines from a file: .geojson and .json by read_geojson_barriers(), any other vector
/// source (GeoPackage, Shapefile, ...) through GDAL's OGR (io/gdal_plugin.h; `where` names the
/// option or argument if GDAL cannot be loaded). UserError naming the file when it holds no
/// valid barriers.
Barriers read_barriers_file(const std::string& path, const std::string& where);

}  // namespace radrecon
