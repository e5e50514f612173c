#pragma once
// GDAL support as a plugin (io/plugin.h): the GDAL readers and writers (io/gdal_raster.h,
// io/gdal_vector.h) are built into libradrecon_gdal.so, beside the executable, and loaded on
// first use.

#include <array>
#include <span>
#include <string_view>
#include <string>
#include <vector>

#include "io/gdal_raster.h"
#include "io/samples_csv.h"

namespace radrecon {

/// The plugin's entry points (same compiler and library as the program: plain C++ signatures).
struct GdalFunctions {
  std::string (*raster_driver)(const std::string& path, const std::string& format, const std::string& where);
  void (*check_crs)(const std::string& crs);
  std::vector<std::string> (*write_raster)(const std::string& path, const std::string& staging, const Raster& raster,
                                           std::span<const double> values, int channels, const GeoRasterOptions& options);
  ScatteredSamples (*read_samples)(const std::string& path, std::vector<std::string>* value_names,
                                   const CsvColumns& columns);
  std::vector<Vec2> (*read_queries)(const std::string& path, const CsvColumns& columns);
  std::vector<Polyline> (*read_barriers)(const std::string& path);
  std::vector<std::string> (*source_files)(const std::string& path);
  std::vector<std::string> (*raster_files)(const std::string& path);
  void (*check_raster)(const std::string& path, const GeoRasterOptions& options, int channels, bool square_pixels);
  std::string (*source_crs)(const std::string& path);
  bool (*same_crs)(const std::string& a, const std::string& b);
};

/// The name of the symbol the plugin exports: `const void* ()`, the address of its GdalFunctions.
inline constexpr const char* kGdalPluginEntry = "radrecon_gdal_functions";

/// The plugin's functions, loaded on the first call (plugin_table(); $RADRECON_GDAL_PLUGIN may
/// name its path). UserError naming `what` (the option that needs GDAL) when it cannot be loaded.
const GdalFunctions& gdal_functions(const std::string& what);

/// Writes a raster through GDAL (GdalFunctions::write_raster) atomically: in a fresh folder
/// `.radrecon-gdal-XXXXXX` beside `path`, removed after, or by a signal (TemporaryPath,
/// io/atomic_file.h), with what it holds. Its files are then moved beside `path`, each renamed
/// (move_into_place()) once none has a folder or another non-file under its name there, all or
/// none (a failed rename puts back the files already moved), signals deferred; and of a
/// raster it replaces, the files the new one does not have are removed (EarlierRaster). Returns
/// the warnings.
std::vector<std::string> write_gdal_raster(const std::string& path, const Raster& raster, std::span<const double> values,
                                           int channels, const GeoRasterOptions& options);

/// A raster about to be replaced at `path`: its files as GDAL lists them (GdalFunctions::
/// raster_files), taken before the new raster takes its name. A file of it that the new raster
/// does not write stays beside it otherwise, and is read with it: an older .prj gives the new
/// raster the old CRS, an older .aux.xml its statistics or no-data value.
class EarlierRaster {
 public:
  /// Lists the files of the raster at `path`, if there is one. With `only_with_side_files`, only
  /// when a file beside it begins with its stem ("o" of o.tif: o.tfw, o.tif.aux.xml): GDAL is
  /// not loaded to list a GeoTIFF that stands alone, as radrecon's own GeoTIFF writer leaves it.
  EarlierRaster(const std::string& path, bool only_with_side_files);
  /// Removes those of the listed files, in `path`'s folder, that are side files named after it
  /// (PATH.aux.xml, STEM.prj, a world file, ...: never a product's metadata that GDAL lists too,
  /// such as summary.txt or METADATA.DIM), that the new raster did not write there (`written`:
  /// file names) and that are none of `inputs`. Returns a warning for each that cannot be removed.
  std::vector<std::string> remove_unreplaced(const std::vector<std::string>& written,
                                             const std::vector<std::string>& inputs) const;

 private:
  std::string path_;
  std::vector<std::string> files_;
};

/// The extensions of a file read as a CSV or XYZ table (besides none); any other is read through
/// OGR (is_ogr_vector_path()).
inline constexpr std::array<std::string_view, 5> kTableExtensions = {".csv", ".txt", ".xyz", ".dat", ".tsv"};

/// Whether `path` is read through OGR rather than as a native CSV/XYZ table: any extension but
/// kTableExtensions (and none).
bool is_ogr_vector_path(const std::string& path);

/// Every file of an input that may be a vector source, for the outputs that may not land on one:
/// `path` itself, and for a source of several files (a shapefile's .shx, .dbf and .prj; a VRT's
/// sources) those GDAL lists (GdalFunctions::source_files; `what` names the option needing GDAL).
/// A table, GeoJSON, GeoPackage or FlatGeobuf is one file: not opened.
std::vector<std::string> vector_input_files(const std::string& path, const std::string& what);

}  // namespace radrecon
