#include "io/gdal_plugin.h"

#include <algorithm>
#include <cerrno>
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

namespace {

/// Moves the files `names` from the folder `from` into `to` (move_into_place()), all or none: a
/// file each replaces is kept first as a hard link in `from` (".was." and its name), and if a
/// move fails, those moved go back (or away, if they replaced nothing) before the error goes on.
/// A header moved beside the data of the raster it replaced (a BIL's .hdr) would describe it
/// wrongly. Where no hard link can be made, that file is moved without its way back.
void move_all_or_none(const std::filesystem::path& from, const std::filesystem::path& to,
                      const std::vector<std::filesystem::path>& names) {
  namespace fs = std::filesystem;
  std::vector<bool> kept(names.size(), false);
  for (size_t k = 0; k < names.size(); ++k) {
    std::error_code ec;
    if (fs::is_regular_file(fs::symlink_status(to / names[k], ec))) {
      fs::create_hard_link(to / names[k], from / (".was." + names[k].string()), ec);
      kept[k] = !ec;
    }
  }
  for (size_t k = 0; k < names.size(); ++k) {
    try {
      move_into_place(from / names[k], to / names[k]);
    } catch (...) {
      for (size_t j = 0; j < k; ++j) {
        std::error_code ec;
        if (kept[j])
          fs::rename(from / (".was." + names[j].string()), to / names[j], ec);
        else
          fs::remove(to / names[j], ec);
      }
      throw;
    }
  }
  for (size_t k = 0; k < names.size(); ++k) {
    std::error_code ec;
    if (kept[k]) fs::remove(from / (".was." + names[k].string()), ec);
  }
}

}  // namespace

std::vector<std::string> write_gdal_raster(const std::string& path, const Raster& raster, std::span<const double> values,
                                           int channels, const GeoRasterOptions& options) {
  namespace fs = std::filesystem;
  const GdalFunctions& gdal = gdal_functions("--out");
  const fs::path out(path);
  const fs::path parent = out.has_parent_path() ? out.parent_path() : fs::path(".");
  std::string pattern = (parent / ".radrecon-gdal-XXXXXX").string();
  if (mkdtemp(pattern.data()) == nullptr) throw output_error(path, errno, " (creating a temporary folder beside it)");
  const TemporaryPath pending(pattern, TemporaryPath::Kind::folder);
  try {
    std::vector<std::string> warnings = gdal.write_raster(path, pattern, raster, values, channels, options);
    const EarlierRaster earlier(path, false);
    // The raster and its side files, each checked before any is moved: a folder (or a device)
    // under one of their names would stop the move half-way.
    std::vector<fs::path> names;
    for (const fs::directory_entry& e : fs::directory_iterator(pattern)) names.push_back(e.path().filename());
    std::sort(names.begin(), names.end());
    for (const fs::path& name : names) {
      std::error_code ec;
      const fs::file_status there = fs::status(parent / name, ec);
      if (fs::exists(there) && !fs::is_regular_file(there))
        throw UserError((parent / name).string(), std::string(fs::is_directory(there) ? "is a folder" : "is not a regular file") +
                                                      ", where the raster " + path + " has a file of its own; refusing to replace it");
    }
    // A signal from here on waits: it would leave the raster's files half moved, or the earlier
    // raster's side files beside the new one.
    const DeferredSignals whole;
    move_all_or_none(pattern, parent, names);
    std::error_code ec;
    fs::remove(pattern, ec);  // empty now: were it not, the raster is in place all the same
    std::vector<std::string> written;
    for (const fs::path& name : names) written.push_back(name.string());
    for (std::string& warning : earlier.remove_unreplaced(written, options.inputs)) warnings.push_back(std::move(warning));
    return warnings;
  } catch (...) {
    std::error_code ec;
    fs::remove_all(pattern, ec);
    throw;
  }
}

EarlierRaster::EarlierRaster(const std::string& path, bool only_with_side_files) : path_(path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return;
  if (only_with_side_files) {
    const fs::path file(path);
    const std::string stem = file.stem().string(), name = file.filename().string();
    bool beside = false;
    for (fs::directory_iterator it(file.has_parent_path() ? file.parent_path() : fs::path("."), ec), end; !ec && it != end && !beside;
         it.increment(ec)) {
      const std::string other = it->path().filename().string();
      beside = other != name && other.compare(0, stem.size(), stem) == 0;
    }
    if (!beside) return;
  }
  files_ = gdal_functions("--out").raster_files(path);
}

namespace {

/// Whether `name` is a side file of the raster `output` that GIS would read with a new raster of
/// that name: the whole name followed by .aux.xml, .aux, .ovr or .msk, or the stem followed by
/// .prj, .hdr, .aux, .stx, .clr, .rrd or a world file's extension (case aside). Never a product's
/// metadata that GDAL also lists for a raster (summary.txt, METADATA.DIM, X_MTL.txt, .RPB, .IMD:
/// a user's files, some shared by every raster of the folder).
bool is_side_file_of(const std::filesystem::path& output, const std::string& name) {
  const std::string file = ascii_lower(output.filename().string()), stem = ascii_lower(output.stem().string());
  const std::string lower = ascii_lower(name);
  for (const char* suffix : {".aux.xml", ".aux", ".ovr", ".msk"})
    if (lower == file + suffix) return true;
  for (const char* extension : {".prj", ".hdr", ".aux", ".stx", ".clr", ".rrd", ".tfw", ".tifw", ".tiffw", ".wld"})
    if (lower == stem + extension) return true;
  return false;
}

}  // namespace

std::vector<std::string> EarlierRaster::remove_unreplaced(const std::vector<std::string>& written,
                                                          const std::vector<std::string>& inputs) const {
  namespace fs = std::filesystem;
  std::vector<std::string> warnings;
  const fs::path out(path_);
  const fs::path parent = out.has_parent_path() ? out.parent_path() : fs::path(".");
  for (const std::string& listed : files_) {
    const fs::path file(listed);
    std::error_code ec;
    // Only the raster's own side files beside it: not one elsewhere, nor one the new raster
    // wrote, nor an input of the run, nor any file GDAL lists that is not named after the raster.
    if (!is_side_file_of(out, file.filename().string())) continue;
    if (!fs::equivalent(file.has_parent_path() ? file.parent_path() : fs::path("."), parent, ec) || ec) continue;
    if (std::find(written.begin(), written.end(), file.filename().string()) != written.end()) continue;
    if (!fs::is_regular_file(fs::symlink_status(file, ec))) continue;
    if (std::any_of(inputs.begin(), inputs.end(), [&](const std::string& input) {
          std::error_code e;
          return fs::equivalent(file, input, e);
        }))
      continue;
    if (!fs::remove(file, ec) && ec)
      warnings.push_back(listed + ": a file of the raster " + path_ + " replaced, which the new one does not have, cannot be " +
                         "removed (" + ec.message() + "); GIS may read it with the new raster");
  }
  return warnings;
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
