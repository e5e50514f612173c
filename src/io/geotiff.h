#pragma once
// GeoTIFF written by libtiff and libgeotiff alone (Debian's libtiff and libgeotiff, with PROJ to
// read the CRS), built into the plugin libradrecon_geotiff.so (io/plugin.h). GDAL writes the
// same file (io/gdal_raster.h), but loading it and its hundred libraries costs ~80 ms on the
// 2-core machine, more than interpolating W1; these load in ~20 ms. The file is what GDAL's
// GTiff driver writes by default, read back the same by GDAL: uncompressed strips, the bands
// pixel-interleaved, 32- or 64-bit IEEE floats, north-up (io/geo_raster.h), the geotransform as
// ModelTiepoint and ModelPixelScale with the PixelIsArea raster type, the no-data value in
// GDAL's tag (42113, as text), and the CRS as its EPSG code in the GeoKeys; BigTIFF past 4 GB.

#include <filesystem>
#include <span>
#include <string>

#include "io/geo_raster.h"
#include "io/raster.h"

namespace radrecon {

/// The plugin's table of functions.
struct GeoTiffFunctions {
  /// Whether write() can record `crs`: none (empty), or one that PROJ reads as a projected or
  /// geographic 2-D CRS with an EPSG code (EPSG:2193, or a WKT carrying its ID). Any other CRS
  /// takes GDAL, which writes it whole and reports one it cannot read.
  bool (*can_record_crs)(const std::string& crs);
  /// Writes raster values (raster order: the y0 row first, `channels` per point) as a GeoTIFF
  /// of `channels` bands into `file` (a temporary file: the caller makes it atomic), NaN written
  /// as options.nodata (the caller has refused a clash: refuse_nodata_clash()); UserError naming
  /// `shown_as` if libtiff cannot.
  void (*write)(const std::filesystem::path& file, const std::string& shown_as, const Raster& raster,
                std::span<const double> values, int channels, const GeoRasterOptions& options);
};

/// The name of the symbol the plugin exports: `const void* ()`, the address of its GeoTiffFunctions.
inline constexpr const char* kGeoTiffPluginEntry = "radrecon_geotiff_functions";

/// The plugin's functions, loaded on first use (a UserError naming `what` if they cannot be;
/// $RADRECON_GEOTIFF_PLUGIN may name its path).
const GeoTiffFunctions& geotiff_functions(const std::string& what);

}  // namespace radrecon
