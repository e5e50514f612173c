// Samples and query points from OGR vector sources (io/gdal_vector.h).

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <string_view>

#include "core/error.h"
#include "core/parse.h"
#include "core/tolerances.h"
#include "io/gdal_vector.h"
#include "io/ogr_layer.h"

namespace radrecon {

namespace {

/// A point of a feature's geometry, its z NaN where it has none.
struct FeaturePoint {
  Vec2 p;
  double z = std::numeric_limits<double>::quiet_NaN();
};

/// Calls each(feature, point) for every point of every feature: a Point's, each of a
/// MultiPoint's (gdal_grid takes them too), or the one the fields --x and --y give.
template <typename PerFeature>
void for_each_point(OgrLayer& src, const CsvColumns& columns, PerFeature&& each) {
  const std::optional<int> xf = columns.x.empty() ? std::nullopt : std::optional<int>(src.field(columns.x, "--x"));
  const std::optional<int> yf = columns.y.empty() ? std::nullopt : std::optional<int>(src.field(columns.y, "--y"));
  if (xf.has_value() != yf.has_value()) throw UserError("--x/--y", "name both the x and the y field, or neither");
  src.layer().ResetReading();
  size_t count = 0;
  const auto take = [&](const OGRFeature& f, const FeaturePoint& q) {
    if (!(std::abs(q.p.x()) <= tol::kMaxSampleCoordinate && std::abs(q.p.y()) <= tol::kMaxSampleCoordinate))
      throw UserError(src.where(f), "its point is not finite or beyond the largest coordinate, " +
                                        format_number(tol::kMaxSampleCoordinate));
    each(f, q);
  };
  const auto of = [](const OGRPoint& point) {
    return FeaturePoint{Vec2(point.getX(), point.getY()),
                        point.Is3D() ? point.getZ() : std::numeric_limits<double>::quiet_NaN()};
  };
  for (std::unique_ptr<OGRFeature> f(src.layer().GetNextFeature()); f; f.reset(src.layer().GetNextFeature())) {
    ++count;
    if (xf) {
      take(*f, {Vec2(src.number(*f, *xf), src.number(*f, *yf))});
      continue;
    }
    const OGRGeometry* g = f->GetGeometryRef();
    const OGRwkbGeometryType type = g ? wkbFlatten(g->getGeometryType()) : wkbUnknown;
    if (type == wkbPoint && !g->IsEmpty()) {
      take(*f, of(*g->toPoint()));
    } else if (type == wkbMultiPoint && !g->IsEmpty()) {
      for (const OGRPoint* point : *g->toMultiPoint()) take(*f, of(*point));
    } else {
      throw UserError(src.where(*f), std::string("has ") + (g ? (g->IsEmpty() ? "an empty " : "") + std::string(g->getGeometryName()) : "no geometry") +
                                         "; expected a Point or MultiPoint (or name x and y fields with --x and --y)");
    }
  }
  if (count == 0) throw UserError(src.path(), std::string("layer '") + src.layer().GetName() + "' has no features");
}

/// Fields that number the features rather than measure anything (a shapefile's FID that
/// ogr2ogr adds, a GeoPackage's id): left out of the values unless --value names them.
bool numbers_features(std::string_view lower_name) {
  return lower_name == "fid" || lower_name == "id" || lower_name == "ogc_fid" || lower_name == "objectid" || lower_name == "gid";
}

/// Where a sample's values come from: fields, or the points' z (`z`).
struct ValueSources {
  std::vector<int> fields;
  bool z = false;
};

/// The text fields whose every value reads as a number (a CSV's columns through a VRT), and for
/// those of which only some do, the first feature whose value does not: "feature 2 holds 'n/a'"
/// ("" for a field of numbers, and for one of text that holds none).
std::vector<std::string> text_fields_not_numbers(OgrLayer& src, std::vector<bool>& all_numbers) {
  const int n = src.fields().GetFieldCount();
  all_numbers.assign(static_cast<size_t>(n), false);
  std::vector<std::string> why(static_cast<size_t>(n));
  std::vector<bool> some_number(static_cast<size_t>(n), false);
  for (int k = 0; k < n; ++k) all_numbers[static_cast<size_t>(k)] = src.text(k);
  const std::vector<bool> text = all_numbers;
  if (std::find(text.begin(), text.end(), true) == text.end()) return why;  // no pass needed
  src.layer().ResetReading();
  for (std::unique_ptr<OGRFeature> f(src.layer().GetNextFeature()); f; f.reset(src.layer().GetNextFeature()))
    for (int k = 0; k < n; ++k) {
      const size_t i = static_cast<size_t>(k);
      if (!text[i] || (!all_numbers[i] && some_number[i])) continue;  // decided
      const std::string_view t = trim_blanks(f->IsFieldSetAndNotNull(k) ? f->GetFieldAsString(k) : "");
      double v = 0;
      if (f->IsFieldSetAndNotNull(k) && parse_double(t, v) == NumberStatus::ok) {
        some_number[i] = true;
      } else if (all_numbers[i]) {
        all_numbers[i] = false;
        why[i] = "feature " + std::to_string(f->GetFID()) + (f->IsFieldSetAndNotNull(k) ? " holds " + in_quotes(t) : " has none");
      }
    }
  for (int k = 0; k < n; ++k)
    if (!some_number[static_cast<size_t>(k)]) why[static_cast<size_t>(k)].clear();  // text, not numbers
  return why;
}

/// Whether the first feature's geometry has z.
bool points_have_z(OgrLayer& src) {
  src.layer().ResetReading();
  const std::unique_ptr<OGRFeature> f(src.layer().GetNextFeature());
  return f && f->GetGeometryRef() != nullptr && f->GetGeometryRef()->Is3D();
}

/// The one z every point of the layer's Point and MultiPoint geometries has, if they all have the
/// same (a PointZ shapefile of z = 0, as exporters write them); nullopt otherwise.
std::optional<double> one_z(OgrLayer& src) {
  std::optional<double> z;
  bool same = true;
  const auto see = [&](const OGRPoint& p) {
    if (!p.Is3D()) same = false;
    else if (!z) z = p.getZ();
    else same = same && p.getZ() == *z;
  };
  src.layer().ResetReading();
  for (std::unique_ptr<OGRFeature> f(src.layer().GetNextFeature()); f && same; f.reset(src.layer().GetNextFeature())) {
    const OGRGeometry* g = f->GetGeometryRef();
    const OGRwkbGeometryType type = g ? wkbFlatten(g->getGeometryType()) : wkbUnknown;
    if (type == wkbPoint) see(*g->toPoint());
    else if (type == wkbMultiPoint)
      for (const OGRPoint* p : *g->toMultiPoint()) see(*p);
  }
  return same ? z : std::nullopt;
}

/// The values' sources, by --value, or by default (docs/interpolate.md, "Vector sources").
ValueSources value_sources(OgrLayer& src, const CsvColumns& columns, std::vector<std::string>& names) {
  ValueSources out;
  const bool z = columns.x.empty() && points_have_z(src);
  const int n = src.fields().GetFieldCount();
  const auto has_field = [&](const std::string& name) {
    for (int k = 0; k < n; ++k)
      if (ascii_lower(src.name(k)) == ascii_lower(name)) return true;
    return false;
  };
  for (const std::string& name : columns.values) {
    if (ascii_lower(name) == "z" && z && !has_field(name)) {  // the points' z, where no field is named so
      if (out.z) throw UserError("--value", "names z twice");
      out.z = true;
      names.push_back("z");
      continue;
    }
    out.fields.push_back(src.field(name, "--value"));
    names.push_back(src.name(out.fields.back()));
  }
  if (!columns.values.empty()) return out;
  // As gdal_grid: the points' z when they have one; unless every point has the same z and the
  // layer has numeric fields (a PointZ shapefile of z = 0 beside its depths: a flat raster).
  std::vector<bool> all_numbers;
  const std::vector<std::string> why_not = text_fields_not_numbers(src, all_numbers);
  std::vector<std::string> left_out[3];  // coordinates' names, the features' numbers, Booleans
  std::vector<int> fields;                // the numeric fields that would be interpolated
  for (int k = 0; k < n; ++k) {
    const std::string name = src.name(k), lower = ascii_lower(name);
    if (!(src.numeric(k) || all_numbers[static_cast<size_t>(k)]) || lower == ascii_lower(columns.x) ||
        lower == ascii_lower(columns.y))
      continue;
    if (columns.x.empty() ? names_a_coordinate(lower) : repeats_a_coordinate_name(lower)) left_out[0].push_back(name);
    else if (numbers_features(lower)) left_out[1].push_back(name);
    else if (src.boolean(k)) left_out[2].push_back(name);
    else fields.push_back(k);
  }
  std::string field_names;
  for (const int k : fields) field_names += (field_names.empty() ? "" : ", ") + src.name(k);
  if (z) {
    const std::optional<double> flat = fields.empty() ? std::nullopt : one_z(src);
    if (!flat) {
      out.z = true;
      names.push_back("z");
      if (!fields.empty())
        warn(src.path() + ": the values are the points' z (as gdal_grid takes them); the numeric fields " + field_names +
             " are not interpolated (--value names the fields to interpolate)");
      return out;
    }
    warn(src.path() + ": every point's z is " + format_number(*flat) + ": the numeric fields " + field_names +
         " are interpolated instead (--value z names the z)");
  }
  out.fields = fields;
  for (const int k : fields) names.push_back(src.name(k));
  const auto list = [](const std::vector<std::string>& names) {
    std::string s;
    for (const std::string& n : names) s += (s.empty() ? "" : ", ") + n;
    return s;
  };
  const char* reasons[3] = {columns.x.empty() ? "named as a coordinate" : "named as the output's coordinate columns (x, y)",
                            "numbering the features", "Boolean"};
  if (!out.fields.empty())
    for (int r = 0; r < 3; ++r)
      if (!left_out[r].empty()) {
        const bool one = left_out[r].size() == 1;
        warn(src.path() + (one ? ": the field " : ": the fields ") + list(left_out[r]) + (one ? " is" : " are") +
             " not interpolated: " + reasons[r] +
             (r == 0 ? std::string(", the points' coordinates coming from ") +
                           (columns.x.empty() ? "their geometry" : "--x and --y")
                     : std::string()) +
             " (--value names the fields to interpolate)");
      }
  // A field of text that holds numbers but in some features: not interpolated, said so (it was
  // left out in silence beside the numeric fields).
  if (!out.fields.empty())
    for (int k = 0; k < n; ++k)
      if (!why_not[static_cast<size_t>(k)].empty())
        warn(src.path() + ": the text field " + src.name(k) + " is not interpolated: " + why_not[static_cast<size_t>(k)] +
             ", not a number (--value " + src.name(k) + " names it, and then refuses that feature)");
  if (out.fields.empty()) {
    std::string found;  // the fields there are, with their types (a number written as a string is text)
    for (int k = 0; k < n; ++k) {
      const OGRFieldDefn* d = src.fields().GetFieldDefn(k);
      found += (found.empty() ? "" : ", ") + std::string(d->GetNameRef()) + " (" +
               OGRFieldDefn::GetFieldTypeName(d->GetType()) +
               (why_not[static_cast<size_t>(k)].empty() ? "" : ": " + why_not[static_cast<size_t>(k)]) + ")";
    }
    std::string left;
    for (int r = 0; r < 3; ++r)
      if (!left_out[r].empty()) left += std::string("; ") + reasons[r] + ", left out: " + list(left_out[r]);
    throw UserError(src.path(), "has no numeric field to interpolate (its fields: " + (found.empty() ? "none" : found) +
                                    left + "); name one with --value");
  }
  return out;
}

}  // namespace

ScatteredSamples read_samples_ogr(const std::string& path, std::vector<std::string>* value_names, const CsvColumns& columns) {
  OgrLayer src(path);
  // An empty layer is said to be so before its fields are looked at.
  src.layer().ResetReading();
  if (std::unique_ptr<OGRFeature>(src.layer().GetNextFeature()) == nullptr)
    throw UserError(path, std::string("layer '") + src.layer().GetName() + "' has no features");
  std::vector<std::string> names;
  const ValueSources sources = value_sources(src, columns, names);
  ScatteredSamples s;
  s.channels = static_cast<int>(sources.fields.size()) + (sources.z ? 1 : 0);
  const auto check = [&](const OGRFeature& f, const std::string& what, double v) {
    if (std::abs(v) > tol::kMaxSampleValue)
      throw UserError(src.where(f), what + ": " + format_number(v) + " is beyond the largest value, " +
                                        format_number(tol::kMaxSampleValue));
    return v;
  };
  for_each_point(src, columns, [&](const OGRFeature& f, const FeaturePoint& q) {
    s.points.push_back(q.p);
    for (const int k : sources.fields) s.values.push_back(check(f, "field " + src.name(k), src.number(f, k)));
    if (sources.z) {
      if (!std::isfinite(q.z)) throw UserError(src.where(f), "its point has no z (or not a finite one); --value names a field instead");
      s.values.push_back(check(f, "its z", q.z));
    }
  });
  if (value_names) *value_names = names;
  return s;
}

std::vector<Vec2> read_queries_ogr(const std::string& path, const CsvColumns& columns) {
  OgrLayer src(path);
  std::vector<Vec2> points;
  for_each_point(src, columns, [&](const OGRFeature&, const FeaturePoint& q) { points.push_back(q.p); });
  return points;
}

}  // namespace radrecon
