#include "io/gdal_vector.h"

#include <cmath>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <string_view>

#include <cpl_error.h>
#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include "core/barrier_line.h"
#include "core/error.h"
#include "core/parse.h"
#include "core/tolerances.h"
#include "io/gdal_plugin.h"

namespace radrecon {

namespace {

/// kTableExtensions, as a list for a message: ".csv, .txt, ..., .tsv".
std::string table_names() {
  std::string out;
  for (const std::string_view e : kTableExtensions) out += (out.empty() ? "" : ", ") + std::string(e);
  return out;
}

/// GDAL's drivers, registered on first use.
void register_drivers() {
  static std::once_flag once;
  std::call_once(once, [] { GDALAllRegister(); });
}

/// The first layer of the vector source at `path`, opened read-only.
class OgrLayer {
 public:
  explicit OgrLayer(const std::string& path) : path_(path) {
    register_drivers();
    CPLPushErrorHandler(CPLQuietErrorHandler);
    CPLErrorReset();
    data_.reset(static_cast<GDALDataset*>(
        GDALOpenEx(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, nullptr, nullptr, nullptr)));
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

  OGRLayer& layer() { return *layer_; }
  const std::string& path() const { return path_; }
  OGRFeatureDefn& fields() { return *layer_->GetLayerDefn(); }
  std::string where(const OGRFeature& f) const {
    return path_ + ": layer '" + layer_->GetName() + "', feature " + std::to_string(f.GetFID());
  }

  /// The field named `name` (case-insensitive) for option `option`.
  int field(const std::string& name, const std::string& option) {
    for (int k = 0; k < fields().GetFieldCount(); ++k)
      if (ascii_lower(fields().GetFieldDefn(k)->GetNameRef()) == ascii_lower(name)) return k;
    std::string names;
    for (int k = 0; k < fields().GetFieldCount(); ++k) names += (names.empty() ? "" : ", ") + std::string(fields().GetFieldDefn(k)->GetNameRef());
    throw UserError(option, path_ + " has no field named '" + name + "' (its fields: " + (names.empty() ? "none" : names) + ")");
  }

  bool numeric(int k) {
    const OGRFieldType t = fields().GetFieldDefn(k)->GetType();
    return t == OFTReal || t == OFTInteger || t == OFTInteger64;
  }

  /// The finite number in field k of feature f.
  double number(const OGRFeature& f, int k) {
    const std::string name = fields().GetFieldDefn(k)->GetNameRef();
    if (!f.IsFieldSetAndNotNull(k)) throw UserError(where(f), "field " + name + " has no value");
    if (!numeric(k)) throw UserError(where(f), "field " + name + " is not numeric");
    const double v = f.GetFieldAsDouble(k);
    if (!std::isfinite(v)) throw UserError(where(f), "field " + name + " is not finite");
    return v;
  }

 private:
  std::string path_;
  std::unique_ptr<GDALDataset> data_;
  OGRLayer* layer_ = nullptr;
};

/// Reads the (x, y) of every feature and, for samples, its values.
template <typename PerFeature>
void for_each_point(OgrLayer& src, const CsvColumns& columns, PerFeature&& each) {
  const std::optional<int> xf = columns.x.empty() ? std::nullopt : std::optional<int>(src.field(columns.x, "--x"));
  const std::optional<int> yf = columns.y.empty() ? std::nullopt : std::optional<int>(src.field(columns.y, "--y"));
  if (xf.has_value() != yf.has_value()) throw UserError("--x/--y", "name both the x and the y field, or neither");
  src.layer().ResetReading();
  size_t count = 0;
  for (std::unique_ptr<OGRFeature> f(src.layer().GetNextFeature()); f; f.reset(src.layer().GetNextFeature())) {
    Vec2 p;
    if (xf) {
      p = Vec2(src.number(*f, *xf), src.number(*f, *yf));
    } else {
      const OGRGeometry* g = f->GetGeometryRef();
      if (g == nullptr || wkbFlatten(g->getGeometryType()) != wkbPoint)
        throw UserError(src.where(*f), std::string("has ") + (g ? g->getGeometryName() : "no geometry") +
                                           "; expected a Point (or name x and y fields with --x and --y)");
      const OGRPoint* point = g->toPoint();
      p = Vec2(point->getX(), point->getY());
    }
    if (!(std::abs(p.x()) <= tol::kMaxSampleCoordinate && std::abs(p.y()) <= tol::kMaxSampleCoordinate))
      throw UserError(src.where(*f), "its point is not finite or beyond the largest coordinate, " +
                                         format_number(tol::kMaxSampleCoordinate));
    each(*f, p);
    ++count;
  }
  if (count == 0) throw UserError(src.path(), std::string("layer '") + src.layer().GetName() + "' has no features");
}

}  // namespace

ScatteredSamples read_samples_ogr(const std::string& path, std::vector<std::string>* value_names, const CsvColumns& columns) {
  OgrLayer src(path);
  std::vector<int> value_fields;
  for (const std::string& name : columns.values) value_fields.push_back(src.field(name, "--value"));
  if (columns.values.empty()) {
    // Every numeric field but the coordinates': those --x and --y name, and fields named x or y,
    // which (beside a point geometry, as ogr2ogr keeps a CSV's columns) would repeat the output's
    // own x and y columns.
    std::string left_out;
    for (int k = 0; k < src.fields().GetFieldCount(); ++k) {
      const std::string name = ascii_lower(src.fields().GetFieldDefn(k)->GetNameRef());
      if (!src.numeric(k) || name == ascii_lower(columns.x) || name == ascii_lower(columns.y)) continue;
      if (repeats_a_coordinate_name(name)) {
        left_out += (left_out.empty() ? "" : ", ") + std::string(src.fields().GetFieldDefn(k)->GetNameRef());
        continue;
      }
      value_fields.push_back(k);
    }
    if (!left_out.empty() && !value_fields.empty())
      warn(path + (left_out.find(',') == std::string::npos ? ": the field " + left_out + " is not interpolated: it is"
                                                            : ": the fields " + left_out + " are not interpolated: they are") +
           " named as the output's coordinate columns (x, y), the points' coordinates coming from " +
           (columns.x.empty() ? std::string("their geometry") : "--x and --y") + " (--value names the fields to interpolate)");
  }
  if (value_fields.empty()) {
    std::string found;  // the fields there are, with their types (a number written as a string is text)
    for (int k = 0; k < src.fields().GetFieldCount(); ++k) {
      const OGRFieldDefn* d = src.fields().GetFieldDefn(k);
      found += (found.empty() ? "" : ", ") + std::string(d->GetNameRef()) + " (" +
               OGRFieldDefn::GetFieldTypeName(d->GetType()) + ")";
    }
    throw UserError(path, "has no numeric field to interpolate (its fields: " + (found.empty() ? "none" : found) +
                              "; a number in quotes is a string); name one with --value");
  }
  ScatteredSamples s;
  s.channels = static_cast<int>(value_fields.size());
  for_each_point(src, columns, [&](const OGRFeature& f, const Vec2& p) {
    s.points.push_back(p);
    for (const int k : value_fields) {
      const double v = src.number(f, k);
      if (std::abs(v) > tol::kMaxSampleValue)
        throw UserError(src.where(f), "field " + std::string(src.fields().GetFieldDefn(k)->GetNameRef()) + ": " +
                                          format_number(v) + " is beyond the largest value, " +
                                          format_number(tol::kMaxSampleValue));
      s.values.push_back(v);
    }
  });
  if (value_names) {
    value_names->clear();
    for (const int k : value_fields) value_names->push_back(src.fields().GetFieldDefn(k)->GetNameRef());
  }
  return s;
}

std::vector<Vec2> read_queries_ogr(const std::string& path, const CsvColumns& columns) {
  OgrLayer src(path);
  std::vector<Vec2> points;
  for_each_point(src, columns, [&](const OGRFeature&, const Vec2& p) { points.push_back(p); });
  return points;
}

namespace {

/// GDAL's warning for an unclosed Polygon ring, which it reads as it is: the reader below
/// refuses the ring itself, naming it, and the warning's advice (a configuration option that
/// makes GDAL drop the geometry) is not radrecon's.
void quiet_unclosed_rings(CPLErr level, CPLErrorNum number, const char* message) {
  if (level == CE_Warning && std::string_view(message).starts_with("Non closed ring detected")) return;
  CPLDefaultErrorHandler(level, number, message);
}

}  // namespace

std::vector<Polyline> read_ogr_barriers(const std::string& path) {
  OgrLayer src(path);
  std::vector<Polyline> lines;
  // One line of a feature's geometry: `part` names it within the feature ("" for a LineString,
  // "line 2" of a MultiLineString, "ring 1" of a Polygon, "polygon 2, ring 1" of a
  // MultiPolygon; counted from 1, the exterior ring first), as the messages do.
  const auto add = [&](const OGRFeature& f, const OGRSimpleCurve& l, const std::string& part, BarrierLineKind kind) {
    const auto where = [&](std::optional<size_t> point) {
      std::string w = src.where(f);
      if (!part.empty()) w += ", " + part;
      if (point) w += ", point " + std::to_string(*point + 1);
      return w;
    };
    Polyline line;
    for (int k = 0; k < l.getNumPoints(); ++k) {
      const Vec2 p(l.getX(k), l.getY(k));
      // As GeoJSON barriers (geojson.h): beyond it squared distances overflow.
      if (!(std::abs(p.x()) <= tol::kMaxSampleCoordinate && std::abs(p.y()) <= tol::kMaxSampleCoordinate))
        throw UserError(where(static_cast<size_t>(k)), "not finite or beyond the largest coordinate, " +
                                                           format_number(tol::kMaxSampleCoordinate));
      line.push_back(p);
    }
    // The rules of GeoJSON's barriers (core/barrier_line.h), in OGR's words.
    if (const auto defect = barrier_line_defect(line, kind, "point")) throw UserError(where(defect->point), defect->what);
    lines.push_back(std::move(line));
  };
  // A Polygon's rings; `part` names the polygon within a MultiPolygon ("polygon 2"), else "".
  const auto polygon = [&](const OGRFeature& f, const OGRPolygon& p, const std::string& part) {
    const std::string before = part.empty() ? std::string() : part + ", ";
    // A Polygon without rings is refused as from GeoJSON: the barrier meant is not there.
    if (p.IsEmpty()) throw UserError(src.where(f) + (part.empty() ? std::string() : ", " + part), "an empty Polygon (no ring)");
    int k = 0;
    for (const OGRLinearRing* r : p) add(f, *r, before + "ring " + std::to_string(++k), BarrierLineKind::polygon_ring);
  };
  CPLPushErrorHandler(quiet_unclosed_rings);
  struct PopHandler {
    ~PopHandler() { CPLPopErrorHandler(); }
  } pop;
  src.layer().ResetReading();
  for (std::unique_ptr<OGRFeature> f(src.layer().GetNextFeature()); f; f.reset(src.layer().GetNextFeature())) {
    const OGRGeometry* g = f->GetGeometryRef();
    if (g == nullptr) continue;
    switch (wkbFlatten(g->getGeometryType())) {
      case wkbLineString: add(*f, *g->toLineString(), "", BarrierLineKind::line_string); break;
      case wkbMultiLineString: {
        int k = 0;
        for (const OGRLineString* l : *g->toMultiLineString())
          add(*f, *l, "line " + std::to_string(++k), BarrierLineKind::line_string);
        break;
      }
      case wkbPolygon: polygon(*f, *g->toPolygon(), ""); break;
      case wkbMultiPolygon: {
        int k = 0;
        for (const OGRPolygon* p : *g->toMultiPolygon()) polygon(*f, *p, "polygon " + std::to_string(++k));
        break;
      }
      default:
        throw UserError(src.where(*f), std::string("has a ") + g->getGeometryName() + "; a barrier is a line or a polygon's ring");
    }
  }
  if (lines.empty()) throw UserError(path, "holds no barrier line");
  return lines;
}

std::vector<std::string> ogr_source_files(const std::string& path) {
  register_drivers();
  CPLPushErrorHandler(CPLQuietErrorHandler);
  std::unique_ptr<GDALDataset> data(
      static_cast<GDALDataset*>(GDALOpenEx(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, nullptr, nullptr, nullptr)));
  CPLPopErrorHandler();
  std::vector<std::string> files;
  if (data)
    if (char** list = data->GetFileList()) {
      for (char** f = list; *f != nullptr; ++f) files.emplace_back(*f);
      CSLDestroy(list);
    }
  if (files.empty()) files.push_back(path);
  return files;
}

}  // namespace radrecon
