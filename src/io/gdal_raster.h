#pragma once
// Rasters written through GDAL (Debian's libgdal): any raster format GDAL can create, chosen by
// the output's extension (.tif: GeoTIFF) or by driver name, georeferenced by the raster's domain
// so that GIS tools place it: north-up, the first stored row is the raster's y1 row (the top),
// geotransform (x0, (x1 - x0) / W, 0, y1, 0, -(y1 - y0) / H); a coordinate reference system passed
// through as given; a no-data value where a method has no value (NaN). The functions live in the
// GDAL plugin (io/gdal_plugin.h); the program calls them through gdal_functions().

#include <span>
#include <string>

#include "io/raster.h"

namespace radrecon {

/// The no-data value written by default: gdal_grid's -nodata is 0, which is a real value of many
/// fields; -9999 is the usual choice of elevation and bathymetry grids.
inline constexpr double kDefaultNoData = -9999;

struct GdalRasterOptions {
  std::string format;    ///< a GDAL driver's short name (e.g. "GTiff", "AAIGrid"); empty: by the extension
  bool float64 = false;  ///< bands of 64-bit floats, else 32-bit
  std::string crs;       ///< anything GDAL's SetFromUserInput takes (EPSG:2193, WKT, PROJ); empty: none
  double nodata = kDefaultNoData;  ///< written for NaN and declared as each band's no-data value
};

/// The short name of the GDAL driver that would write `path` (`format` if given, else the first
/// raster driver that can create files of its extension); UserError naming `where` if there is
/// none, with the extensions it knows.
std::string gdal_raster_driver(const std::string& path, const std::string& format, const std::string& where);

/// Checks the CRS text (UserError naming --crs) before any work.
void check_gdal_crs(const std::string& crs);

/// Writes raster values (raster order: the y0 row first, `channels` per point) as a raster of
/// `channels` bands, north-up (rows flipped), NaN written as options.nodata. UserError if a
/// finite value equals the no-data value (it would read back as missing). Atomic: written in a
/// temporary folder beside `path`, then moved (with any side files the format has).
void write_raster_gdal(const std::string& path, const Raster& raster, std::span<const double> values, int channels,
                       const GdalRasterOptions& options);

}  // namespace radrecon
