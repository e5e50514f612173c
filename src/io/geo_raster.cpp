#include "io/geo_raster.h"

#include "core/error.h"
#include "core/parse.h"
#include "io/geotiff.h"
#include "io/plugin.h"

namespace radrecon {

void refuse_nodata_clash(std::span<const double> values, double nodata, bool float64) {
  // A Float32 band holds each value rounded to a float: a clash is one there.
  const auto stored = [float64](double v) { return float64 ? v : static_cast<double>(static_cast<float>(v)); };
  const double nodata_stored = stored(nodata);
  for (const double v : values)
    if (stored(v) == nodata_stored)
      throw UserError("--nodata", "the value " + format_number(nodata) + " occurs in the results" +
                                      (v == nodata ? "" : " (as " + format_number(v) + ", once rounded to a 32-bit float)") +
                                      ", where it would read back as no data; choose another --nodata");
}

const GeoTiffFunctions& geotiff_functions(const std::string& what) {
  static const PluginSpec kPlugin{"libradrecon_geotiff.so", kGeoTiffPluginEntry, "RADRECON_GEOTIFF_PLUGIN",
                                  "GeoTIFF support (libtiff)"};
  return *static_cast<const GeoTiffFunctions*>(plugin_table(kPlugin, what));
}

}  // namespace radrecon
