// Barrier files (GeoJSON): every accepted form gives exactly the polylines written in it, in
// document order, and every refusal names the file and the field (or the line).

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "io/geojson.h"
#include "reconstruct/barriers.h"
#include "support/temp_dir.h"

namespace radrecon {
namespace geojson_test {

namespace fs = std::filesystem;

class GeojsonBarriers : public ::testing::Test {
 protected:
  fs::path write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name, std::ios::binary) << text;
    return dir_ / name;
  }
  /// The polylines of `text` read as b.geojson.
  std::vector<Polyline> read(const std::string& text) const {
    return read_geojson_barriers(write("b.geojson", text).string());
  }
  /// The message of reading `text` as b.geojson, or "" if it is accepted.
  std::string refusal(const std::string& text) const {
    return testing_support::user_error_message([&] { read(text); });
  }
  /// Whether reading `text` is refused with a message that holds every one of `parts`.
  ::testing::AssertionResult RefusedMentioning(const std::string& text, const std::vector<std::string>& parts) const {
    return testing_support::refused_mentioning([&] { read(text); }, parts) << " (" << text << ")";
  }
  testing_support::TempDir dir_{"radrecon_geojson_test"};
};

/// A short way to write expected polylines.
std::vector<Polyline> lines(std::initializer_list<std::initializer_list<std::pair<double, double>>> ls) {
  std::vector<Polyline> out;
  for (const auto& l : ls) {
    Polyline line;
    for (const auto& [x, y] : l) line.emplace_back(x, y);
    out.push_back(line);
  }
  return out;
}

TEST_F(GeojsonBarriers, ALineStringGeometry) {
  EXPECT_EQ(read(R"({"type": "LineString", "coordinates": [[0, 0], [1.5, -2], [0.1, 3e2]]})"),
            lines({{{0, 0}, {1.5, -2}, {0.1, 300}}}));
}

TEST_F(GeojsonBarriers, ZAndFurtherElementsOfAPositionAreIgnored) {
  EXPECT_EQ(read(R"({"type": "LineString", "coordinates": [[1, 2, 3], [4, 5, -6.5, 7], [8, 9]]})"),
            lines({{{1, 2}, {4, 5}, {8, 9}}}));
}

TEST_F(GeojsonBarriers, AMultiLineStringGivesItsLinesInOrder) {
  EXPECT_EQ(read(R"({"type": "MultiLineString", "coordinates": [[[0, 0], [1, 0]], [[5, 5], [5, 6], [6, 6]]]})"),
            lines({{{0, 0}, {1, 0}}, {{5, 5}, {5, 6}, {6, 6}}}));
}

TEST_F(GeojsonBarriers, APolygonGivesEachRingClosedHolesIncluded) {
  EXPECT_EQ(read(R"({"type": "Polygon", "coordinates": [
                      [[0, 0], [10, 0], [10, 10], [0, 10], [0, 0]],
                      [[2, 2], [2, 3], [3, 3], [2, 2]]]})"),
            lines({{{0, 0}, {10, 0}, {10, 10}, {0, 10}, {0, 0}}, {{2, 2}, {2, 3}, {3, 3}, {2, 2}}}));
}

TEST_F(GeojsonBarriers, AMultiPolygonGivesItsRingsInOrder) {
  EXPECT_EQ(read(R"({"type": "MultiPolygon", "coordinates": [
                      [[[0, 0], [1, 0], [1, 1], [0, 0]]],
                      [[[5, 5], [7, 5], [7, 7], [5, 7], [5, 5]], [[6, 6], [6.5, 6], [6, 6.5], [6, 6]]]]})"),
            lines({{{0, 0}, {1, 0}, {1, 1}, {0, 0}},
                   {{5, 5}, {7, 5}, {7, 7}, {5, 7}, {5, 5}},
                   {{6, 6}, {6.5, 6}, {6, 6.5}, {6, 6}}}));
}

TEST_F(GeojsonBarriers, AGeometryCollectionNestedOrNotGivesItsMembersInOrder) {
  EXPECT_EQ(read(R"({"type": "GeometryCollection", "geometries": [
                      {"type": "LineString", "coordinates": [[0, 0], [0, 1]]},
                      {"type": "GeometryCollection", "geometries": [
                        {"type": "MultiLineString", "coordinates": [[[1, 1], [2, 2]]]},
                        {"type": "GeometryCollection", "geometries": []}]},
                      {"type": "Polygon", "coordinates": [[[3, 3], [4, 3], [4, 4], [3, 3]]]}]})"),
            lines({{{0, 0}, {0, 1}}, {{1, 1}, {2, 2}}, {{3, 3}, {4, 3}, {4, 4}, {3, 3}}}));
}

TEST_F(GeojsonBarriers, AFeature) {
  EXPECT_EQ(read(R"({"type": "Feature", "id": 7, "properties": {"name": "wall"},
                     "geometry": {"type": "LineString", "coordinates": [[-1, -1], [1, 1]]}})"),
            lines({{{-1, -1}, {1, 1}}}));
}

TEST_F(GeojsonBarriers, AFeatureCollectionInDocumentOrderSkippingNullGeometries) {
  // Foreign members, "bbox", "crs" and properties are ignored; a Feature without a location
  // ("geometry": null) holds no line; an empty MultiLineString holds none either.
  EXPECT_EQ(read(R"({"type": "FeatureCollection",
                     "crs": {"type": "name", "properties": {"name": "urn:ogc:def:crs:EPSG::2056"}},
                     "bbox": [0, 0, 10, 10], "name": "walls",
                     "features": [
    {"type": "Feature", "properties": null, "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [1, 0], [0, 1], [0, 0]]]}},
    {"type": "Feature", "properties": {}, "geometry": null},
    {"type": "Feature", "properties": {}, "geometry": {"type": "LineString", "bbox": [2, 2, 3, 3], "coordinates": [[2, 2, 0], [3, 3, 0]]}},
    {"type": "Feature", "properties": {}, "geometry": {"type": "MultiLineString", "coordinates": []}},
    {"type": "Feature", "properties": {}, "geometry": {"type": "MultiLineString", "coordinates": [[[4, 4], [4, 5]], [[6, 6], [7, 6]]]}},
    {"type": "Feature", "properties": {}, "geometry": {"type": "GeometryCollection", "geometries": [
      {"type": "LineString", "coordinates": [[8, 8], [9, 9]]}]}}
  ]})"),
            lines({{{0, 0}, {1, 0}, {0, 1}, {0, 0}}, {{2, 2}, {3, 3}}, {{4, 4}, {4, 5}}, {{6, 6}, {7, 6}}, {{8, 8}, {9, 9}}}));
}

TEST_F(GeojsonBarriers, ExtremeButAcceptedCoordinates) {
  EXPECT_EQ(read(R"({"type": "LineString", "coordinates": [[1e100, -1e100], [-0.0, 1e-320], [1e-400, 5]]})"),
            lines({{{1e100, -1e100}, {0, 1e-320}, {0, 5}}}));
}

TEST_F(GeojsonBarriers, WhatIsReadPassesBarriersFromPolylines) {
  const std::vector<Polyline> read_lines =
      read(R"({"type": "MultiPolygon", "coordinates": [[[[0, 0], [1, 0], [1, 1], [0, 0]]]]})");
  const Result<Barriers> barriers = Barriers::from_polylines(read_lines);
  ASSERT_TRUE(barriers.ok()) << barriers.reason();
  EXPECT_EQ(barriers.value().segments().size(), 3u);
}

TEST_F(GeojsonBarriers, ALargeFileReadsExactly) {
  // 500 one-segment Features, then a 500-segment LineString, all on exact binary fractions.
  std::vector<Polyline> expected;
  std::string text = R"({"type": "FeatureCollection", "features": [)";
  for (int i = 0; i < 500; ++i) {
    const double x = i * 0.25, y = -i * 0.125;
    expected.push_back({Vec2(x, y), Vec2(x + 0.5, y + 1)});
    text += (i ? ",\n" : "\n") + std::string(R"({"type": "Feature", "properties": {"i": )") + std::to_string(i) +
            R"(}, "geometry": {"type": "LineString", "coordinates": [[)" + std::to_string(x) + ", " +
            std::to_string(y) + "], [" + std::to_string(x + 0.5) + ", " + std::to_string(y + 1) + "]]}}";
  }
  Polyline long_line;
  text += R"(, {"type": "Feature", "properties": {}, "geometry": {"type": "LineString", "coordinates": [)";
  for (int i = 0; i <= 500; ++i) {
    const double x = i * 0.5, y = (i % 2) * 0.75;
    long_line.emplace_back(x, y);
    text += (i ? ", [" : "[") + std::to_string(x) + ", " + std::to_string(y) + "]";
  }
  text += "]}}\n]}\n";
  expected.push_back(long_line);
  const std::vector<Polyline> got = read(text);
  ASSERT_EQ(got.size(), 501u);
  EXPECT_EQ(got, expected);
  const Result<Barriers> barriers = Barriers::from_polylines(got);
  ASSERT_TRUE(barriers.ok()) << barriers.reason();
  EXPECT_EQ(barriers.value().segments().size(), 1000u);
}

TEST_F(GeojsonBarriers, RefusesAnUnreadableEmptyOrInvalidFile) {
  const std::string missing = (dir_ / "absent.geojson").string();
  EXPECT_NE(testing_support::user_error_message([&] { read_geojson_barriers(missing); }).find(missing + ": cannot open"),
            std::string::npos);
  EXPECT_TRUE(RefusedMentioning("", {"b.geojson: empty file: no barrier lines"}));
  EXPECT_TRUE(RefusedMentioning(" \n\t\r\n", {"b.geojson: empty file: no barrier lines"}));
  // Invalid JSON: the line.
  EXPECT_TRUE(RefusedMentioning("{\"type\": \"LineString\",\n \"coordinates\": [[0, 0],\n [1, 1],]}",
                                {"b.geojson:3: not valid JSON"}));
  // A number too large for a double (it would be infinite): the line, and the number.
  EXPECT_TRUE(RefusedMentioning("{\"type\": \"LineString\",\n \"coordinates\": [[0, 0],\n\n [1e400, 1]]}",
                                {"b.geojson:4: not a valid GeoJSON file", "1e400"}));
  EXPECT_TRUE(RefusedMentioning("[1, 2]", {"b.geojson: (top level): must be a GeoJSON object"}));
}

TEST_F(GeojsonBarriers, RefusesAFileWithoutBarrierLines) {
  EXPECT_TRUE(RefusedMentioning(R"({"type": "FeatureCollection", "features": []})", {"b.geojson: no barrier lines"}));
  EXPECT_TRUE(RefusedMentioning(R"({"type": "FeatureCollection", "features": [
                                     {"type": "Feature", "properties": {}, "geometry": null}]})",
                                {"b.geojson: no barrier lines"}));
  EXPECT_TRUE(RefusedMentioning(R"({"type": "Feature", "properties": {}, "geometry": null})", {"b.geojson: no barrier lines"}));
  EXPECT_TRUE(RefusedMentioning(R"({"type": "MultiPolygon", "coordinates": []})", {"b.geojson: no barrier lines"}));
  EXPECT_TRUE(RefusedMentioning(R"({"type": "GeometryCollection", "geometries": []})", {"b.geojson: no barrier lines"}));
}

TEST_F(GeojsonBarriers, RefusesAMissingOrUnknownType) {
  EXPECT_TRUE(RefusedMentioning(R"({"coordinates": [[0, 0], [1, 1]]})", {"b.geojson: type: missing"}));
  EXPECT_TRUE(RefusedMentioning(R"({"type": 3, "coordinates": [[0, 0], [1, 1]]})", {"b.geojson: type: must be a string"}));
  EXPECT_TRUE(RefusedMentioning(R"({"type": "Polyline", "coordinates": [[0, 0], [1, 1]]})",
                                {"b.geojson: type: unknown GeoJSON type 'Polyline'", "LineString"}));
  EXPECT_TRUE(RefusedMentioning(R"({"type": "linestring", "coordinates": [[0, 0], [1, 1]]})",
                                {"b.geojson: type: unknown GeoJSON type 'linestring'"}));
  EXPECT_TRUE(RefusedMentioning(R"({"type": "FeatureCollection", "features": [
                                     {"type": "Feature", "geometry": {"type": "LineString", "coordinates": [[0, 0], [1, 1]]}},
                                     {"geometry": {"type": "LineString", "coordinates": [[0, 0], [1, 1]]}}]})",
                                {"b.geojson: features[1].type: missing"}));
  EXPECT_TRUE(RefusedMentioning(R"({"type": "FeatureCollection", "features": [
                                     {"type": "Feature", "geometry": {"coordinates": [[0, 0], [1, 1]]}}]})",
                                {"b.geojson: features[0].geometry.type: missing"}));
  EXPECT_TRUE(RefusedMentioning(R"({"type": "FeatureCollection", "features": [
                                     {"type": "LineString", "coordinates": [[0, 0], [1, 1]]}]})",
                                {"b.geojson: features[0].type: must be \"Feature\""}));
  EXPECT_TRUE(RefusedMentioning(R"({"type": "Feature", "geometry": {"type": "Feature", "geometry": null}})",
                                {"b.geojson: geometry.type: a Feature where a geometry belongs"}));
  EXPECT_TRUE(RefusedMentioning(R"({"type": "GeometryCollection", "geometries": [
                                     {"type": "LineString", "coordinates": [[0, 0], [1, 1]]}, 5]})",
                                {"b.geojson: geometries[1]: must be a GeoJSON object"}));
}

TEST_F(GeojsonBarriers, RefusesMissingOrMistypedMembers) {
  EXPECT_TRUE(RefusedMentioning(R"({"type": "FeatureCollection"})", {"b.geojson: features: missing"}));
  EXPECT_TRUE(RefusedMentioning(R"({"type": "FeatureCollection", "features": {}})",
                                {"b.geojson: features: must be an array of Features"}));
  EXPECT_TRUE(RefusedMentioning(R"({"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {}}]})",
                                {"b.geojson: features[0].geometry: missing"}));
  EXPECT_TRUE(RefusedMentioning(R"({"type": "LineString"})", {"b.geojson: coordinates: missing"}));
  EXPECT_TRUE(RefusedMentioning(R"({"type": "LineString", "coordinates": null})",
                                {"b.geojson: coordinates: expected an array of positions"}));
  EXPECT_TRUE(RefusedMentioning(R"({"type": "MultiLineString", "coordinates": 5})",
                                {"b.geojson: coordinates: must be an array of LineString coordinates"}));
  EXPECT_TRUE(RefusedMentioning(R"({"type": "MultiLineString", "coordinates": [{}]})",
                                {"b.geojson: coordinates[0]: expected an array of positions"}));
  // A level of brackets missing: a number where a position belongs.
  EXPECT_TRUE(RefusedMentioning(R"({"type": "MultiLineString", "coordinates": [[0, 0], [1, 1]]})",
                                {"b.geojson: coordinates[0][0]: expected a position [x, y], found a number"}));
  EXPECT_TRUE(RefusedMentioning(R"({"type": "LineString", "coordinates": [0, 0]})",
                                {"b.geojson: coordinates[0]: expected a position [x, y], found a number"}));
  EXPECT_TRUE(RefusedMentioning(R"({"type": "GeometryCollection"})", {"b.geojson: geometries: missing"}));
  EXPECT_TRUE(RefusedMentioning(R"({"type": "GeometryCollection", "geometries": {}})",
                                {"b.geojson: geometries: must be an array of geometries"}));
}

TEST_F(GeojsonBarriers, RefusesPointsNamingTheFeature) {
  EXPECT_TRUE(RefusedMentioning(R"({"type": "FeatureCollection", "features": [
                                     {"type": "Feature", "geometry": {"type": "LineString", "coordinates": [[0, 0], [1, 1]]}},
                                     {"type": "Feature", "geometry": {"type": "Point", "coordinates": [2, 2]}}]})",
                                {"b.geojson: features[1].geometry.type: a Point cannot be a barrier"}));
  EXPECT_TRUE(RefusedMentioning(R"({"type": "MultiPoint", "coordinates": [[0, 0], [1, 1]]})",
                                {"b.geojson: type: a MultiPoint cannot be a barrier"}));
  EXPECT_TRUE(RefusedMentioning(R"({"type": "GeometryCollection", "geometries": [
                                     {"type": "LineString", "coordinates": [[0, 0], [1, 1]]},
                                     {"type": "Point", "coordinates": [2, 2]}]})",
                                {"b.geojson: geometries[1].type: a Point cannot be a barrier"}));
}

TEST_F(GeojsonBarriers, RefusesTooShortLinesAndBadRings) {
  EXPECT_TRUE(RefusedMentioning(R"({"type": "LineString", "coordinates": [[0, 0]]})",
                                {"b.geojson: coordinates: a LineString needs at least 2 positions, it has 1"}));
  EXPECT_TRUE(RefusedMentioning(R"({"type": "LineString", "coordinates": []})",
                                {"b.geojson: coordinates: a LineString needs at least 2 positions, it has 0"}));
  EXPECT_TRUE(RefusedMentioning(R"({"type": "MultiLineString", "coordinates": [[[0, 0], [1, 1]], [[2, 2]]]})",
                                {"b.geojson: coordinates[1]: a LineString needs at least 2 positions"}));
  EXPECT_TRUE(RefusedMentioning(R"({"type": "Polygon", "coordinates": []})", {"b.geojson: coordinates: expected a Polygon's rings"}));
  EXPECT_TRUE(RefusedMentioning(R"({"type": "Polygon", "coordinates": [[[0, 0], [1, 0], [0, 0]]]})",
                                {"b.geojson: coordinates[0]: a Polygon ring needs at least 4 positions", "it has 3"}));
  EXPECT_TRUE(RefusedMentioning(R"({"type": "Polygon", "coordinates": [[[0, 0], [1, 0], [1, 1], [0, 0]],
                                                                    [[0.2, 0.1], [0.8, 0.1], [0.8, 0.7], [0.2, 0.2]]]})",
                                {"b.geojson: coordinates[1]: a Polygon ring must be closed", "[0.2, 0.2]", "[0.2, 0.1]"}));
  EXPECT_TRUE(RefusedMentioning(R"({"type": "MultiPolygon", "coordinates": [[[[0, 0], [1, 0], [1, 1], [0, 0]]], [[[0, 0], [1, 0], [1, 1], [0, 1]]]]})",
                                {"b.geojson: coordinates[1][0]: a Polygon ring must be closed"}));
  EXPECT_TRUE(RefusedMentioning(R"({"type": "MultiPolygon", "coordinates": [[]]})",
                                {"b.geojson: coordinates[0]: expected a Polygon's rings"}));
  EXPECT_TRUE(RefusedMentioning(R"({"type": "Polygon", "coordinates": [[0, 0], [1, 0], [1, 1], [0, 0]]})",
                                {"b.geojson: coordinates[0][0]: expected a position [x, y], found a number"}));
  EXPECT_TRUE(RefusedMentioning(R"({"type": "Polygon", "coordinates": [5]})", {"b.geojson: coordinates[0]: expected a ring"}));
  EXPECT_TRUE(RefusedMentioning(R"({"type": "MultiPolygon", "coordinates": {}})",
                                {"b.geojson: coordinates: must be an array of Polygon coordinates"}));
}

TEST_F(GeojsonBarriers, RefusesZeroLengthSegments) {
  EXPECT_TRUE(RefusedMentioning(R"({"type": "LineString", "coordinates": [[0, 0], [1, 1], [1, 1], [2, 2]]})",
                                {"b.geojson: coordinates[2]: repeats the position before it, [1, 1]"}));
  // Equal in x and y, differing in the ignored z: still a segment of zero length in the plane.
  EXPECT_TRUE(RefusedMentioning(R"({"type": "LineString", "coordinates": [[0, 0, 1], [0, 0, 2]]})",
                                {"b.geojson: coordinates[1]: repeats the position before it"}));
  EXPECT_TRUE(RefusedMentioning(R"({"type": "Polygon", "coordinates": [[[0, 0], [1, 0], [1, 1], [0, 0], [0, 0]]]})",
                                {"b.geojson: coordinates[0][4]: repeats the position before it"}));
}

TEST_F(GeojsonBarriers, RefusesBadPositions) {
  const std::string in_feature = R"({"type": "FeatureCollection", "features": [
    {"type": "Feature", "geometry": {"type": "LineString", "coordinates": [[0, 0], [1, 1]]}},
    {"type": "Feature", "geometry": {"type": "MultiLineString", "coordinates": [[[0, 0], [1, 1], POSITION]]}}]})";
  const auto with = [&](const std::string& position) {
    std::string text = in_feature;
    text.replace(text.find("POSITION"), 8, position);
    return text;
  };
  const std::string where = "b.geojson: features[1].geometry.coordinates[0][2]";
  EXPECT_EQ(refusal(with("[2, 2]")), "");
  EXPECT_TRUE(RefusedMentioning(with("[2]"), {where + ": expected a position [x, y]"}));
  EXPECT_TRUE(RefusedMentioning(with("[]"), {where + ": expected a position [x, y]"}));
  EXPECT_TRUE(RefusedMentioning(with("2"), {where + ": expected a position [x, y]"}));
  EXPECT_TRUE(RefusedMentioning(with("{\"x\": 2, \"y\": 2}"), {where + ": expected a position [x, y]"}));
  EXPECT_TRUE(RefusedMentioning(with("[\"NaN\", 2]"), {where + "[0]: must be a number"}));
  EXPECT_TRUE(RefusedMentioning(with("[2, \"Infinity\"]"), {where + "[1]: must be a number"}));
  EXPECT_TRUE(RefusedMentioning(with("[2, null]"), {where + "[1]: must be a number"}));
  EXPECT_TRUE(RefusedMentioning(with("[2, 2, \"high\"]"), {where + "[2]: must be a number"}));
  EXPECT_TRUE(RefusedMentioning(with("[2, true]"), {where + "[1]: must be a number"}));
  EXPECT_TRUE(RefusedMentioning(with("[1.5e100, 2]"), {where + "[0]: 1.5e+100 is beyond the largest coordinate, 1e+100"}));
  EXPECT_TRUE(RefusedMentioning(with("[2, -1e101]"), {where + "[1]: -1e+101 is beyond the largest coordinate"}));
  // JSON has no NaN or Infinity: those words are invalid JSON, refused with their line.
  EXPECT_TRUE(RefusedMentioning(with("[NaN, 2]"), {"b.geojson:3: not valid JSON"}));
  EXPECT_TRUE(RefusedMentioning(with("[2, Infinity]"), {"b.geojson:3: not valid JSON"}));
  EXPECT_TRUE(RefusedMentioning(with("[2, -1e999]"), {"b.geojson:3: not a valid GeoJSON file", "-1e999"}));
}

TEST_F(GeojsonBarriers, RefusesGeometryCollectionsNestedTooDeep) {
  std::string deep = R"({"type": "LineString", "coordinates": [[0, 0], [1, 1]]})";
  for (int i = 0; i < 64; ++i) deep = R"({"type": "GeometryCollection", "geometries": [)" + deep + "]}";
  EXPECT_EQ(read(deep), lines({{{0, 0}, {1, 1}}}));
  deep = R"({"type": "GeometryCollection", "geometries": [)" + deep + "]}";
  EXPECT_TRUE(RefusedMentioning(deep, {"b.geojson: geometries[0]", "nested more than 64 deep"}));
}

}  // namespace geojson_test
}  // namespace radrecon
