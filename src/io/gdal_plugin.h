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
};

/// The name of the symbol the plugin exports: `const void* ()`, the address of its GdalFunctions.
inline constexpr const char* kGdalPluginEntry = "radrecon_gdal_functions";

/// The plugin's functions, loaded on the first call (plugin_table(); $RADRECON_GDAL_PLUGIN may
/// name its path). UserError naming `what` (the option that needs GDAL) when it cannot be loaded.
const GdalFunctions& gdal_functions(const std::string& what);

/// Writes a raster through GDAL (GdalFunctions::write_raster) atomically: in a fresh folder
/// `.radrecon-gdal-XXXXXX` beside `path`, removed after, or by a signal (TemporaryPath,
/// io/atomic_file.h), with what it holds. Its files are then moved beside `path`, each renamed
/// (move_into_place()) once none has a folder or another non-file under its name there. Returns
/// the warnings.
std::vector<std::string> write_gdal_raster(const std::string& path, const Raster& raster, std::span<const double> values,
                                           int channels, const GeoRasterOptions& options);

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
