// Contact lines against the scenes' closed forms: the paper's wall feet on the ground, the base
// of a box on a floor, a card through a floor, and nothing where surfaces do not touch.

#include <gtest/gtest.h>

#include <algorithm>

#include "scene/contacts.h"
#include "support/scenes.h"

namespace radrecon {
namespace {

using testing_support::quad;

constexpr double kExact = 1e-12;  ///< metres: the contact points are corners, up to round-off

void expect_segment(const Segment2& got, const Vec2& a, const Vec2& b) {
  EXPECT_NEAR(got.a.x(), a.x(), kExact);
  EXPECT_NEAR(got.a.y(), a.y(), kExact);
  EXPECT_NEAR(got.b.x(), b.x(), kExact);
  EXPECT_NEAR(got.b.y(), b.y(), kExact);
}

TEST(ContactLines, ThePaperGroundHasExactlyTheTwoWallFeet) {
  const Scene scene = paper_scene();
  const SideRef ground = *find_side(scene, "ground");
  const std::vector<Segment2> lines = contact_lines(scene, ground);
  ASSERT_EQ(lines.size(), 2u);
  expect_segment(lines[0], {2.6, 0.6}, {2.6, 2.6});  // wall1's foot (scene order: wall1, wall2)
  expect_segment(lines[1], {0.6, 2.6}, {2.6, 2.6});  // wall2's foot
  // The walls meet the ground and each other only along their own borders; the light touches
  // nothing.
  for (const char* side : {"wall1/front", "wall1/back", "wall2/front", "wall2/back", "light"})
    EXPECT_TRUE(contact_lines(scene, *find_side(scene, side)).empty()) << side;
}

TEST(ContactLines, ABoxOnAFloorGivesItsFourBaseEdges) {
  Scene scene;
  scene.surfaces.push_back(quad("floor", {0, 0, 0}, {10, 0, 0}, {10, 10, 0}, {0, 10, 0}, 0.5));
  // A 2 x 3 x 1 box at (4..6, 3..6), its four sides (normals outward), standing on the floor.
  scene.surfaces.push_back(quad("south", {4, 3, 0}, {6, 3, 0}, {6, 3, 1}, {4, 3, 1}, 0.5));
  scene.surfaces.push_back(quad("east", {6, 3, 0}, {6, 6, 0}, {6, 6, 1}, {6, 3, 1}, 0.5));
  scene.surfaces.push_back(quad("north", {6, 6, 0}, {4, 6, 0}, {4, 6, 1}, {6, 6, 1}, 0.5));
  scene.surfaces.push_back(quad("west", {4, 6, 0}, {4, 3, 0}, {4, 3, 1}, {4, 6, 1}, 0.5));
  scene.surfaces.push_back(quad("top", {4, 3, 1}, {6, 3, 1}, {6, 6, 1}, {4, 6, 1}, 0.5));
  const std::vector<Segment2> lines = contact_lines(scene, SideRef{0, false});
  ASSERT_EQ(lines.size(), 4u);
  expect_segment(lines[0], {4, 3}, {6, 3});
  expect_segment(lines[1], {6, 3}, {6, 6});
  expect_segment(lines[2], {4, 6}, {6, 6});
  expect_segment(lines[3], {4, 3}, {4, 6});
}

TEST(ContactLines, ACardThroughAFloorCutsItsFrontAndBackAndAGapCutsNothing) {
  Scene scene;
  auto floor = quad("floor", {0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}, 0.5);
  floor.two_sided = true;
  scene.surfaces.push_back(floor);
  scene.surfaces.push_back(quad("card", {1, 1, -1}, {3, 1, -1}, {3, 1, 1}, {1, 1, 1}, 0.5));  // through it
  scene.surfaces.push_back(quad("hover", {1, 3, 0.01}, {3, 3, 0.01}, {3, 3, 1}, {1, 3, 1}, 0.5));  // 1 cm above
  for (bool back : {false, true}) {
    const std::vector<Segment2> lines = contact_lines(scene, SideRef{0, back});
    ASSERT_EQ(lines.size(), 1u) << (back ? "back" : "front");
    expect_segment(lines[0], {1, 1}, {3, 1});
  }
}

TEST(ContactLines, AStandingSurfaceIsClippedToTheSide) {
  Scene scene;
  scene.surfaces.push_back(quad("floor", {0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}, 0.5));
  scene.surfaces.push_back(quad("long wall", {-1, 2, 0}, {6, 2, 0}, {6, 2, 1}, {-1, 2, 1}, 0.5));
  const std::vector<Segment2> lines = contact_lines(scene, SideRef{0, false});
  ASSERT_EQ(lines.size(), 1u);
  expect_segment(lines[0], {0, 2}, {4, 2});
}

}  // namespace
}  // namespace radrecon
