// Barrier lines, the files and the CRS of OGR vector sources (io/gdal_vector.h).

#include "io/gdal_vector.h"

#include <cmath>
#include <fstream>
#include <iterator>
#include <memory>
#include <optional>
#include <string_view>

#include <cpl_conv.h>
#include <cpl_error.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>

#include <nlohmann/json.hpp>

#include "core/barrier_line.h"
#include "core/error.h"
#include "core/parse.h"
#include "core/tolerances.h"
#include "io/ogr_layer.h"

namespace radrecon {

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

namespace {

/// The vector source at `path` opened read-only without a word: null when GDAL cannot.
std::unique_ptr<GDALDataset> open_quietly(const std::string& path) {
  register_ogr_drivers();
  CPLPushErrorHandler(CPLQuietErrorHandler);
  std::unique_ptr<GDALDataset> data(
      static_cast<GDALDataset*>(GDALOpenEx(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, nullptr, nullptr, nullptr)));
  CPLPopErrorHandler();
  return data;
}

}  // namespace

/// Whether a GeoJSON file names its CRS (the "crs" member of its top level, as GeoJSON before
/// RFC 7946 wrote it): without one, GDAL reports WGS 84 whatever the coordinates are.
bool geojson_names_crs(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const nlohmann::json doc = nlohmann::json::parse(text, nullptr, false);
  return doc.is_object() && doc.contains("crs") && !doc["crs"].is_null();
}

std::string ogr_source_crs(const std::string& path) {
  const std::unique_ptr<GDALDataset> data = open_quietly(path);
  if (!data || data->GetLayerCount() < 1) return {};
  const OGRSpatialReference* declared = data->GetLayer(0)->GetSpatialRef();
  if (declared == nullptr) return {};
  // GeoJSON (RFC 7946: WGS 84 always) says nothing of files of local or projected coordinates,
  // which are common; only a "crs" member it names counts.
  const std::string driver = data->GetDriver() != nullptr ? data->GetDriver()->GetDescription() : "";
  if ((driver == "GeoJSON" && !geojson_names_crs(path)) || driver == "GeoJSONSeq" || driver == "TopoJSON") return {};
  OGRSpatialReference srs(*declared);
  // An EPSG code where the CRS is one (radrecon's own GeoTIFF writer takes those), else its WKT.
  const char* authority = srs.GetAuthorityName(nullptr);
  const char* code = srs.GetAuthorityCode(nullptr);
  if (authority != nullptr && code != nullptr && std::string_view(authority) == "EPSG") return std::string("EPSG:") + code;
  char* wkt = nullptr;
  const char* const options[] = {"FORMAT=WKT2_2019", nullptr};
  if (srs.exportToWkt(&wkt, options) != OGRERR_NONE || wkt == nullptr) {
    CPLFree(wkt);
    return {};
  }
  std::string out(wkt);
  CPLFree(wkt);
  return out;
}

bool same_crs(const std::string& a, const std::string& b) {
  OGRSpatialReference x, y;
  CPLPushErrorHandler(CPLQuietErrorHandler);
  const bool read = x.SetFromUserInput(a.c_str()) == OGRERR_NONE && y.SetFromUserInput(b.c_str()) == OGRERR_NONE;
  CPLPopErrorHandler();
  return !read || x.IsSame(&y);  // one GDAL cannot read is no evidence of a difference
}

std::vector<std::string> ogr_source_files(const std::string& path) {
  const std::unique_ptr<GDALDataset> data = open_quietly(path);
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
