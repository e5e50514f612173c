#pragma once
// Samples, query points and barrier lines from any vector source GDAL's OGR reads: GeoPackage,
// Shapefile, GeoJSON, FlatGeobuf, GML, KML, ... (`ogrinfo --formats`). The first layer is read.
// Samples and queries: each feature's point geometry is (x, y), or the fields --x and --y name;
// the values are the numeric fields --value names, else every numeric field but the coordinates'
// (those --x and --y name, and fields named x or y).
// Barriers: LineString and MultiLineString features, and the rings of Polygon and MultiPolygon
// features. Coordinates are taken as they are stored (no reprojection). These functions live in
// the GDAL plugin (io/gdal_plugin.h); the program calls them through gdal_functions().

#include <string>
#include <vector>

#include "io/samples_csv.h"

namespace radrecon {

/// The samples of the source's first layer. UserError naming the file and the feature for a
/// missing or empty layer, a feature without a point (and no --x/--y fields), a non-numeric,
/// null or non-finite value, or a coordinate beyond tol::kMaxSampleCoordinate. Duplicate points
/// are merged as read_samples_csv() merges them.
ScatteredSamples read_samples_ogr(const std::string& path, std::vector<std::string>* value_names, const CsvColumns& columns);

/// The query points of the source's first layer (as samples, without values).
std::vector<Vec2> read_queries_ogr(const std::string& path, const CsvColumns& columns);

/// The barrier lines of the source's first layer: a LineString's, each line of a
/// MultiLineString, each ring of a Polygon or MultiPolygon (a feature without a geometry holds
/// none). UserError naming the file, layer and feature, and the part and point where there are
/// several ("b.gpkg: layer 'walls', feature 2, polygon 1, ring 2: a Polygon ring must be closed:
/// ..."), for another geometry (a point), an empty Polygon, a coordinate beyond
/// tol::kMaxSampleCoordinate, a line barrier_line_defect() refuses (as GeoJSON's: a LineString
/// of fewer than 2 points, a ring of fewer than 4 or not closed, a segment of zero length), or
/// no line at all. What is returned therefore always passes Barriers::from_polylines().
std::vector<Polyline> read_ogr_barriers(const std::string& path);

/// The CRS its first layer declares: "EPSG:CODE" when it is an EPSG one, else its WKT; "" when
/// it declares none (or GDAL cannot open it: the readers above say why), and for GeoJSON without
/// a "crs" member, which GDAL reports as WGS 84 whatever its coordinates (RFC 7946), while files
/// of local or projected coordinates are common.
std::string ogr_source_crs(const std::string& path);

/// Whether two CRSs (EPSG codes, WKT, PROJ strings) are the same (OGRSpatialReference::IsSame());
/// true when GDAL cannot read one of them.
bool same_crs(const std::string& a, const std::string& b);

/// Every file of the vector source (GDALDataset::GetFileList(): a shapefile's .shp, .shx, .dbf,
/// .prj, ...), so that no output lands on one; just `path` if GDAL cannot open it.
std::vector<std::string> ogr_source_files(const std::string& path);

}  // namespace radrecon
