// The GeoTIFF plugin (io/geotiff.h): libtiff writes the image, libgeotiff its GeoKeys, PROJ
// reads the CRS.

#include <algorithm>
#include <charconv>
#include <cerrno>
#include <cmath>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <mutex>
#include <string_view>
#include <string>
#include <vector>

#include <geotiff/geotiffio.h>
#include <geotiff/geovalues.h>
#include <geotiff/xtiffio.h>
#include <proj.h>
#include <tiffio.h>

#include "core/check.h"
#include "core/error.h"
#include "core/parse.h"
#include "io/geotiff.h"

namespace radrecon {

namespace {

/// Largest code a GeoKey's SHORT holds below GeoTIFF's "user-defined" 32767.
constexpr int kLargestGeoKeyCode = 32766;

/// The code `authority` gives as a GeoKey holds it (EPSG, 1 to kLargestGeoKeyCode), else 0.
int geokey_code(const char* authority, const char* code) {
  if (authority == nullptr || code == nullptr || std::string(authority) != "EPSG") return 0;
  const std::string text(code);
  int value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  return error == std::errc() && end == text.data() + text.size() && value >= 1 && value <= kLargestGeoKeyCode ? value
                                                                                                                : 0;
}

/// Whether `crs` is in a form GDAL's SetFromUserInput takes too (PROJ takes more, such as a bare
/// CRS name, which GDAL refuses): EPSG:n, urn:ogc:def:crs:EPSG::n, or a WKT CRS.
bool in_gdal_form(const std::string& crs) {
  const std::string lower = ascii_lower(crs);
  const auto code_after = [&](std::string_view prefix) {
    return lower.starts_with(prefix) && lower.size() > prefix.size() &&
           lower.find_first_not_of("0123456789", prefix.size()) == std::string::npos;
  };
  if (code_after("epsg:") || code_after("urn:ogc:def:crs:epsg::")) return true;
  for (const char* keyword : {"projcs[", "geogcs[", "projcrs[", "projectedcrs[", "geogcrs[", "geographiccrs[",
                              "geodcrs[", "geodeticcrs["})
    if (lower.starts_with(keyword)) return true;
  return false;
}

bool resolve_crs(const std::string& crs, GeoTiffCrs* out) {
  *out = GeoTiffCrs{};
  if (crs.empty()) return true;
  if (!in_gdal_form(crs)) return false;
  const std::unique_ptr<PJ_CONTEXT, decltype(&proj_context_destroy)> context(proj_context_create(),
                                                                              proj_context_destroy);
  if (!context) return false;
  proj_log_level(context.get(), PJ_LOG_NONE);
  const std::unique_ptr<PJ, decltype(&proj_destroy)> object(proj_create(context.get(), crs.c_str()), proj_destroy);
  if (!object) return false;
  GeoTiffCrs keys;
  const PJ_TYPE type = proj_get_type(object.get());
  keys.projected = type == PJ_TYPE_PROJECTED_CRS;
  if (!keys.projected && type != PJ_TYPE_GEOGRAPHIC_2D_CRS) return false;
  keys.epsg = geokey_code(proj_get_id_auth_name(object.get(), 0), proj_get_id_code(object.get(), 0));
  if (keys.epsg == 0) return false;
  const char* name = proj_get_name(object.get());
  keys.name = name != nullptr ? name : "";
  const std::unique_ptr<PJ, decltype(&proj_destroy)> axes(
      proj_crs_get_coordinate_system(context.get(), object.get()), proj_destroy);
  const char* unit_authority = nullptr;
  const char* unit_code = nullptr;
  if (axes && proj_cs_get_axis_info(context.get(), axes.get(), 0, nullptr, nullptr, nullptr, nullptr, nullptr,
                                    &unit_authority, &unit_code))
    keys.unit_epsg = geokey_code(unit_authority, unit_code);
  // EPSG's degree for axes is GeoTIFF's Angular_Degree (as GDAL writes it).
  constexpr int kEpsgAxisDegree = 9122;
  if (keys.unit_epsg == kEpsgAxisDegree) keys.unit_epsg = Angular_Degree;
  *out = keys;
  return true;
}

/// GDAL's metadata and no-data tags (its TIFF tags 42112, XML, and 42113, the value as text),
/// which libtiff must be told of.
constexpr ttag_t kTagGdalMetadata = 42112;
constexpr ttag_t kTagGdalNoData = 42113;
TIFFExtendProc parent_extender = nullptr;
void add_gdal_tags(TIFF* tif) {
  static const TIFFFieldInfo kFields[] = {
      {kTagGdalMetadata, -1, -1, TIFF_ASCII, FIELD_CUSTOM, 1, 0, const_cast<char*>("GDALMetadata")},
      {kTagGdalNoData, -1, -1, TIFF_ASCII, FIELD_CUSTOM, 1, 0, const_cast<char*>("GDALNoDataValue")}};
  TIFFMergeFieldInfo(tif, kFields, 2);
  if (parent_extender != nullptr) parent_extender(tif);
}

/// The bands' descriptions as GDAL's metadata tag holds them (GDAL reads them back as each band's
/// GetDescription()): <Item name="DESCRIPTION" sample="K" role="description">, XML-escaped.
std::string band_descriptions_xml(const std::vector<std::string>& names) {
  std::string xml = "<GDALMetadata>\n";
  for (size_t k = 0; k < names.size(); ++k) {
    xml += "  <Item name=\"DESCRIPTION\" sample=\"" + std::to_string(k) + "\" role=\"description\">";
    for (const char c : names[k]) {
      if (c == '&') xml += "&amp;";
      else if (c == '<') xml += "&lt;";
      else if (c == '>') xml += "&gt;";
      else if (c == '"') xml += "&quot;";
      else xml += c;
    }
    xml += "</Item>\n";
  }
  return xml + "</GDALMetadata>";
}

/// libtiff's last error on one file (its own handler, not the process-wide one: other code, GDAL
/// included, may use libtiff at the same time), naming `shown_as` rather than the temporary file.
struct TiffMessages {
  std::string file, shown_as, last;
  static int keep(TIFF*, void* self, const char* module, const char* format, va_list args) {
    auto& m = *static_cast<TiffMessages*>(self);
    char text[512];
    std::vsnprintf(text, sizeof text, format, args);
    m.last = (module != nullptr && *module ? std::string(module) + ": " : std::string()) + text;
    for (size_t at; !m.file.empty() && (at = m.last.find(m.file)) != std::string::npos;)
      m.last.replace(at, m.file.size(), m.shown_as);
    return 1;  // handled: not passed on to the process-wide handler
  }
  static int ignore(TIFF*, void*, const char*, const char*, va_list) { return 1; }
  std::string reason() const { return last.empty() ? "libtiff gave no reason" : last; }
};

/// Past this size (bytes of pixels) the file is a BigTIFF: a classic TIFF's offsets are 32-bit.
constexpr double kBigTiffBytes = 4.0e9;

void write(const std::filesystem::path& file, const std::string& shown_as, const Raster& raster,
           std::span<const double> values, int channels, const GeoRasterOptions& options, const GeoTiffCrs& crs) {
  const size_t width = static_cast<size_t>(raster.width), height = static_cast<size_t>(raster.height);
  RR_CHECK(channels >= 1 && width >= 1 && height >= 1 && values.size() == width * height * channels,
           "raster values do not match the raster");
  static std::once_flag tags;
  std::call_once(tags, [] {
    XTIFFInitialize();  // the GeoTIFF tags
    parent_extender = TIFFSetTagExtender(add_gdal_tags);
  });
  TiffMessages messages{file.string(), shown_as, {}};
  const std::unique_ptr<TIFFOpenOptions, decltype(&TIFFOpenOptionsFree)> open_options(TIFFOpenOptionsAlloc(),
                                                                                         TIFFOpenOptionsFree);
  if (!open_options) throw UserError(shown_as, "libtiff cannot start");
  TIFFOpenOptionsSetErrorHandlerExtR(open_options.get(), TiffMessages::keep, &messages);
  TIFFOpenOptionsSetWarningHandlerExtR(open_options.get(), TiffMessages::ignore, nullptr);
  const int bytes = options.float64 ? 8 : 4;
  const bool big = static_cast<double>(width) * height * channels * bytes > kBigTiffBytes;
  const std::unique_ptr<TIFF, decltype(&XTIFFClose)> tif(TIFFOpenExt(file.c_str(), big ? "w8" : "w", open_options.get()),
                                                         XTIFFClose);
  if (!tif) throw UserError(shown_as, "cannot create it: " + messages.reason());
  const auto require = [&](int ok, const char* what) {
    if (ok != 1)  // with the system's reason, which libtiff's words may leave out
      throw UserError(shown_as, std::string("libtiff cannot write ") + what + ": " + with_failed_write_reason(messages.reason()));
  };
  TIFF* t = tif.get();
  require(TIFFSetField(t, TIFFTAG_IMAGEWIDTH, static_cast<uint32_t>(width)), "the width");
  require(TIFFSetField(t, TIFFTAG_IMAGELENGTH, static_cast<uint32_t>(height)), "the height");
  require(TIFFSetField(t, TIFFTAG_SAMPLESPERPIXEL, static_cast<uint16_t>(channels)), "the band count");
  require(TIFFSetField(t, TIFFTAG_BITSPERSAMPLE, static_cast<uint16_t>(8 * bytes)), "the sample size");
  require(TIFFSetField(t, TIFFTAG_SAMPLEFORMAT, SAMPLEFORMAT_IEEEFP), "the sample format");
  require(TIFFSetField(t, TIFFTAG_PHOTOMETRIC, PHOTOMETRIC_MINISBLACK), "the photometric interpretation");
  require(TIFFSetField(t, TIFFTAG_PLANARCONFIG, PLANARCONFIG_CONTIG), "the band interleaving");
  require(TIFFSetField(t, TIFFTAG_COMPRESSION, COMPRESSION_NONE), "the compression");
  if (channels > 1) {  // bands past the first: unspecified extra samples, as GDAL writes them
    const std::vector<uint16_t> extra(static_cast<size_t>(channels - 1), EXTRASAMPLE_UNSPECIFIED);
    require(TIFFSetField(t, TIFFTAG_EXTRASAMPLES, static_cast<uint16_t>(extra.size()), extra.data()), "the extra samples");
  }
  require(TIFFSetField(t, TIFFTAG_ROWSPERSTRIP, std::min(static_cast<uint32_t>(height), TIFFDefaultStripSize(t, 0))),
          "the strip size");

  // Georeferencing: the top-left corner (x0, y1) is the tie point of pixel (0, 0), north-up.
  const Rect& d = raster.domain;
  const double scale[3] = {raster.dx(), raster.dy(), 0};
  const double tie[6] = {0, 0, 0, d.x0, d.y1, 0};
  require(TIFFSetField(t, TIFFTAG_GEOPIXELSCALE, 3, scale), "the pixel scale");
  require(TIFFSetField(t, TIFFTAG_GEOTIEPOINTS, 6, tie), "the tie point");
  char nodata[40];
  std::snprintf(nodata, sizeof nodata, "%.18g", options.nodata);  // GDAL's own spelling
  require(TIFFSetField(t, kTagGdalNoData, nodata), "the no-data value");
  if (!options.band_names.empty())
    require(TIFFSetField(t, kTagGdalMetadata, band_descriptions_xml(options.band_names).c_str()), "the bands' names");
  if (crs.epsg != 0) {  // the GeoKeys GDAL writes for an EPSG code; none without a CRS, as GDAL writes none
    const std::unique_ptr<GTIF, decltype(&GTIFFree)> keys(GTIFNew(t), GTIFFree);
    if (!keys) throw UserError(shown_as, "libgeotiff cannot start its keys");
    GTIF* k = keys.get();
    GTIFKeySet(k, GTModelTypeGeoKey, TYPE_SHORT, 1, crs.projected ? ModelTypeProjected : ModelTypeGeographic);
    GTIFKeySet(k, GTRasterTypeGeoKey, TYPE_SHORT, 1, RasterPixelIsArea);
    const bool named = !crs.name.empty();
    if (crs.projected) {
      GTIFKeySet(k, ProjectedCSTypeGeoKey, TYPE_SHORT, 1, crs.epsg);
      if (named) GTIFKeySet(k, GTCitationGeoKey, TYPE_ASCII, 0, crs.name.c_str());
      if (crs.unit_epsg != 0) GTIFKeySet(k, ProjLinearUnitsGeoKey, TYPE_SHORT, 1, crs.unit_epsg);
    } else {
      GTIFKeySet(k, GeographicTypeGeoKey, TYPE_SHORT, 1, crs.epsg);
      if (named) GTIFKeySet(k, GeogCitationGeoKey, TYPE_ASCII, 0, crs.name.c_str());
      if (crs.unit_epsg != 0) GTIFKeySet(k, GeogAngularUnitsGeoKey, TYPE_SHORT, 1, crs.unit_epsg);
    }
    require(GTIFWriteKeys(k), "the GeoKeys");
  }

  // Stored row r is the raster's row height - 1 - r: north-up.
  std::vector<unsigned char> row(width * channels * bytes);
  for (size_t r = 0; r < height; ++r) {
    const double* from = values.data() + (height - 1 - r) * width * channels;
    for (size_t k = 0; k < width * channels; ++k) {
      const double v = std::isnan(from[k]) ? options.nodata : from[k];
      if (options.float64) std::memcpy(row.data() + 8 * k, &v, 8);
      else {
        const float f = static_cast<float>(v);  // beyond a float's range: +-infinity, as GDAL writes it
        std::memcpy(row.data() + 4 * k, &f, 4);
      }
    }
    errno = 0;
    require(TIFFWriteScanline(t, row.data(), static_cast<uint32_t>(r), 0), "a row");
  }
  errno = 0;
  require(TIFFFlush(t), "the file's end");  // a full disk shows here
}

}  // namespace

}  // namespace radrecon

extern "C" __attribute__((visibility("default"))) const void* radrecon_geotiff_functions() {
  static const radrecon::GeoTiffFunctions functions{radrecon::resolve_crs, radrecon::write};
  return &functions;
}
