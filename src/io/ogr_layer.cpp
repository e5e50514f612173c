// The first layer of an OGR vector source (io/ogr_layer.h).

#include "io/ogr_layer.h"

#include <cmath>
#include <filesystem>
#include <mutex>
#include <string_view>

#include <cpl_error.h>

#include "core/error.h"
#include "core/parse.h"
#include "io/gdal_plugin.h"

namespace radrecon {

namespace {

/// kTableExtensions, as a list for a message: ".csv, .txt, ..., .tsv".
std::string table_names() {
  std::string out;
  for (const std::string_view e : kTableExtensions) out += (out.empty() ? "" : ", ") + std::string(e);
  return out;
}

}  // namespace

void register_ogr_drivers() {
  static std::once_flag once;
  std::call_once(once, [] { GDALAllRegister(); });
}

OgrLayer::OgrLayer(const std::string& path) : path_(path) {
  register_ogr_drivers();
  CPLPushErrorHandler(CPLQuietErrorHandler);
  CPLErrorReset();
  data_.reset(static_cast<GDALDataset*>(GDALOpenEx(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, nullptr, nullptr, nullptr)));
  const std::string reason = CPLGetLastErrorMsg();
  CPLPopErrorHandler();
  std::error_code ec;
  // A plain path (not a GDAL connection string such as PG:..., a URL or a /vsi... path) that
  // names nothing: said so, rather than left to GDAL's "not recognized".
  const bool plain = path.find(':') == std::string::npos && path.rfind("/vsi", 0) != 0;
  if (!data_ && plain && !std::filesystem::exists(path, ec)) throw UserError(path, "no such file");
  if (!data_)
    throw UserError(path, "cannot open as a vector source" + (reason.empty() ? std::string() : ": " + reason) +
                              (plain ? " (a CSV or XYZ table is read as one only under the names " + table_names() +
                                           " or no extension: rename it if it is one)"
                                     : std::string()));
  if (data_->GetLayerCount() < 1) throw UserError(path, "has no layer");
  layer_ = data_->GetLayer(0);
  // The first layer is read (docs/interpolate.md); the others, said so rather than left unseen.
  if (data_->GetLayerCount() > 1)
    warn(path + ": " + std::to_string(data_->GetLayerCount()) + " layers; the first, '" + layer_->GetName() +
         "', is read (the others are not)");
}

int OgrLayer::field(const std::string& name, const std::string& option) {
  for (int k = 0; k < fields().GetFieldCount(); ++k)
    if (ascii_lower(fields().GetFieldDefn(k)->GetNameRef()) == ascii_lower(name)) return k;
  std::string names;
  for (int k = 0; k < fields().GetFieldCount(); ++k) names += (names.empty() ? "" : ", ") + std::string(fields().GetFieldDefn(k)->GetNameRef());
  throw UserError(option, path_ + " has no field named '" + name + "' (its fields: " + (names.empty() ? "none" : names) + ")");
}

double OgrLayer::number(const OGRFeature& f, int k) {
  if (!f.IsFieldSetAndNotNull(k)) throw UserError(where(f), "field " + name(k) + " has no value");
  double v = 0;
  if (numeric(k)) {
    v = f.GetFieldAsDouble(k);
  } else if (text(k)) {
    const std::string_view t = trim_blanks(f.GetFieldAsString(k));
    if (parse_double(t, v) != NumberStatus::ok)
      throw UserError(where(f), "field " + name(k) + ": " + in_quotes(t) + " is not a finite number");
  } else {
    throw UserError(where(f), "field " + name(k) + " is not numeric (" +
                                  OGRFieldDefn::GetFieldTypeName(fields().GetFieldDefn(k)->GetType()) + ")");
  }
  if (!std::isfinite(v)) throw UserError(where(f), "field " + name(k) + " is not finite");
  return v;
}

}  // namespace radrecon
