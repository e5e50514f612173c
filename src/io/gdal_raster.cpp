#include "io/gdal_raster.h"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <memory>
#include <mutex>
#include <sstream>
#include <string_view>
#include <vector>

#include <cpl_conv.h>
#include <cpl_error.h>
#include <cpl_string.h>
#include <gdal_frmts.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include "core/check.h"
#include "core/error.h"
#include "core/parse.h"
#include "core/tolerances.h"

namespace radrecon {

namespace {

/// Registers the drivers that writing with `driver` needs: GTiff and MEM (the staging dataset)
/// alone for GeoTIFF, the common case, in ~1 ms; every driver otherwise (GDALAllRegister(): some
/// 200 drivers and the plugin folder, ~20 ms on the 2-core machine, as much as interpolating W1).
void register_drivers(const std::string& driver) {
  static std::once_flag minimal, all;
  std::call_once(minimal, [] {
    GDALRegister_GTiff();
    GDALRegister_MEM();
  });
  if (driver != "GTiff") std::call_once(all, [] { GDALAllRegister(); });
}

/// GDAL's own messages go to its last-error slot, not to stderr, while this lives.
class QuietGdal {
 public:
  QuietGdal() {
    CPLPushErrorHandler(CPLQuietErrorHandler);
    CPLErrorReset();
  }
  ~QuietGdal() { CPLPopErrorHandler(); }
  static std::string last_error() {
    const char* msg = CPLGetLastErrorMsg();
    return msg && *msg ? msg : "GDAL gave no reason";
  }
};

bool can_create_raster(GDALDriver* d) {
  return d->GetMetadataItem(GDAL_DCAP_RASTER) != nullptr &&
         (d->GetMetadataItem(GDAL_DCAP_CREATE) != nullptr || d->GetMetadataItem(GDAL_DCAP_CREATECOPY) != nullptr);
}

/// The advice of a refusal for the format: formats known to keep floating-point bands.
constexpr const char* kFloatFormatsAdvice = "; write .tif, .asc, .nc or another format of floating-point bands";

/// Whether the driver may write bands of `type`: it lists it among its band types
/// (GDAL_DMD_CREATIONDATATYPES), or lists none and is not one of those known to write integers
/// alone (CALS's 1-bit, BLX's 16-bit). XYZ, Leveller, ZMap and others list none, yet write floats.
bool lists_band_type(GDALDriver* d, const char* type) {
  const char* types = d->GetMetadataItem(GDAL_DMD_CREATIONDATATYPES);
  if (types == nullptr) return std::string_view(d->GetDescription()) != "CALS" && std::string_view(d->GetDescription()) != "BLX";
  std::istringstream list(types);
  for (std::string t; list >> t;)
    if (t == type) return true;
  return false;
}

/// Refuses a driver that cannot write bands of `type` (its creation data types, where it lists
/// them): GDAL would round the values into its own type (Byte for GIF, JPEG, XPM and PNG) without
/// a word. Only for Float32: the list is Create()'s, and a driver that writes through CreateCopy()
/// alone may hold more (an Arc/Info grid lists no Float64, yet writes a Float64 band's values in
/// full), or less (XYZ lists nothing; the read-back judges what it wrote).
void require_band_type(GDALDriver* d, const char* type, const std::string& where) {
  if (lists_band_type(d, type)) return;
  const char* types = d->GetMetadataItem(GDAL_DMD_CREATIONDATATYPES);
  throw UserError(where, std::string("GDAL's ") + d->GetDescription() + " driver writes bands of " +
                             (types != nullptr ? types : "integers") +
                             " only, which would round the values to them (radrecon writes " + type + ")" +
                             kFloatFormatsAdvice);
}

/// The raster written at `file` (in its temporary folder) read back and compared with `image`,
/// what was given to the driver: see write_raster_gdal(). Returns the warnings.
std::vector<std::string> read_back(const std::string& path, const std::string& file, const std::string& driver,
                                   GDALDataset& image, const GeoRasterOptions& options) {
  const std::string its = "GDAL's " + driver + " driver ";
  const int width = image.GetRasterXSize(), height = image.GetRasterYSize(), bands = image.GetRasterCount();
  // Formats known to keep floating-point bands, the output's own left out; several bands need one
  // that stores them as bands of one raster.
  std::string advice = ": write ";
  {
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    std::vector<std::string> formats = bands > 1 ? std::vector<std::string>{".tif", ".img"} : std::vector<std::string>{".tif", ".asc", ".nc"};
    std::erase(formats, ext);
    for (size_t k = 0; k < formats.size(); ++k) advice += (k ? ", " : "") + formats[k];
    advice += bands > 1 ? " or another format of several floating-point bands, or one value column at a time (--value)"
                        : " or another format of floating-point bands";
  }
  std::unique_ptr<GDALDataset> back(GDALDataset::Open(file.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
  if (!back)
    throw UserError(path, its + "wrote nothing GDAL can read back (" + QuietGdal::last_error() + ")" +
                              (std::isnan(options.nodata) ? "; it may not read NaN, which --nodata a number avoids" : "") + advice);
  if (back->GetRasterCount() == 0 && back->GetMetadata("SUBDATASETS") != nullptr)
    throw UserError(path, its + "stores the " + std::to_string(bands) +
                              " value columns as separate variables (subdatasets), not as the bands of one raster" + advice);
  if (back->GetRasterXSize() != width || back->GetRasterYSize() != height || back->GetRasterCount() != bands)
    throw UserError(path, its + "wrote " + std::to_string(back->GetRasterXSize()) + " x " + std::to_string(back->GetRasterYSize()) +
                              " pixels of " + std::to_string(back->GetRasterCount()) + " band(s) for " + std::to_string(width) +
                              " x " + std::to_string(height) + " of " + std::to_string(bands) + advice);
  std::vector<double> wrote(static_cast<size_t>(width)), read(static_cast<size_t>(width));
  // The no-data value as the staged band holds it (a float32 band rounds it, as
  // refuse_nodata_clash() takes it); NaN matches NaN.
  const double nodata = options.float64 ? options.nodata : static_cast<double>(static_cast<float>(options.nodata));
  const auto same_value = [](double a, double b) { return a == b || (std::isnan(a) && std::isnan(b)); };
  bool holes = false;   // whether any pixel is the no-data value
  double most_off = 0;  // the largest difference read back, relative to its band's largest magnitude
  int declared_has = 0;
  const double declared = back->GetRasterBand(1)->GetNoDataValue(&declared_has);
  for (int b = 1; b <= bands; ++b) {
    GDALRasterBand* w = image.GetRasterBand(b);
    GDALRasterBand* r = back->GetRasterBand(b);
    const GDALDataType type = r->GetRasterDataType();
    if (type != GDT_Float32 && type != GDT_Float64)
      throw UserError(path, its + "wrote bands of " + GDALGetDataTypeName(type) + ", which round the values" + advice);
    // One pass: the band's largest magnitude written (no-data aside) and the largest difference
    // read back, with where it is, judged against the largest magnitude at the end.
    double largest = 0, worst_off = 0;
    std::string worst;  // where the largest difference is, for the message
    bool beyond_float = false;  // whether it is a value a float32 band holds as infinity
    const auto at = [&](int i, int j, double expected, double got) {
      return " (band " + std::to_string(b) + ", row " + std::to_string(j) + ", column " + std::to_string(i) + ": wrote " +
             format_number(expected) + ", reads " + format_number(got) + ")";
    };
    for (int j = 0; j < height; ++j) {
      if (w->RasterIO(GF_Read, 0, j, width, 1, wrote.data(), width, 1, GDT_Float64, 0, 0) != CE_None ||
          r->RasterIO(GF_Read, 0, j, width, 1, read.data(), width, 1, GDT_Float64, 0, 0) != CE_None)
        throw UserError(path, its + "wrote a raster GDAL cannot read back (" + QuietGdal::last_error() + ")" + advice);
      for (int i = 0; i < width; ++i) {
        const double expected = wrote[static_cast<size_t>(i)], got = read[static_cast<size_t>(i)];
        if (same_value(expected, nodata)) {  // a point without a value: the format's own no-data value will do
          holes = true;
          if (!(same_value(got, expected) || (declared_has && same_value(got, declared))))
            throw UserError(path, its + "does not keep the points without a value" + at(i, j, expected, got) + advice);
          continue;
        }
        if (std::isfinite(expected)) largest = std::max(largest, std::abs(expected));
        if (got == expected) continue;  // infinities too (a value beyond a float's range)
        const double off = std::isnan(got) ? std::numeric_limits<double>::infinity() : std::abs(got - expected);
        if (off > worst_off || worst.empty()) worst_off = off, worst = at(i, j, expected, got), beyond_float = std::isinf(expected);
      }
    }
    if (worst.empty()) continue;
    if (!(worst_off <= tol::kRasterReadBackRelative * largest))
      throw UserError(path, its + "does not keep the values" + worst +
                                (beyond_float ? "; a value beyond a 32-bit float's range is infinity in a float32 band, "
                                                "which this format does not keep"
                                              : "") +
                                advice);
    if (largest > 0) most_off = std::max(most_off, worst_off / largest);
  }
  std::vector<std::string> warnings;
  double given[6], kept[6];
  image.GetGeoTransform(given);
  bool same = back->GetGeoTransform(kept) == CE_None;
  for (int k = 0; k < 6 && same; ++k) same = std::abs(kept[k] - given[k]) <= 1e-9 * (std::abs(given[k]) + std::abs(given[1]) + std::abs(given[5]));
  if (!same)
    warnings.push_back(path + ": " + its + "keeps no georeferencing: the raster's domain is not in the file (.tif, .asc or .nc keep it)");
  // Beyond the rounding of the band type itself (a 32-bit float's half ulp, 6e-8 relative).
  if (most_off > (options.float64 ? 1e-15 : 6e-8))
    warnings.push_back(path + ": " + its + "rounds the values, by up to " + format_number(most_off) +
                       " of the largest (its decimal digits; .tif, .asc or .nc keep them as written)");
  if (holes && !declared_has)
    warnings.push_back(path + ": " + its + "declares no no-data value: the points without a value read as " +
                       format_number(options.nodata) + " (.tif, .asc or .nc declare it)");
  else if (holes && !same_value(declared, nodata) && !same_value(declared, options.nodata))
    warnings.push_back(path + ": " + its + "writes its own no-data value, " + format_number(declared) + ", for --nodata " +
                       format_number(options.nodata));
  return warnings;
}

/// Drivers that create rasters but not a file of the values, refused before any work (the
/// read-back of write_raster_gdal() would refuse them after it).
const char* no_file_of_values(const std::string& driver) {
  if (driver == "MEM") return "keeps the raster in memory and writes no file";
  if (driver == "VRT") return "writes a description of other rasters, not values";
  if (driver == "KMLSUPEROVERLAY") return "writes 8-bit colour tiles for Google Earth, not values";
  return nullptr;
}

/// What a driver that lists Float32 bands does not write of radrecon's rasters (bands of floats,
/// one a value column, a north-up geotransform, the CRS of --crs if any, a no-data value), found
/// by writing each with GDAL 3.6: refused before the work (check_gdal_raster()), saying why, and
/// left out of the formats an unknown extension is told of, but for those of one band, told as
/// such. A driver not named here writes them as far as known (the read-back judges, after).
struct DriverLimits {
  const char* driver;
  const char* extension;  ///< only for files of this extension (lower case, no dot); nullptr: all
  const char* never;      ///< why it writes none of them; nullptr: it writes some
  bool one_band;          ///< it writes one band at most
  int exact_bands;        ///< the only number of bands it writes (0: any)
  bool needs_crs, needs_geographic_crs, needs_square_pixels;
  bool keeps_georeferencing;  ///< false: written with radrecon's warning that it keeps none
  const char* several_bands = nullptr;  ///< what it makes of several bands, if not a refusal of its own
};
constexpr DriverLimits kDriverLimits[] = {
    // driver, extension, never, one band, exact bands, CRS, geographic CRS, square pixels, georeferencing
    {"NTv2", nullptr, "writes grid-shift files of four bands (latitude and longitude shifts and their accuracies), not values",
     false, 0, false, false, false, true},
    {"Leveller", nullptr, "needs the heights' range as a creation option (MINUSERPIXELVALUE), which radrecon does not give",
     true, 0, false, false, false, true},
    {"Terragen", nullptr, "needs the heights' span as creation options, which radrecon does not give", true, 0, false, false,
     false, true},
    {"HF2", nullptr, "rounds the values to its vertical precision (0.01)", true, 0, false, false, false, true},
    {"SIGDEM", nullptr, "stores the values as integers of a fixed step (0.001), which rounds them", true, 0, true, false, false,
     true},
    {"NWT_GRD", nullptr, "writes a grid that GDAL reads back as 8-bit colour bands, not the values", true, 0, false, false, false,
     true},
    {"SAGA", "sg-grd-z", "reads zipped SAGA grids but does not write them (.sdat is SAGA's grid)", true, 0, false, false, true,
     true},
    {"BAG", nullptr, nullptr, false, 2, true, false, false, true},  // bathymetry: elevation and its uncertainty
    {"GRIB", nullptr, nullptr, false, 0, true, false, false, false},
    {"NITF", nullptr, nullptr, false, 0, false, true, false, true},  // its corners in degrees (IGEOLO)
    {"ISIS3", nullptr, nullptr, false, 0, false, false, true, false},
    {"SAGA", nullptr, nullptr, true, 0, false, false, true, true},
    {"PCRaster", nullptr, nullptr, true, 0, false, false, false, false},  // georeferenced for square pixels only
    {"AAIGrid", nullptr, nullptr, true, 0, false, false, false, true},
    {"RST", nullptr, nullptr, true, 0, false, false, false, true},
    {"BT", nullptr, nullptr, true, 0, false, false, false, true},
    {"GTX", nullptr, nullptr, true, 0, false, false, false, true},
    {"GSAG", nullptr, nullptr, true, 0, false, false, false, true},
    {"GSBG", nullptr, nullptr, true, 0, false, false, false, true},
    {"GS7BG", nullptr, nullptr, true, 0, false, false, false, true},
    {"XYZ", nullptr, nullptr, true, 0, false, false, false, true},
    {"ZMap", nullptr, nullptr, true, 0, false, false, false, true},
    {"GPKG", nullptr, nullptr, true, 0, false, false, false, true},
    {"netCDF", nullptr, nullptr, true, 0, false, false, false, true,
     "stores several value columns as separate variables (subdatasets), not as the bands of one raster"},
    {"FITS", nullptr, nullptr, false, 0, false, false, false, false},
    {"PDS4", nullptr, nullptr, false, 0, false, false, false, false},
    {"MFF", nullptr, nullptr, false, 0, false, false, false, false},  // but for a geographic CRS
};

/// The limits of `driver` writing files of extension `ext` (lower case, no dot), or nullptr.
const DriverLimits* limits_of(const std::string& driver, const std::string& ext) {
  for (const DriverLimits& l : kDriverLimits)
    if (driver == l.driver && (l.extension == nullptr || ext == l.extension)) return &l;
  return nullptr;
}

/// The advice of a refusal for a format of one band.
constexpr const char* kSeveralBandsAdvice =
    ": write .tif, .img or another format of several floating-point bands, or one value column at a time (--value)";

}  // namespace

std::string gdal_raster_driver(const std::string& path, const std::string& format, const std::string& where) {
  std::string ext = lower_extension(path);
  if (!ext.empty()) ext.erase(0, 1);
  if (format.empty() && is_geotiff_output(path, format)) return "GTiff";  // before COG, which claims them too
  register_drivers(format);
  GDALDriverManager* drivers = GetGDALDriverManager();
  if (!format.empty()) {
    GDALDriver* d = drivers->GetDriverByName(format.c_str());
    if (d == nullptr || !can_create_raster(d))
      throw UserError("--format", "'" + format + "' is no GDAL driver that creates rasters (gdalinfo --formats lists them)");
    if (const char* why = no_file_of_values(d->GetDescription()))
      throw UserError("--format", std::string("GDAL's ") + d->GetDescription() + " driver " + why + kFloatFormatsAdvice);
    if (const DriverLimits* limits = limits_of(d->GetDescription(), ext); limits != nullptr && limits->never != nullptr)
      throw UserError("--format", std::string("GDAL's ") + d->GetDescription() + " driver " + limits->never + kFloatFormatsAdvice);
    require_band_type(d, "Float32", "--format");
    return d->GetDescription();  // GDAL's spelling of the name, whatever the option's case
  }
  std::string known, one_band;  // the extensions of formats of several bands, and of one
  for (int k = 0; k < drivers->GetDriverCount(); ++k) {
    GDALDriver* d = drivers->GetDriver(k);
    if (!can_create_raster(d)) continue;
    const char* exts = d->GetMetadataItem(GDAL_DMD_EXTENSIONS);
    if (exts == nullptr) continue;
    std::istringstream list(exts);
    for (std::string e; list >> e;) {
      const DriverLimits* limits = limits_of(d->GetDescription(), ascii_lower(e));
      if (ascii_lower(e) == ext && !ext.empty()) {
        if (const char* why = no_file_of_values(d->GetDescription()))
          throw UserError(where, std::string("GDAL's ") + d->GetDescription() + " driver " + why + " (." + ext + ")" +
                                     kFloatFormatsAdvice);
        if (limits != nullptr && limits->never != nullptr)
          throw UserError(where, std::string("GDAL's ") + d->GetDescription() + " driver " + limits->never + " (." + ext + ")" +
                                     kFloatFormatsAdvice);
        require_band_type(d, "Float32", where);
        return d->GetDescription();
      }
      // The extensions that would be written, of a plain georeferenced raster of floats (without
      // conditions on its CRS or its pixels): radrecon's own (.png) and the refused left out.
      const bool plain = limits == nullptr || (limits->never == nullptr && limits->exact_bands == 0 && !limits->needs_crs &&
                                               !limits->needs_geographic_crs && !limits->needs_square_pixels &&
                                               limits->keeps_georeferencing);
      std::string& list = limits != nullptr && limits->one_band ? one_band : known;
      if (plain && no_file_of_values(d->GetDescription()) == nullptr && lists_band_type(d, "Float32") &&
          ascii_lower(e) != "png" && known.find(" ." + e + ",") == std::string::npos &&
          one_band.find(" ." + e + ",") == std::string::npos)
        list += " ." + e + ",";
    }
  }
  throw UserError(where, "unknown output extension '" + std::filesystem::path(path).extension().string() +
                             "': radrecon writes .csv, .pfm and .png, and through GDAL" + known.substr(0, known.size() - 1) +
                             (one_band.empty() ? "" : "; of one value column also" + one_band.substr(0, one_band.size() - 1)) +
                             " (or name a driver with --format)");
}

void check_gdal_raster(const std::string& path, const GeoRasterOptions& options, int channels, bool square_pixels) {
  const std::string driver = gdal_raster_driver(path, options.format, "--out");
  std::string ext = lower_extension(path);
  if (!ext.empty()) ext.erase(0, 1);
  const DriverLimits* limits = limits_of(driver, ext);
  if (limits == nullptr) return;
  const std::string its = "GDAL's " + driver + " driver ";
  const std::string columns = std::to_string(channels) + " value column" + (channels == 1 ? "" : "s");
  if (limits->exact_bands != 0 && channels != limits->exact_bands)
    throw UserError("--out", its + "writes " + std::to_string(limits->exact_bands) + " bands exactly" +
                                 (driver == "BAG" ? " (an elevation and its uncertainty)" : "") + "; the samples have " +
                                 columns + " (--value picks them)" + kFloatFormatsAdvice);
  if (limits->one_band && channels > 1)
    throw UserError("--out", its + (limits->several_bands != nullptr ? std::string(limits->several_bands) : "writes one band at most") +
                                 "; the samples have " + columns + kSeveralBandsAdvice);
  if (limits->needs_crs && options.crs.empty())
    throw UserError("--out", its + "needs a coordinate reference system: give --crs (e.g. EPSG:4326)" + kFloatFormatsAdvice);
  if (limits->needs_geographic_crs) {
    QuietGdal quiet;
    OGRSpatialReference srs;
    if (options.crs.empty() || srs.SetFromUserInput(options.crs.c_str()) != OGRERR_NONE || !srs.IsGeographic())
      throw UserError("--out", its + "writes its corners in geographic coordinates only: give a geographic --crs (e.g. "
                                     "EPSG:4326)" + kFloatFormatsAdvice);
  }
  if (limits->needs_square_pixels && !square_pixels)
    throw UserError("--out", its + "writes square pixels only: give --raster and --domain whose cells are as wide as tall" +
                                 kFloatFormatsAdvice);
}

std::vector<std::string> gdal_raster_files(const std::string& path) {
  register_drivers("");  // every driver: the raster may be of any format
  QuietGdal quiet;
  const std::unique_ptr<GDALDataset> raster(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
  if (!raster) return {};
  std::vector<std::string> files;
  char** list = raster->GetFileList();
  for (char** f = list; f != nullptr && *f != nullptr; ++f) files.emplace_back(*f);
  CSLDestroy(list);
  return files;
}

void check_gdal_crs(const std::string& crs) {
  if (crs.empty()) return;
  QuietGdal quiet;
  OGRSpatialReference srs;
  if (srs.SetFromUserInput(crs.c_str()) != OGRERR_NONE)
    throw UserError("--crs", "'" + crs + "' is no coordinate reference system GDAL knows (e.g. EPSG:2193, a WKT or PROJ string): " +
                                 QuietGdal::last_error());
}

std::vector<std::string> write_raster_gdal(const std::string& path, const std::string& staging, const Raster& raster,
                                           std::span<const double> values, int channels, const GeoRasterOptions& options) {
  RR_CHECK(channels >= 1 && values.size() == static_cast<size_t>(raster.width) * raster.height * channels,
           "raster values do not match the raster");
  const std::string driver_name = gdal_raster_driver(path, options.format, "--out");
  register_drivers(driver_name);
  QuietGdal quiet;
  GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName(driver_name.c_str());
  RR_CHECK(mem != nullptr && driver != nullptr, "GDAL drivers missing");
  const GDALDataType type = options.float64 ? GDT_Float64 : GDT_Float32;
  std::unique_ptr<GDALDataset> image(mem->Create("", raster.width, raster.height, channels, type, nullptr));
  if (!image) throw UserError(path, "GDAL cannot hold the raster in memory: " + QuietGdal::last_error());
  const Rect& d = raster.domain;
  double transform[6] = {d.x0, raster.dx(), 0, d.y1, 0, -raster.dy()};
  image->SetGeoTransform(transform);
  if (!options.crs.empty()) {
    OGRSpatialReference srs;
    srs.SetFromUserInput(options.crs.c_str());
    srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    image->SetSpatialRef(&srs);
  }
  std::vector<double> row(static_cast<size_t>(raster.width));
  for (int c = 0; c < channels; ++c) {
    GDALRasterBand* band = image->GetRasterBand(c + 1);
    band->SetNoDataValue(options.nodata);
    if (static_cast<size_t>(c) < options.band_names.size()) band->SetDescription(options.band_names[static_cast<size_t>(c)].c_str());
    for (int j = 0; j < raster.height; ++j) {
      // Stored row r is the raster's row height - 1 - r: north-up.
      const size_t first = static_cast<size_t>(raster.height - 1 - j) * raster.width;
      for (int i = 0; i < raster.width; ++i) {
        const double v = values[(first + i) * channels + c];
        row[static_cast<size_t>(i)] = std::isnan(v) ? options.nodata : v;
      }
      if (band->RasterIO(GF_Write, 0, j, raster.width, 1, row.data(), raster.width, 1, GDT_Float64, 0, 0) != CE_None)
        throw UserError(path, "GDAL cannot fill the raster: " + QuietGdal::last_error());
    }
  }
  // Written in the caller's fresh folder beside the output, which moves it: no half-written file
  // under the output's name, and side files (e.g. an ENVI header) move along.
  namespace fs = std::filesystem;
  const fs::path out(path);
  const fs::path parent = out.has_parent_path() ? out.parent_path() : fs::path(".");
  const fs::path tmp(staging);
  // MRF compresses by PNG by default, which takes no floating-point bands: DEFLATE, lossless.
  CPLStringList creation;
  if (driver_name == "MRF") creation.SetNameValue("COMPRESS", "DEFLATE");
  // netCDF's "history" attribute would hold the time and the staging folder's random name: two
  // runs of the same command wrote files that differed in it (a thread-count audit).
  if (driver_name == "netCDF") creation.SetNameValue("WRITE_GDAL_HISTORY", "NO");
  errno = 0;  // a failing write's reason, which GDAL's words may leave out (with_failed_write_reason())
  std::unique_ptr<GDALDataset> file(driver->CreateCopy((tmp / out.filename()).c_str(), image.get(), FALSE, creation.List(),
                                                        nullptr, nullptr));
  if (!file) {
    std::string why = with_failed_write_reason(QuietGdal::last_error());
    // The temporary folder is no name of the user's.
    for (size_t at; (at = why.find(tmp.filename().string() + "/")) != std::string::npos;) why.erase(at, tmp.filename().string().size() + 1);
    throw UserError(path, "GDAL's " + driver_name + " driver cannot write it: " + why);
  }
  file.reset();  // closes and flushes
  if (CPLGetLastErrorType() >= CE_Failure)
    throw UserError(path, "GDAL failed writing it: " + with_failed_write_reason(QuietGdal::last_error()));
  std::vector<std::string> warnings = read_back(path, (tmp / out.filename()).string(), driver_name, *image, options);
  // Every file written, checked before the caller moves any: none may land on an input.
  for (const fs::directory_entry& e : fs::directory_iterator(tmp)) {
    const fs::path to = parent / e.path().filename();
    std::error_code ec;
    for (const std::string& input : options.inputs)
      if (fs::exists(to, ec) && fs::equivalent(to, input, ec))
        throw UserError(path, "GDAL's " + driver_name + " driver writes '" + to.string() + "' beside it, which is the input file '" +
                                  input + "'; refusing to overwrite it (name the output otherwise)");
  }
  return warnings;
}

}  // namespace radrecon
