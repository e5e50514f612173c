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

/// A CRS as the GeoKeys record it: by its EPSG code (as GDAL records an EPSG-coded CRS, any
/// parameters a WKT changes beside its ID are not kept).
struct GeoTiffCrs {
  int epsg = 0;            ///< 0: no CRS (no GeoKeys written)
  bool projected = false;  ///< else geographic 2-D
  std::string name;        ///< its name, for the citation key
  int unit_epsg = 0;       ///< the EPSG code of its axes' unit; 0: unknown
};

/// The plugin's table of functions.
struct GeoTiffFunctions {
  /// `crs` as write() records it, or false when it cannot: it takes none (empty), or a CRS in a
  /// form GDAL's --crs takes too (EPSG:n, urn:ogc:def:crs:EPSG::n, or a WKT CRS) that PROJ reads
  /// as a projected or geographic 2-D CRS with an EPSG code. Any other CRS takes GDAL, which
  /// writes it whole or refuses it.
  bool (*resolve_crs)(const std::string& crs, GeoTiffCrs* out);
  /// Writes raster values (raster order: the y0 row first, `channels` per point) as a GeoTIFF
  /// of `channels` bands into `file` (a temporary file: the caller makes it atomic), NaN written
  /// as options.nodata (the caller has refused a clash: refuse_nodata_clash()), with `crs`
  /// (options.crs is not read); UserError naming `shown_as` if libtiff cannot.
  void (*write)(const std::filesystem::path& file, const std::string& shown_as, const Raster& raster,
                std::span<const double> values, int channels, const GeoRasterOptions& options, const GeoTiffCrs& crs);
};

/// The name of the symbol the plugin exports: `const void* ()`, the address of its GeoTiffFunctions.
inline constexpr const char* kGeoTiffPluginEntry = "radrecon_geotiff_functions";

/// The plugin's functions, loaded on first use (a UserError naming `what` if they cannot be;
/// $RADRECON_GEOTIFF_PLUGIN may name its path).
const GeoTiffFunctions& geotiff_functions(const std::string& what);

}  // namespace radrecon
