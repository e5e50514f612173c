// The GDAL plugin's entry point (io/gdal_plugin.h).

#include "io/gdal_plugin.h"
#include "io/gdal_vector.h"

extern "C" __attribute__((visibility("default"))) const void* radrecon_gdal_functions() {
  static const radrecon::GdalFunctions functions{
      radrecon::gdal_raster_driver,  radrecon::check_gdal_crs,  radrecon::write_raster_gdal,
      radrecon::read_samples_ogr,    radrecon::read_queries_ogr, radrecon::read_ogr_barriers,
      radrecon::ogr_source_files,    radrecon::gdal_raster_files, radrecon::check_gdal_raster,
      radrecon::ogr_source_crs,      radrecon::same_crs};
  return &functions;
}
