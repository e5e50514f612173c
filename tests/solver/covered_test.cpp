// The parts of a surface that others lying on it hide (solver/covered.h), against areas known in
// closed form.

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "scene/contacts.h"
#include "solver/covered.h"
#include "support/scenes.h"

namespace radrecon {
namespace covered_test {

using testing_support::quad;

/// The corners as a polygon (a cover).
ConvexPolygon polygon(std::initializer_list<Vec3> corners) {
  ConvexPolygon p;
  for (const Vec3& c : corners) p.push(c);
  return p;
}

TEST(Covered, ExposedFractionIsOneMinusTheOverlapOverTheArea) {
  // A 1 x 1 m element in z = 0 facing +z (and the same corners read facing -z: the orientation
  // of neither polygon matters).
  const std::vector<Vec3> element = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const std::vector<ConvexPolygon> square = {polygon({{0.5, 0.25, 0}, {2, 0.25, 0}, {2, 2, 0}, {0.5, 2, 0}})};
  for (const Vec3& normal : {Vec3(0, 0, 1), Vec3(0, 0, -1)}) {
    EXPECT_NEAR(exposed_fraction(element, normal, square), 1 - 0.5 * 0.75, 1e-15);  // overlap 0.5 x 0.75
    // A triangle with its right angle at (0.2, 0.2) and legs 0.5: area 0.125, all inside.
    const std::vector<ConvexPolygon> triangle = {polygon({{0.2, 0.2, 0}, {0.2, 0.7, 0}, {0.7, 0.2, 0}})};
    EXPECT_NEAR(exposed_fraction(element, normal, triangle), 1 - 0.125, 1e-15);
    const std::vector<ConvexPolygon> apart = {polygon({{2, 2, 0}, {3, 2, 0}, {3, 3, 0}})};
    EXPECT_EQ(exposed_fraction(element, normal, apart), 1.0);
    const std::vector<ConvexPolygon> all = {polygon({{-1, -1, 0}, {2, -1, 0}, {2, 2, 0}, {-1, 2, 0}})};
    EXPECT_EQ(exposed_fraction(element, normal, all), 0.0);
    EXPECT_EQ(exposed_fraction(element, normal, {}), 1.0);
  }
}

TEST(Covered, ALampOnACeilingCoversItAndNotTheFloor) {
  Scene scene;
  scene.name = "room";
  scene.surfaces.push_back(quad("ceiling", {0, 0, 2}, {0, 2.5, 2}, {3, 2.5, 2}, {3, 0, 2}, 0.5));
  scene.surfaces.push_back(quad("lamp", {1, 1, 2}, {1, 1.5, 2}, {2, 1.5, 2}, {2, 1, 2}, 0.5, 40));
  scene.surfaces.push_back(quad("floor", {0, 0, 0}, {3, 0, 0}, {3, 2.5, 0}, {0, 2.5, 0}, 0.5));
  const std::vector<std::vector<ConvexPolygon>> covers = covers_by_surface(scene);
  ASSERT_EQ(covers.size(), 3u);
  const std::vector<ConvexPolygon>& on_ceiling = covers[0];
  ASSERT_EQ(on_ceiling.size(), 1u);
  // The whole ceiling: the lamp hides 0.5 of its 7.5 m^2.
  const std::vector<Vec3> ceiling = {{0, 0, 2}, {0, 2.5, 2}, {3, 2.5, 2}, {3, 0, 2}};
  EXPECT_NEAR(exposed_fraction(ceiling, scene.surfaces[0].normal(), on_ceiling), 1 - 0.5 / 7.5, 1e-14);
  EXPECT_TRUE(covers[1].empty());  // the larger ceiling does not lie on the lamp
  EXPECT_TRUE(covers[2].empty());
}

/// A triangle of the corners a, b, c (its front by the right-hand rule), grey.
Surface triangle(const std::string& name, const Vec3& a, const Vec3& b, const Vec3& c) {
  Surface s;
  s.name = name;
  s.set_triangle(a, b, c);
  s.reflectance = Rgb::Constant(0.5);
  return s;
}

TEST(Covered, OneSidedFacesBackToBackAreASheetAndNeitherFaceCoversTheOther) {
  // A plate of no thickness as a top quad (facing +z) over two bottom triangles (facing -z):
  // each triangle is smaller than the quad and lay on it as a box's bottom lies on a floor, so
  // the lit top was all covered and took no light (an outside-in trial). A second plate's top
  // is cut into a triangle and a quad of other sizes than its bottom's two triangles, so that
  // faces of either side lie on faces of the other. A box's bottom standing on a third plate of
  // two equal quads still covers its top; a plate facing down on the floor still covers it; and
  // a two-sided panel is no sheet: the lamps under it cover it.
  Scene scene;
  scene.surfaces.push_back(quad("floor", {0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}, 0.5));           // 0
  scene.surfaces.push_back(quad("top", {1, 1, 1}, {2, 1, 1}, {2, 2, 1}, {1, 2, 1}, 0.5));             // 1
  scene.surfaces.push_back(triangle("bottom a", {1, 1, 1}, {1, 2, 1}, {2, 2, 1}));                     // 2
  scene.surfaces.push_back(triangle("bottom b", {1, 1, 1}, {2, 2, 1}, {2, 1, 1}));                     // 3
  scene.surfaces.push_back(triangle("top c", {3, 1, 1}, {3.5, 1, 1}, {3, 1.25, 1}));                   // 4: 0.0625 m^2
  scene.surfaces.push_back(quad("top d", {3.5, 1, 1}, {3.5, 1.5, 1}, {3, 1.5, 1}, {3, 1.25, 1}, 0.5));  // 5: 0.1875 m^2
  scene.surfaces.push_back(triangle("bottom e", {3, 1, 1}, {3, 1.5, 1}, {3.5, 1, 1}));                 // 6: 0.125 m^2
  scene.surfaces.push_back(triangle("bottom f", {3.5, 1, 1}, {3, 1.5, 1}, {3.5, 1.5, 1}));             // 7: 0.125 m^2
  scene.surfaces.push_back(quad("mat", {0.5, 0.5, 0}, {0.5, 1, 0}, {1, 1, 0}, {1, 0.5, 0}, 0.5));     // 8: facing down
  scene.surfaces.push_back(quad("plate top", {1, 3, 1}, {2, 3, 1}, {2, 4, 1}, {1, 4, 1}, 0.5));         // 9
  scene.surfaces.push_back(quad("plate bottom", {1, 3, 1}, {1, 4, 1}, {2, 4, 1}, {2, 3, 1}, 0.5));      // 10
  scene.surfaces.push_back(quad("box bottom", {1.25, 3.25, 1}, {1.25, 3.5, 1}, {1.5, 3.5, 1}, {1.5, 3.25, 1}, 0.5));  // 11
  Surface panel = quad("panel", {3, 3, 2}, {3, 4, 2}, {4, 4, 2}, {4, 3, 2}, 0.5);                       // 12: two-sided
  panel.two_sided = true;
  scene.surfaces.push_back(panel);
  scene.surfaces.push_back(triangle("lamp g", {3, 3, 2}, {4, 3, 2}, {4, 4, 2}));                       // 13: facing +z
  scene.surfaces.push_back(triangle("lamp h", {3, 3, 2}, {4, 4, 2}, {3, 4, 2}));                       // 14
  for (size_t k = 1; k < scene.surfaces.size(); ++k)
    ASSERT_GT(std::abs(scene.surfaces[k].normal().z()), 0.99) << scene.surfaces[k].name;
  ASSERT_LT(scene.surfaces[12].normal().dot(scene.surfaces[13].normal()), 0);
  // (Top c lies on top d beside it, touching only along an edge: listed, it hides nothing.)
  const std::vector<std::vector<size_t>> expected = {{8}, {}, {}, {}, {}, {4}, {}, {}, {}, {11}, {11}, {}, {13, 14}, {}, {}};
  EXPECT_EQ(covering_surfaces(scene), expected);
  const std::vector<size_t> regions = {1, 0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 0, 2, 0, 0};
  for (size_t k = 0; k < scene.surfaces.size(); ++k)  // the excluded regions: the same rule
    EXPECT_EQ(excluded_regions(scene, SideRef{k, false}).size(), regions[k]) << scene.surfaces[k].name;
  // The floor: the mat's 0.25 m^2 of its 16.
  const std::vector<std::vector<ConvexPolygon>> covers = covers_by_surface(scene);
  const std::vector<Vec3> floor = {{0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}};
  EXPECT_NEAR(exposed_fraction(floor, scene.surfaces[0].normal(), covers[0]), 1 - 0.25 / 16, 1e-14);
  // Without bottom b the top is no sheet's face: bottom a covers it; and without their sheet's
  // other face the second plate's pieces cover one another (c lies on e and f, e and f on d).
  Scene half = scene;
  half.surfaces.erase(half.surfaces.begin() + 3);
  EXPECT_EQ(covering_surfaces(half)[1], std::vector<size_t>{2});
  Scene apart = scene;
  for (Vec3& c : apart.surfaces[9].corners) c.z() += 0.5;  // the third plate's top lifted off
  EXPECT_EQ(covering_surfaces(apart)[10], std::vector<size_t>{11});
}

}  // namespace covered_test
}  // namespace radrecon
