#pragma once
// What the writers of georeferenced rasters share: GDAL's for any raster format it creates
// (io/gdal_raster.h) and libtiff's for GeoTIFF (io/geotiff.h). Both write north-up: the first
// stored row is the raster's y1 row (the top), the geotransform is
// (x0, (x1 - x0) / W, 0, y1, 0, -(y1 - y0) / H), and a method's missing values (NaN) are written
// as the no-data value, which each band declares.

#include <span>
#include <string>
#include <vector>

#include "core/parse.h"

namespace radrecon {

/// The no-data value written by default: gdal_grid's -nodata is 0, which is a real value of many
/// fields; -9999 is the usual choice of elevation and bathymetry grids.
inline constexpr double kDefaultNoData = -9999;

struct GeoRasterOptions {
  std::string format;    ///< a GDAL driver's short name (e.g. "GTiff", "AAIGrid"); empty: by the extension
  bool float64 = false;  ///< bands of 64-bit floats, else 32-bit
  std::string crs;       ///< a coordinate reference system (EPSG:2193, WKT, PROJ), passed through; empty: none
  double nodata = kDefaultNoData;  ///< written for NaN and declared as each band's no-data value
  /// The command's input files: a side file a format writes beside the output (an ENVI or ERS
  /// header's data file, named like the output without its extension) may not be one of them.
  std::vector<std::string> inputs;
  /// Each band's description: the value columns' names (a GeoTIFF's bands read in QGIS or by
  /// gdalinfo as "depth", "mag"); empty: none.
  std::vector<std::string> band_names;
};

/// UserError naming --nodata if a value equals `nodata` as the band stores both (rounded to a
/// float unless `float64`): it would read back as missing.
void refuse_nodata_clash(std::span<const double> values, double nodata, bool float64);

/// Whether writing `path` with --format `format` makes a GeoTIFF: .tif or .tiff without
/// --format, or --format GTiff (GDAL's name, in any case). Inline: the GDAL plugin asks too.
inline bool is_geotiff_output(const std::string& path, const std::string& format) {
  if (!format.empty()) return ascii_lower(format) == "gtiff";
  const std::string ext = lower_extension(path);
  return ext == ".tif" || ext == ".tiff";
}

}  // namespace radrecon
