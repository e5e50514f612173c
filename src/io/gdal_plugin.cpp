#include "io/gdal_plugin.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>

#include "core/error.h"
#include "core/parse.h"
#include "io/atomic_file.h"
#include "io/plugin.h"

namespace radrecon {

const GdalFunctions& gdal_functions(const std::string& what) {
  static const PluginSpec kPlugin{"libradrecon_gdal.so", kGdalPluginEntry, "RADRECON_GDAL_PLUGIN", "GDAL support"};
  return *static_cast<const GdalFunctions*>(plugin_table(kPlugin, what));
}

std::vector<std::string> write_gdal_raster(const std::string& path, const Raster& raster, std::span<const double> values,
                                           int channels, const GeoRasterOptions& options) {
  namespace fs = std::filesystem;
  const GdalFunctions& gdal = gdal_functions("--out");
  const fs::path out(path);
  const fs::path parent = out.has_parent_path() ? out.parent_path() : fs::path(".");
  std::string pattern = (parent / ".radrecon-gdal-XXXXXX").string();
  if (mkdtemp(pattern.data()) == nullptr) throw UserError(path, "cannot create a temporary folder beside it");
  const TemporaryPath pending(pattern, TemporaryPath::Kind::folder);
  try {
    std::vector<std::string> warnings = gdal.write_raster(path, pattern, raster, values, channels, options);
    fs::remove(pattern);
    return warnings;
  } catch (...) {
    std::error_code ec;
    fs::remove_all(pattern, ec);
    throw;
  }
}

bool is_ogr_vector_path(const std::string& path) {
  const std::string ext = lower_extension(path);
  return !ext.empty() && std::find(kTableExtensions.begin(), kTableExtensions.end(), ext) == kTableExtensions.end();
}

std::vector<std::string> vector_input_files(const std::string& path, const std::string& what) {
  // A table, or a format of one file by its definition: no need to open it twice.
  const std::string ext = lower_extension(path);
  if (!is_ogr_vector_path(path) || ext == ".geojson" || ext == ".json" || ext == ".gpkg" || ext == ".fgb")
    return {path};
  std::vector<std::string> files = gdal_functions(what).source_files(path);
  files.push_back(path);  // as given, whatever GDAL lists
  return files;
}

}  // namespace radrecon
