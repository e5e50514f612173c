#pragma once
// Rasters written through GDAL (Debian's libgdal): any raster format GDAL can create, chosen by
// the output's extension or by driver name, georeferenced by the raster's domain so that GIS
// tools place it (io/geo_raster.h: north-up, the geotransform, no-data); a coordinate reference
// system passed through as given. A GeoTIFF whose CRS is none or an EPSG code is written by
// libtiff instead (io/geotiff.h), without GDAL's start-up. The functions live in the GDAL plugin
// (io/gdal_plugin.h); the program calls them through gdal_functions().

#include <span>
#include <string>
#include <vector>

#include "io/geo_raster.h"
#include "io/raster.h"

namespace radrecon {

/// The short name of the GDAL driver that would write `path` (`format` if given, else the first
/// raster driver that can create files of its extension); UserError naming `where` if there is
/// none, with the extensions of the formats that write a plain georeferenced raster of floats, or
/// if the driver is known to write none of radrecon's rasters (NTv2, HF2, SIGDEM, ...).
std::string gdal_raster_driver(const std::string& path, const std::string& format, const std::string& where);

/// Refuses (UserError naming --out) before the work a raster of `channels` bands that the driver
/// writing `path` is known not to write: of more bands than it takes (one for the Arc/Info grid,
/// netCDF, XYZ, ...), without a --crs it needs (GRIB, BAG), of a CRS it cannot record (NITF:
/// geographic only), of pixels not square where it takes only those (SAGA, ISIS3). `square_pixels`:
/// the raster's cells are as wide as tall.
void check_gdal_raster(const std::string& path, const GeoRasterOptions& options, int channels, bool square_pixels);

/// Checks the CRS text (UserError naming --crs) before any work: anything GDAL's SetFromUserInput
/// takes.
void check_gdal_crs(const std::string& crs);

/// Writes raster values (raster order: the y0 row first, `channels` per point) as a raster of
/// `channels` bands, north-up (rows flipped), NaN written as options.nodata (the caller has
/// refused a clash: refuse_nodata_clash()). Written in the empty folder `staging` beside `path`
/// (with any side files the format has), UserError if any of them would land on one of
/// options.inputs; the caller makes `staging`, moves its files beside `path` and removes it
/// (write_gdal_raster() in io/gdal_plugin.h).
/// Read back in `staging`: UserError if GDAL cannot read it (MEM writes no file, a VRT no
/// values), or its size, bands or values are not what was written (KMLSUPEROVERLAY writes 8-bit
/// tiles); a warning for each of the georeferencing and the no-data value it does not keep.
/// Returns the warnings.
std::vector<std::string> write_raster_gdal(const std::string& path, const std::string& staging, const Raster& raster,
                                           std::span<const double> values, int channels, const GeoRasterOptions& options);

/// The files of the raster at `path` as GDAL lists them (GDALDataset::GetFileList(): the raster,
/// its header, .prj, .aux.xml, world file, ...), opened read-only; none if GDAL cannot open it as
/// a raster.
std::vector<std::string> gdal_raster_files(const std::string& path);

}  // namespace radrecon
