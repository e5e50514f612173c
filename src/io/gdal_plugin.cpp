#include "io/gdal_plugin.h"

#include "core/parse.h"
#include "io/plugin.h"

namespace radrecon {

const GdalFunctions& gdal_functions(const std::string& what) {
  static const PluginSpec kPlugin{"libradrecon_gdal.so", kGdalPluginEntry, "RADRECON_GDAL_PLUGIN", "GDAL support"};
  return *static_cast<const GdalFunctions*>(plugin_table(kPlugin, what));
}

bool is_ogr_vector_path(const std::string& path) {
  const std::string ext = lower_extension(path);
  return !(ext.empty() || ext == ".csv" || ext == ".txt" || ext == ".xyz" || ext == ".dat" || ext == ".tsv");
}

}  // namespace radrecon
