#include "io/geojson.h"

#include <cctype>
#include <filesystem>

#include <cmath>

#include <nlohmann/json.hpp>

#include "core/barrier_line.h"
#include "core/error.h"
#include "core/parse.h"
#include "core/tolerances.h"
#include "io/gdal_plugin.h"
#include "io/json_reader.h"

namespace radrecon {

namespace {

using json = nlohmann::json;

/// GeometryCollections nested deeper than this are refused (RFC 7946 advises against nesting
/// them at all): the reader recurses into them, and a hostile file must not exhaust the stack.
constexpr int kMaxCollectionDepth = 64;

/// The geometry types that hold lines, and (with the collection of geometries) all that are read.
const std::string kLineTypes = "LineString, MultiLineString, Polygon or MultiPolygon";
const std::string kGeometryTypes = "LineString, MultiLineString, Polygon, MultiPolygon or GeometryCollection";

/// Collects the polylines of one document, reporting every problem with its field path.
class BarrierReader {
 public:
  explicit BarrierReader(const std::string& source) : r_(source) {}

  /// The top level: a FeatureCollection, a Feature or a geometry.
  void document(const json& doc) {
    const std::string type = type_of(doc, "");
    if (type == "FeatureCollection") {
      const json& features = r_.member(doc, "features", "");
      if (!features.is_array()) r_.fail("features", "must be an array of Features");
      for (size_t i = 0; i < features.size(); ++i) {
        const std::string fp = JsonReader::at("features", i);
        if (type_of(features[i], fp) != "Feature") r_.fail(JsonReader::join(fp, "type"), "must be \"Feature\"");
        feature(features[i], fp);
      }
    } else if (type == "Feature") {
      feature(doc, "");
    } else {
      geometry(doc, "", 0);
    }
  }

  std::vector<Polyline> lines;

 private:
  /// `path` for a message: the field, or "(top level)".
  static std::string field(const std::string& path) { return path.empty() ? "(top level)" : path; }

  /// The "type" of the GeoJSON object `j`.
  std::string type_of(const json& j, const std::string& path) const {
    if (!j.is_object()) r_.fail(field(path), "must be a GeoJSON object {\"type\": ...}");
    if (!j.contains("type")) r_.fail(JsonReader::join(path, "type"), "missing (every GeoJSON object names its type)");
    return r_.string(j["type"], JsonReader::join(path, "type"));
  }

  /// A Feature: its geometry, if not null (a Feature without a location).
  void feature(const json& j, const std::string& path) {
    const std::string gp = JsonReader::join(path, "geometry");
    if (!j.contains("geometry")) r_.fail(gp, "missing (a Feature without a location has \"geometry\": null)");
    if (j["geometry"].is_null()) return;
    geometry(j["geometry"], gp, 0);
  }

  /// A geometry object; `depth` counts the GeometryCollections around it.
  void geometry(const json& j, const std::string& path, int depth) {
    const std::string type = type_of(j, path);
    const std::string tp = JsonReader::join(path, "type");
    if (type == "GeometryCollection") {
      if (depth >= kMaxCollectionDepth)
        r_.fail(field(path), "GeometryCollections nested more than " + std::to_string(kMaxCollectionDepth) + " deep");
      const std::string gp = JsonReader::join(path, "geometries");
      const json& geometries = r_.member(j, "geometries", path);
      if (!geometries.is_array()) r_.fail(gp, "must be an array of geometries");
      for (size_t i = 0; i < geometries.size(); ++i) geometry(geometries[i], JsonReader::at(gp, i), depth + 1);
      return;
    }
    if (type == "Point" || type == "MultiPoint")
      r_.fail(tp, "a " + type + " cannot be a barrier: barriers are lines (" + kLineTypes + ")");
    if (type == "Feature" || type == "FeatureCollection")
      r_.fail(tp, "a " + type + " where a geometry belongs (" + kGeometryTypes + ")");
    if (type != "LineString" && type != "MultiLineString" && type != "Polygon" && type != "MultiPolygon")
      r_.fail(tp, "unknown GeoJSON type " + in_quotes(type) + "; barriers are read from " + kGeometryTypes);

    const std::string cp = JsonReader::join(path, "coordinates");
    const json& coords = r_.member(j, "coordinates", path);
    if (type == "LineString") {
      lines.push_back(positions(coords, cp, false));
    } else if (type == "Polygon") {
      polygon(coords, cp);
    } else {  // MultiLineString, MultiPolygon: an array of the former (possibly empty)
      const bool polygons = type == "MultiPolygon";
      if (!coords.is_array())
        r_.fail(cp, polygons ? "must be an array of Polygon coordinates [[[x, y], ...], ...]"
                             : "must be an array of LineString coordinates [[x, y], ...]");
      for (size_t i = 0; i < coords.size(); ++i) {
        if (polygons)
          polygon(coords[i], JsonReader::at(cp, i));
        else
          lines.push_back(positions(coords[i], JsonReader::at(cp, i), false));
      }
    }
  }

  /// A Polygon's coordinates: its rings, exterior first, each a closed polyline.
  void polygon(const json& rings, const std::string& path) {
    if (!rings.is_array() || rings.empty())
      r_.fail(path, "expected a Polygon's rings [[[x, y], ...], ...], the exterior ring first");
    for (size_t i = 0; i < rings.size(); ++i) lines.push_back(positions(rings[i], JsonReader::at(path, i), true));
  }

  /// A LineString's positions, or (`ring`) a Polygon's closed ring.
  Polyline positions(const json& j, const std::string& path, bool ring) const {
    if (!j.is_array()) r_.fail(path, ring ? "expected a ring [[x, y], ...]" : "expected an array of positions [[x, y], ...]");
    // The positions first, then the line: [x, y] where [[x, y], ...] belongs is named as such.
    Polyline line;
    line.reserve(j.size());
    for (size_t i = 0; i < j.size(); ++i) line.push_back(position(j[i], JsonReader::at(path, i)));
    if (const auto defect = barrier_line_defect(
            line, ring ? BarrierLineKind::polygon_ring : BarrierLineKind::line_string, "position"))
      r_.fail(defect->point ? JsonReader::at(path, *defect->point) : path, defect->what);
    return line;
  }

  /// [x, y, ...]: x and y; further elements (z) must be numbers and are ignored.
  Vec2 position(const json& j, const std::string& path) const {
    if (j.is_number()) r_.fail(path, "expected a position [x, y], found a number");
    if (!j.is_array() || j.size() < 2) r_.fail(path, "expected a position [x, y]");
    for (size_t k = 0; k < j.size(); ++k) {
      const std::string kp = JsonReader::at(path, k);
      const double v = r_.number(j[k], kp);
      if (k < 2 && std::abs(v) > tol::kMaxSampleCoordinate)
        r_.fail(kp, format_number(v) + " is beyond the largest coordinate, " + format_number(tol::kMaxSampleCoordinate));
    }
    return Vec2(j[0].get<double>(), j[1].get<double>());
  }

  const JsonReader r_;
};

}  // namespace

std::vector<Polyline> read_geojson_barriers(const std::string& path) {
  const std::string text = read_text_file(path, "barrier file");
  if (text.find_first_not_of(" \t\r\n") == std::string::npos) throw UserError(path, "empty file: no barrier lines");
  const JsonReader r(path);
  BarrierReader reader(path);
  // A GIS tool's file: a key repeated among a feature's properties, which radrecon does not read,
  // is no reason to refuse it.
  reader.document(r.parse(text, "GeoJSON file", JsonReader::Keys::as_parsed));
  if (reader.lines.empty())
    throw UserError(path, "no barrier lines: no " + kLineTypes + " (a Feature whose geometry is null holds none)");
  return std::move(reader.lines);
}

Barriers read_barriers_file(const std::string& path, const std::string& where) {
  const std::string ext = lower_extension(path);
  Result<Barriers> barriers = Barriers::from_polylines(ext == ".geojson" || ext == ".json"
                                                           ? read_geojson_barriers(path)
                                                           : gdal_functions(where).read_barriers(path));
  if (!barriers) throw UserError(path, barriers.reason());
  return std::move(barriers).value();
}

}  // namespace radrecon
