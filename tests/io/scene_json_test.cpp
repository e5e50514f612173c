// The scene model: the JSON reader on valid and malformed input, and the built-in paper scene
// against the design brief's numbers.

#include <gtest/gtest.h>

#include <algorithm>
#include <initializer_list>
#include <string>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "io/scene_json.h"
#include "scene/scene.h"
#include "support/temp_dir.h"

namespace radrecon {
namespace scene_json_test {

using json = nlohmann::json;

// Coordinates and areas below are small decimal numbers combined by a handful of operations:
// any error beyond a few ulps would be a real mistake.
constexpr double kExact = 1e-12;

const char* const kSource = "bad.json";

/// Passes when parsing `text` throws UserError whose message contains every one of `needles`.
testing::AssertionResult RefusedMentioning(const std::string& text, std::initializer_list<std::string> needles) {
  return testing_support::refused_mentioning([&] { parse_scene_json(text, kSource); }, needles) << " (the scene:\n"
                                                                                                  << text << ")";
}

/// A valid scene: a 2 m x 1 m grey floor and a 1 m x 1 m lamp facing it.
json ValidScene() {
  return json::parse(R"({
    "name": "mini",
    "surfaces": [
      {"name": "floor", "corners": [[0, 0, 0], [2, 0, 0], [2, 1, 0], [0, 1, 0]],
       "reflectance": [0.1, 0.2, 0.3], "two_sided": true, "mesh": {"max_divisions": 7}},
      {"name": "lamp", "corners": [[0, 0, 1], [0, 1, 1], [1, 1, 1], [1, 0, 1]],
       "reflectance": 0, "emission": 10}
    ],
    "cameras": [{"name": "cam", "eye": [1, 1, 5], "target": [1, 0.5, 0], "fov_deg": 30}]
  })");
}

void ExpectVec(const Vec3& got, const Vec3& want, double tol) {
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(got[i], want[i], tol) << "component " << i;
}

/// The axis-aligned box of the corners.
void ExpectCornerBox(const Surface& s, const Vec3& lo, const Vec3& hi) {
  Vec3 mn = s.corners[0], mx = s.corners[0];
  for (const Vec3& c : s.corners) {
    mn = mn.cwiseMin(c);
    mx = mx.cwiseMax(c);
  }
  SCOPED_TRACE(s.name);
  ExpectVec(mn, lo, kExact);
  ExpectVec(mx, hi, kExact);
}

TEST(SceneJson, ValidMinimalSceneGivesItsSurfacesAndFields) {
  const Scene scene = parse_scene_json(ValidScene().dump(2), "mini.json");
  EXPECT_EQ(scene.name, "mini");
  ASSERT_EQ(scene.surfaces.size(), 2u);

  const Surface& floor = scene.surfaces[0];
  EXPECT_EQ(floor.name, "floor");
  ExpectVec(floor.corners[0], Vec3(0, 0, 0), 0.0);
  ExpectVec(floor.corners[2], Vec3(2, 1, 0), 0.0);
  EXPECT_DOUBLE_EQ(floor.reflectance[0], 0.1);
  EXPECT_DOUBLE_EQ(floor.reflectance[1], 0.2);
  EXPECT_DOUBLE_EQ(floor.reflectance[2], 0.3);
  EXPECT_EQ(floor.emission_w_m2[0], 0.0);  // emission defaults to none
  EXPECT_TRUE(floor.two_sided);
  ASSERT_TRUE(floor.max_divisions.has_value());
  EXPECT_EQ(*floor.max_divisions, 7);
  EXPECT_NEAR(floor.area_m2(), 2.0, kExact);
  ExpectVec(floor.normal(), Vec3(0, 0, 1), kExact);  // counter-clockwise seen from +z

  const Surface& lamp = scene.surfaces[1];
  EXPECT_EQ(lamp.name, "lamp");
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(lamp.reflectance[c], 0.0);
    EXPECT_EQ(lamp.emission_w_m2[c], 10.0);  // a grey number applies to every channel
  }
  EXPECT_FALSE(lamp.two_sided);
  EXPECT_FALSE(lamp.max_divisions.has_value());
  ExpectVec(lamp.normal(), Vec3(0, 0, -1), kExact);

  EXPECT_EQ(scene.find_surface("lamp"), std::optional<size_t>(1));
  EXPECT_FALSE(scene.find_surface("nothing").has_value());

  ASSERT_EQ(scene.cameras.size(), 1u);
  const Camera& cam = scene.cameras[0];
  EXPECT_EQ(cam.name, "cam");
  ExpectVec(cam.eye, Vec3(1, 1, 5), 0.0);
  ExpectVec(cam.target, Vec3(1, 0.5, 0), 0.0);
  ExpectVec(cam.up, Vec3(0, 0, 1), 0.0);  // the documented default
  EXPECT_EQ(cam.fov_deg, 30.0);
}

TEST(PaperScene, MatchesTheDesignBrief) {
  const Scene scene = paper_scene();
  ASSERT_EQ(scene.surfaces.size(), 4u);
  EXPECT_NO_THROW(validate_scene(scene, "paper"));

  const auto ground_i = scene.find_surface("ground");
  const auto light_i = scene.find_surface("light");
  const auto wall1_i = scene.find_surface("wall1");
  const auto wall2_i = scene.find_surface("wall2");
  ASSERT_TRUE(ground_i && light_i && wall1_i && wall2_i);
  const Surface& ground = scene.surfaces[*ground_i];
  const Surface& light = scene.surfaces[*light_i];
  const Surface& wall1 = scene.surfaces[*wall1_i];
  const Surface& wall2 = scene.surfaces[*wall2_i];

  // Ground: z = 0, x, y in [0, 4], facing +z, grey 0.5, not a light.
  ExpectCornerBox(ground, Vec3(0, 0, 0), Vec3(4, 4, 0));
  ExpectVec(ground.normal(), Vec3(0, 0, 1), kExact);
  EXPECT_NEAR(ground.area_m2(), 16.0, kExact);
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(ground.reflectance[c], 0.5);
    EXPECT_EQ(ground.emission_w_m2[c], 0.0);
  }
  EXPECT_FALSE(ground.two_sided);

  // Light: z = 2.5, x, y in [1, 2], facing -z (down onto the ground), 40 W/m^2.
  ExpectCornerBox(light, Vec3(1, 1, 2.5), Vec3(2, 2, 2.5));
  ExpectVec(light.normal(), Vec3(0, 0, -1), kExact);
  EXPECT_NEAR(light.area_m2(), 1.0, kExact);
  for (int c = 0; c < 3; ++c) EXPECT_EQ(light.emission_w_m2[c], 40.0);
  ASSERT_TRUE(light.max_divisions.has_value());
  EXPECT_EQ(*light.max_divisions, 4);

  // Walls: x = 2.6 (y in [0.6, 2.6]) and y = 2.6 (x in [0.6, 2.6]), z in [0, 1], two-sided.
  ExpectCornerBox(wall1, Vec3(2.6, 0.6, 0), Vec3(2.6, 2.6, 1));
  ExpectCornerBox(wall2, Vec3(0.6, 2.6, 0), Vec3(2.6, 2.6, 1));
  EXPECT_TRUE(wall1.two_sided);
  EXPECT_TRUE(wall2.two_sided);
  EXPECT_NEAR(wall1.area_m2(), 2.0, kExact);
  EXPECT_NEAR(wall2.area_m2(), 2.0, kExact);
  // Each wall's front normal is perpendicular to its plane and faces the light.
  const Vec3 light_centre(1.5, 1.5, 2.5);
  ExpectVec(wall1.normal().cwiseAbs(), Vec3(1, 0, 0), kExact);
  ExpectVec(wall2.normal().cwiseAbs(), Vec3(0, 1, 0), kExact);
  EXPECT_GT(wall1.normal().dot(light_centre - wall1.corners[0]), 0.0);
  EXPECT_GT(wall2.normal().dot(light_centre - wall2.corners[0]), 0.0);
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(wall1.emission_w_m2[c], 0.0);
    EXPECT_EQ(wall2.emission_w_m2[c], 0.0);
  }
  // The walls meet at (2.6, 2.6).
  EXPECT_TRUE(std::any_of(wall1.corners.begin(), wall1.corners.end(),
                          [](const Vec3& c) { return (c - Vec3(2.6, 2.6, 0)).norm() < kExact; }));
  EXPECT_TRUE(std::any_of(wall2.corners.begin(), wall2.corners.end(),
                          [](const Vec3& c) { return (c - Vec3(2.6, 2.6, 0)).norm() < kExact; }));
}

TEST(SceneJson, RefusesTextThatIsNotJsonWithItsLineNumber) {
  // The stray word is on line 3.
  const std::string text = "{\n  \"name\": \"x\",\n  oops\n}\n";
  EXPECT_TRUE(RefusedMentioning(text, {"bad.json:3"}));
}

TEST(SceneJson, RefusesAKeyGivenTwiceInOneObjectNamingWhere) {
  // JSON would keep the last value silently: a scene with two reflectances is refused.
  EXPECT_TRUE(RefusedMentioning(R"({"name": "x", "name": "y", "surfaces": []})",
                                {"the key 'name' appears twice in the top-level object"}));
  json doc = ValidScene();
  const std::string text = doc.dump();
  const std::string twice = text.substr(0, text.rfind("}]")) + R"(, "two_sided": true, "two_sided": false}]})";
  EXPECT_TRUE(RefusedMentioning(twice, {"the key 'two_sided' appears twice in surfaces["}));
  // A long object: the same answer.
  std::string many = R"({"name": "x", "surfaces": [], "extra": {)";
  for (int k = 0; k < 40; ++k) many += "\"k" + std::to_string(k) + "\": " + std::to_string(k) + ", ";
  EXPECT_TRUE(RefusedMentioning(many + R"("k33": 0}})", {"the key 'k33' appears twice in extra"}));
  // The same key in different objects is no repeat.
  EXPECT_FALSE(RefusedMentioning(R"({"name": "x", "a": {"k": 1}, "b": [{"k": 1}, {"k": 2}], "surfaces": []})",
                                 {"appears twice"}));
}

TEST(SceneJson, RefusesAMissingSurfacesField) {
  json doc = ValidScene();
  doc.erase("surfaces");
  EXPECT_TRUE(RefusedMentioning(doc.dump(), {kSource, "surfaces", "missing"}));
}

TEST(SceneJson, RefusesACornerWithTwoNumbers) {
  json doc = ValidScene();
  doc["surfaces"][0]["corners"][1] = json::array({2, 0});
  EXPECT_TRUE(RefusedMentioning(doc.dump(), {kSource, "surfaces[0].corners[1]"}));
}

TEST(SceneJson, RefusesAStringWhereANumberBelongs) {
  json doc = ValidScene();
  doc["surfaces"][0]["corners"][2][1] = "one";
  EXPECT_TRUE(RefusedMentioning(doc.dump(), {kSource, "surfaces[0].corners[2][1]", "number"}));
  json doc2 = ValidScene();
  doc2["surfaces"][1]["emission"] = "10";
  EXPECT_TRUE(RefusedMentioning(doc2.dump(), {kSource, "surfaces[1].emission"}));
}

TEST(SceneJson, SplitsANonPlanarQuadIntoTwoTriangles) {
  json doc = ValidScene();
  doc["surfaces"][0]["corners"][3] = json::array({0, 1, 0.5});  // lifted 0.5 m off the plane
  const Scene scene = parse_scene_json(doc.dump(), kSource);
  ASSERT_EQ(scene.surfaces.size(), ValidScene()["surfaces"].size() + 1);
  EXPECT_TRUE(scene.surfaces[0].is_triangle());
  EXPECT_TRUE(scene.surfaces[1].is_triangle());
}

TEST(SceneJson, AHalfNamedAsAnotherSurfaceIsSaidOfThatSurface) {
  // Counted after the split, the duplicate was said of surfaces[2] in a file of two (an
  // outside-in trial): the surface of that name is named by its own index.
  json doc = ValidScene();
  doc["surfaces"][0]["corners"][3] = json::array({0, 1, 0.5});
  doc["surfaces"][1]["name"] = "floor.b";
  EXPECT_TRUE(RefusedMentioning(doc.dump(), {"surfaces[1].name", "'floor.b' is the name of a half of surfaces[0] 'floor'",
                                             "off its plane"}));
}

TEST(SceneJson, ReadsATriangle) {
  json doc = ValidScene();
  doc["surfaces"][0]["corners"] = json::parse("[[0,0,0],[1,0,0],[0,1,0]]");
  const Scene scene = parse_scene_json(doc.dump(), kSource);
  EXPECT_TRUE(scene.surfaces[0].is_triangle());
  EXPECT_NEAR(scene.surfaces[0].area_m2(), 0.5, 1e-15);
  doc["surfaces"][0]["corners"] = json::parse("[[0,0,0],[1,0,0]]");
  EXPECT_TRUE(RefusedMentioning(doc.dump(), {kSource, "surfaces[0].corners", "3 or 4 points"}));
  doc["surfaces"][0]["corners"] = json::parse("[[0,0,0],[1,0,0],[2,0,0]]");  // collinear
  EXPECT_TRUE(RefusedMentioning(doc.dump(), {kSource, "surfaces[0].corners", "degenerate triangle"}));
}

TEST(SceneJson, RefusesADegenerateQuad) {
  json doc = ValidScene();
  // Four collinear corners: zero area.
  doc["surfaces"][0]["corners"] = json::parse("[[0,0,0],[1,0,0],[2,0,0],[3,0,0]]");
  EXPECT_TRUE(RefusedMentioning(doc.dump(), {kSource, "surfaces[0].corners", "degenerate"}));
  // Two coincident pairs of corners: a segment.
  doc["surfaces"][0]["corners"] = json::parse("[[0,0,0],[0,0,0],[1,1,0],[1,1,0]]");
  EXPECT_TRUE(RefusedMentioning(doc.dump(), {kSource, "surfaces[0].corners"}));
}

TEST(SceneJson, SplitsANonConvexQuadAndRefusesAMisorderedOne) {
  json doc = ValidScene();
  // A dart: corner 2 at (1, 1) is reflex (the turn there is clockwise seen from +z): two triangles.
  doc["surfaces"][0]["corners"] = json::parse("[[0,0,0],[4,0,0],[1,1,0],[0,4,0]]");
  EXPECT_EQ(parse_scene_json(doc.dump(), kSource).surfaces.size(), ValidScene()["surfaces"].size() + 1);
  // Self-intersecting order with non-zero diagonal cross product (corners 2 and 3 swapped-ish).
  doc["surfaces"][0]["corners"] = json::parse("[[0,0,0],[3,0,0],[0,2,0],[1,3,0]]");
  EXPECT_TRUE(RefusedMentioning(doc.dump(), {kSource, "surfaces[0].corners"}));
  // A bow tie whose halves cancel (zero area, corners far from collinear): said to cross itself,
  // not to be collinear.
  doc["surfaces"][0]["corners"] = json::parse("[[0,0,0],[4,0,0],[0,3,0],[4,4,0]]");
  EXPECT_TRUE(RefusedMentioning(doc.dump(), {kSource, "surfaces[0].corners", "crosses itself"}));
  // Two opposite corners at one point: degenerate, not a bow tie.
  doc["surfaces"][0]["corners"] = json::parse("[[0,0,0],[1,0,0],[0,0,0],[0,1,0]]");
  EXPECT_TRUE(RefusedMentioning(doc.dump(), {kSource, "surfaces[0].corners", "coincide"}));
}

TEST(SceneJson, RefusesReflectanceOutsideZeroToOne) {
  json doc = ValidScene();
  doc["surfaces"][0]["reflectance"] = 1.0;  // [0, 1) excludes 1: energy would not decay
  EXPECT_TRUE(RefusedMentioning(doc.dump(), {kSource, "surfaces[0].reflectance"}));
  doc["surfaces"][0]["reflectance"] = -0.1;
  EXPECT_TRUE(RefusedMentioning(doc.dump(), {kSource, "surfaces[0].reflectance"}));
  doc["surfaces"][0]["reflectance"] = json::array({0.5, 1.0, 0.5});  // one bad channel suffices
  EXPECT_TRUE(RefusedMentioning(doc.dump(), {kSource, "surfaces[0].reflectance"}));
}

TEST(SceneJson, RefusesNegativeEmission) {
  json doc = ValidScene();
  doc["surfaces"][1]["emission"] = json::array({10, -1, 10});
  EXPECT_TRUE(RefusedMentioning(doc.dump(), {kSource, "surfaces[1].emission"}));
}

TEST(SceneJson, RefusesDuplicateSurfaceNames) {
  json doc = ValidScene();
  doc["surfaces"][1]["name"] = "floor";
  EXPECT_TRUE(RefusedMentioning(doc.dump(), {kSource, "surfaces[1].name", "floor"}));
}

TEST(SceneJson, RefusesUnknownFields) {
  json doc = ValidScene();
  doc["surfaces"][0]["colour"] = 0.5;
  EXPECT_TRUE(RefusedMentioning(doc.dump(), {kSource, "surfaces[0].colour", "unknown"}));
  json top = ValidScene();
  top["lights"] = json::array();
  EXPECT_TRUE(RefusedMentioning(top.dump(), {kSource, "lights", "unknown"}));
}

TEST(SceneJson, RefusesASceneWithoutEmitter) {
  json doc = ValidScene();
  doc["surfaces"][1]["emission"] = 0;
  EXPECT_TRUE(RefusedMentioning(doc.dump(), {kSource, "emit"}));
}

/// ValidScene() with every coordinate (and the camera) times `scale`.
json ScaledScene(double scale) {
  json doc = ValidScene();
  for (json& surface : doc["surfaces"])
    for (json& corner : surface["corners"])
      for (json& x : corner) x = x.get<double>() * scale;
  for (const char* key : {"eye", "target"})
    for (json& x : doc["cameras"][0][key]) x = x.get<double>() * scale;
  return doc;
}

TEST(SceneJson, RefusesASceneSmallerThanItsVisibilityTolerancesNeed) {
  // Visibility's plane distance is 1e-9 m: a box scene lost its shadows below 3e-8 m. ValidScene()
  // spans the box [0, 2] x [0, 1] x [0, 1], sqrt(6) = 2.449 m across.
  EXPECT_TRUE(RefusedMentioning(ScaledScene(1e-4).dump(), {kSource, "0.000244948", "m across", "scale the model up"}));
  EXPECT_TRUE(RefusedMentioning(ScaledScene(1e-9).dump(), {kSource, "m across"}));
  EXPECT_NO_THROW(parse_scene_json(ScaledScene(1e-3).dump(), kSource));  // 2.4 mm
}

TEST(SceneJson, RefusesACoordinateThatOverflowsToInfinity) {
  // 1e999 is valid JSON syntax but not a finite double.
  // nlohmann reports it as json::out_of_range (406), which must become a UserError too.
  std::string text = ValidScene().dump();
  const std::string corner = "[2,1,0]";
  const size_t at = text.find(corner);
  ASSERT_NE(at, std::string::npos);
  text.replace(at, corner.size(), "[2,1e999,0]");
  EXPECT_TRUE(RefusedMentioning(text, {kSource}));
}

}  // namespace scene_json_test
}  // namespace radrecon
