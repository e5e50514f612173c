#include "io/gdal_plugin.h"

#include <algorithm>

#include "core/parse.h"
#include "io/plugin.h"

namespace radrecon {

const GdalFunctions& gdal_functions(const std::string& what) {
  static const PluginSpec kPlugin{"libradrecon_gdal.so", kGdalPluginEntry, "RADRECON_GDAL_PLUGIN", "GDAL support"};
  return *static_cast<const GdalFunctions*>(plugin_table(kPlugin, what));
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
