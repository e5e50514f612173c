// Contact lines and excluded regions against hand-computed coordinates: the paper's wall feet on
// the ground (and nothing excluded there), the base of a box on a floor and the square under it,
// a plate lying on a floor, a card through a floor, a closed box, and nothing where surfaces do
// not touch.

#include <gtest/gtest.h>

#include <algorithm>

#include "scene/contacts.h"
#include "support/scenes.h"

namespace radrecon {
namespace contacts_test {

using testing_support::quad;

constexpr double kExact = 1e-12;  ///< metres: the contact points are corners, up to round-off

void expect_segment(const Segment2& got, const Vec2& a, const Vec2& b) {
  EXPECT_NEAR(got.a.x(), a.x(), kExact);
  EXPECT_NEAR(got.a.y(), a.y(), kExact);
  EXPECT_NEAR(got.b.x(), b.x(), kExact);
  EXPECT_NEAR(got.b.y(), b.y(), kExact);
}

/// `lines` are exactly `expected` (each from its lexicographically smaller end), in any order.
void expect_lines(const std::vector<Segment2>& lines, const std::vector<Segment2>& expected) {
  ASSERT_EQ(lines.size(), expected.size());
  for (const Segment2& e : expected) {
    const auto same = [&](const Segment2& l) { return (l.a - e.a).norm() <= kExact && (l.b - e.b).norm() <= kExact; };
    EXPECT_EQ(std::count_if(lines.begin(), lines.end(), same), 1)
        << "(" << e.a.x() << ", " << e.a.y() << ") - (" << e.b.x() << ", " << e.b.y() << ")";
  }
}

/// `region` is exactly `corners`: counter-clockwise from the lexicographically smallest, the first
/// not repeated.
void expect_region(const Polyline& region, const std::vector<Vec2>& corners) {
  ASSERT_EQ(region.size(), corners.size());
  for (size_t i = 0; i < corners.size(); ++i) {
    EXPECT_NEAR(region[i].x(), corners[i].x(), kExact) << "vertex " << i;
    EXPECT_NEAR(region[i].y(), corners[i].y(), kExact) << "vertex " << i;
  }
}

/// A wall of height h standing on z = 0 along (x0, y0) -> (x1, y1).
Surface wall(const std::string& name, double x0, double y0, double x1, double y1, double h = 1) {
  return quad(name, {x0, y0, 0}, {x1, y1, 0}, {x1, y1, h}, {x0, y0, h}, 0.5);
}

/// A 4 m x 4 m floor at z = 0, facing up, (s, t) = (x, y).
Surface floor4() { return quad("floor", {0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}, 0.5); }

/// A unit box standing on the 4 m floor at (1..2, 1..2): four walls (normals outward) and a top.
Scene unit_box_on_a_floor() {
  Scene scene;
  scene.surfaces.push_back(floor4());
  scene.surfaces.push_back(wall("south", 1, 1, 2, 1));
  scene.surfaces.push_back(wall("east", 2, 1, 2, 2));
  scene.surfaces.push_back(wall("north", 2, 2, 1, 2));
  scene.surfaces.push_back(wall("west", 1, 2, 1, 1));
  scene.surfaces.push_back(quad("top", {1, 1, 1}, {2, 1, 1}, {2, 2, 1}, {1, 2, 1}, 0.5));
  return scene;
}

const std::vector<Segment2> kUnitBoxBase = {{{1, 1}, {2, 1}}, {{2, 1}, {2, 2}}, {{1, 2}, {2, 2}}, {{1, 1}, {1, 2}}};
const std::vector<Vec2> kUnitBoxSquare = {{1, 1}, {2, 1}, {2, 2}, {1, 2}};

TEST(ContactLines, ThePaperGroundHasExactlyTheTwoWallFeet) {
  const Scene scene = paper_scene();
  const SideRef ground = *find_side(scene, "ground");
  const std::vector<Segment2> lines = contact_lines(scene, ground);
  ASSERT_EQ(lines.size(), 2u);
  expect_segment(lines[0], {2.6, 0.6}, {2.6, 2.6});  // wall1's foot (scene order: wall1, wall2)
  expect_segment(lines[1], {0.6, 2.6}, {2.6, 2.6});  // wall2's foot
  // To the last bit, as docs/method.md says: an end the ground does not cut is the wall's own
  // corner (it was 0.6000000000000001, and a sight line through the corner passed; an outside-in
  // trial's brute force put constant's Table 3a L1 at .020626, the tool at .020639).
  EXPECT_EQ(lines[0].a, Vec2(2.6, 0.6));
  EXPECT_EQ(lines[0].b, Vec2(2.6, 2.6));
  EXPECT_EQ(lines[1].a, Vec2(0.6, 2.6));
  EXPECT_EQ(lines[1].b, Vec2(2.6, 2.6));
  // The walls meet the ground and each other only along their own borders; the light touches
  // nothing.
  for (const char* side : {"wall1/front", "wall1/back", "wall2/front", "wall2/back", "light"})
    EXPECT_TRUE(contact_lines(scene, *find_side(scene, side)).empty()) << side;
}

TEST(ExcludedRegions, ThePaperSceneHasNoneItsLShapedWallsCloseNoLoop) {
  const Scene scene = paper_scene();
  for (const char* side : {"ground", "wall1/front", "wall1/back", "wall2/front", "wall2/back", "light"})
    EXPECT_TRUE(excluded_regions(scene, *find_side(scene, side)).empty()) << side;
}

TEST(ExcludedRegions, AUnitBoxOnAFloorGivesItsFourBaseEdgesAndTheSquareUnderIt) {
  const Scene scene = unit_box_on_a_floor();
  expect_lines(contact_lines(scene, SideRef{0, false}), kUnitBoxBase);
  const std::vector<Polyline> regions = excluded_regions(scene, SideRef{0, false});
  ASSERT_EQ(regions.size(), 1u);
  expect_region(regions[0], kUnitBoxSquare);
  // The box's own faces: the floor and the neighbouring walls meet them along their borders.
  for (size_t k = 1; k < scene.surfaces.size(); ++k) {
    EXPECT_TRUE(contact_lines(scene, SideRef{k, false}).empty()) << scene.surfaces[k].name;
    EXPECT_TRUE(excluded_regions(scene, SideRef{k, false}).empty()) << scene.surfaces[k].name;
  }
}

TEST(ExcludedRegions, AClosedBoxsBottomLyingOnTheFloorAddsNothingToItsWalls) {
  // The bottom facing down (outward) or up (inward): either way it lies on the floor, its edges
  // are the walls' feet (one line each), and the square it covers is the one they enclose.
  for (const bool up : {false, true}) {
    Scene scene = unit_box_on_a_floor();
    scene.surfaces.push_back(up ? quad("bottom", {1, 1, 0}, {2, 1, 0}, {2, 2, 0}, {1, 2, 0}, 0.5)
                                : quad("bottom", {1, 1, 0}, {1, 2, 0}, {2, 2, 0}, {2, 1, 0}, 0.5));
    expect_lines(contact_lines(scene, SideRef{0, false}), kUnitBoxBase);
    const std::vector<Polyline> regions = excluded_regions(scene, SideRef{0, false});
    ASSERT_EQ(regions.size(), 1u) << (up ? "up" : "down");
    expect_region(regions[0], kUnitBoxSquare);
    // The floor is larger: it does not lie on the bottom.
    const SideRef bottom{scene.surfaces.size() - 1, false};
    EXPECT_TRUE(contact_lines(scene, bottom).empty());
    EXPECT_TRUE(excluded_regions(scene, bottom).empty());
  }
}

TEST(ExcludedRegions, APlateLyingOnAFloorIsCoveredAndOutlinedInTheFloorsMetres) {
  // The floor's corner 0 at (4, 4), u along -x, v along -y: (s, t) = (4 - x, 4 - y).
  Scene scene;
  scene.surfaces.push_back(quad("floor", {4, 4, 0}, {0, 4, 0}, {0, 0, 0}, {4, 0, 0}, 0.5));
  scene.surfaces.push_back(quad("plate", {0.5, 2, 0}, {1.5, 2, 0}, {1.5, 3, 0}, {0.5, 3, 0}, 0.5));
  // Covering x in [0.5, 1.5], y in [2, 3]: s in [2.5, 3.5], t in [1, 2].
  expect_lines(contact_lines(scene, SideRef{0, false}),
               {{{2.5, 1}, {3.5, 1}}, {{3.5, 1}, {3.5, 2}}, {{2.5, 2}, {3.5, 2}}, {{2.5, 1}, {2.5, 2}}});
  const std::vector<Polyline> regions = excluded_regions(scene, SideRef{0, false});
  ASSERT_EQ(regions.size(), 1u);
  expect_region(regions[0], {{2.5, 1}, {3.5, 1}, {3.5, 2}, {2.5, 2}});
  // The plate itself is neither cut nor covered.
  EXPECT_TRUE(contact_lines(scene, SideRef{1, false}).empty());
  EXPECT_TRUE(excluded_regions(scene, SideRef{1, false}).empty());
}

TEST(ExcludedRegions, APlateOverTheFloorsEdgeIsClippedAndItsEdgeOnTheBorderIsNoBarrier) {
  // Facing down, 1e-7 m above the floor: within the contact tolerance (1e-6 of its 2 m).
  Scene scene;
  auto floor = floor4();
  floor.two_sided = true;
  scene.surfaces.push_back(floor);
  scene.surfaces.push_back(quad("plate", {3, 1, 1e-7}, {3, 2, 1e-7}, {5, 2, 1e-7}, {5, 1, 1e-7}, 0.5));
  for (const bool back : {false, true}) {  // no thickness: both sides are covered
    expect_lines(contact_lines(scene, SideRef{0, back}), {{{3, 1}, {4, 1}}, {{3, 1}, {3, 2}}, {{3, 2}, {4, 2}}});
    const std::vector<Polyline> regions = excluded_regions(scene, SideRef{0, back});
    ASSERT_EQ(regions.size(), 1u) << (back ? "back" : "front");
    expect_region(regions[0], {{3, 1}, {4, 1}, {4, 2}, {3, 2}});
  }
}

TEST(ExcludedRegions, NeighboursAndDuplicatesCoverNothingAndAGapIsNoContact) {
  Scene scene;
  scene.surfaces.push_back(floor4());
  scene.surfaces.push_back(quad("next tile", {4, 0, 0}, {6, 0, 0}, {6, 4, 0}, {4, 4, 0}, 0.5));      // beside it
  scene.surfaces.push_back(quad("duplicate", {4, 0, 0}, {4, 4, 0}, {0, 4, 0}, {0, 0, 0}, 0.5));      // itself, again
  scene.surfaces.push_back(quad("hovering", {1, 1, 1e-3}, {2, 1, 1e-3}, {2, 2, 1e-3}, {1, 2, 1e-3}, 0.5));  // 1 mm up
  for (size_t k = 0; k < scene.surfaces.size(); ++k) {
    EXPECT_TRUE(contact_lines(scene, SideRef{k, false}).empty()) << scene.surfaces[k].name;
    EXPECT_TRUE(excluded_regions(scene, SideRef{k, false}).empty()) << scene.surfaces[k].name;
  }
}

TEST(ExcludedRegions, TwoBoxesTouchingAreTwoRegionsAndDanglingOrOpenWallsEncloseNothing) {
  Scene scene;
  scene.surfaces.push_back(floor4());
  // Two unit boxes side by side at (1..2, 1..2) and (2..3, 1..2), their walls facing out: the two
  // walls at x = 2 stand back to back, each facing into the other box, and hide each other.
  scene.surfaces.push_back(wall("south left", 1, 1, 2, 1));
  scene.surfaces.push_back(wall("south right", 2, 1, 3, 1));
  scene.surfaces.push_back(wall("east", 3, 1, 3, 2));
  scene.surfaces.push_back(wall("north right", 3, 2, 2, 2));
  scene.surfaces.push_back(wall("north left", 2, 2, 1, 2));
  scene.surfaces.push_back(wall("west", 1, 2, 1, 1));
  scene.surfaces.push_back(wall("left box's east", 2, 1, 2, 2));
  scene.surfaces.push_back(wall("right box's west", 2, 2, 2, 1));
  scene.surfaces.push_back(wall("fence", 3, 2, 3.5, 3));            // from a corner, ending in the open
  scene.surfaces.push_back(wall("partition", 3, 1, 2.5, 1.5, 0.5));  // from a corner into the right box
  // Elsewhere, an open yard of three walls.
  scene.surfaces.push_back(wall("yard west", 1, 3, 1, 3.8));
  scene.surfaces.push_back(wall("yard north", 1, 3.8, 2, 3.8));
  scene.surfaces.push_back(wall("yard east", 2, 3.8, 2, 3));
  EXPECT_EQ(contact_lines(scene, SideRef{0, false}).size(), 12u);
  const std::vector<Polyline> regions = excluded_regions(scene, SideRef{0, false});
  ASSERT_EQ(regions.size(), 2u);
  const bool left_first = regions[0][0].x() < 1.5;
  expect_region(regions[left_first ? 0 : 1], {{1, 1}, {2, 1}, {2, 2}, {1, 2}});
  expect_region(regions[left_first ? 1 : 0], {{2, 1}, {3, 1}, {3, 2}, {2, 2}});
}

TEST(ExcludedRegions, AnAreaThatAStandingSurfaceFacesIsLeftToTheSolver) {
  // The floor inside a room whose walls face in may be seen: a closed room whose walls stand just
  // inside the floor's edge (1e-7 m, float rounding in a model) lost its whole floor. Geometry
  // alone does not exclude such an area; ContactFinder lists it last as faced, and the solver
  // excludes it only if no light reaches it (tests/sampling/solution_reconstruction_test.cpp).
  const auto faced = [](const Scene& scene) { return ContactFinder(scene).at(SideRef{0, false}).faced; };
  for (const double inset : {1e-7, 0.5}) {
    Scene room;
    room.surfaces.push_back(floor4());
    const double a = inset, b = 4 - inset;
    room.surfaces.push_back(wall("south", b, a, a, a));  // (x0, y0) -> (x1, y1) reversed: facing in
    room.surfaces.push_back(wall("east", b, b, b, a));
    room.surfaces.push_back(wall("north", a, b, b, b));
    room.surfaces.push_back(wall("west", a, a, a, b));
    EXPECT_EQ(contact_lines(room, SideRef{0, false}).size(), 4u) << inset;
    EXPECT_TRUE(excluded_regions(room, SideRef{0, false}).empty()) << inset;
    EXPECT_EQ(faced(room), 1u) << inset;
  }
  // One wall of a box facing in (a model's flipped face): its foot's square is seen.
  Scene flipped = unit_box_on_a_floor();
  flipped.surfaces[2] = wall("east", 2, 2, 2, 1);
  EXPECT_TRUE(excluded_regions(flipped, SideRef{0, false}).empty());
  EXPECT_EQ(faced(flipped), 1u);
  // A two-sided wall sees both halves: a pen of two-sided fences encloses its yard, seen.
  Scene pen = unit_box_on_a_floor();
  pen.surfaces.pop_back();  // no top
  for (size_t k = 1; k <= 4; ++k) pen.surfaces[k].two_sided = true;
  EXPECT_TRUE(excluded_regions(pen, SideRef{0, false}).empty());
  EXPECT_EQ(faced(pen), 1u);
  // The same walls one-sided facing out, a roofless box: its yard is still excluded (enclosure is
  // read from the lines and the walls' facing, not from a roof).
  pen.surfaces[1].two_sided = pen.surfaces[2].two_sided = pen.surfaces[3].two_sided = pen.surfaces[4].two_sided = false;
  ASSERT_EQ(excluded_regions(pen, SideRef{0, false}).size(), 1u);
  expect_region(excluded_regions(pen, SideRef{0, false})[0], kUnitBoxSquare);
  EXPECT_EQ(faced(pen), 0u);
}

TEST(ExcludedRegions, AClosedBoxExcludesNothingItsWallsStandOnItsFloorsBorder) {
  const Scene box = testing_support::closed_box(0.5, 1);
  for (size_t k = 0; k < box.surfaces.size(); ++k) {
    EXPECT_TRUE(contact_lines(box, SideRef{k, false}).empty()) << box.surfaces[k].name;
    EXPECT_TRUE(excluded_regions(box, SideRef{k, false}).empty()) << box.surfaces[k].name;
  }
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

TEST(ContactFinder, ManyBoxesOnAFloorEachGiveTheirBaseAndSquareAndWallFeetWithinToleranceCount) {
  // 10 x 10 boxes of 0.2 m at a 0.4 m pitch on the 4 m floor; the walls of every other box stand
  // 1.5e-7 m above it, within the contact tolerance (1e-6 of a wall's 0.2 m is 2e-7), so each of
  // its surfaces' boxes misses the floor's unwidened one: the finder's widened boxes must meet.
  Scene scene;
  scene.surfaces.push_back(floor4());
  constexpr int kBoxes = 10;
  constexpr double kSize = 0.2, kPitch = 0.4, kLift = 1.5e-7;
  for (int j = 0; j < kBoxes; ++j)
    for (int i = 0; i < kBoxes; ++i) {
      const double x0 = 0.1 + kPitch * i, y0 = 0.1 + kPitch * j, x1 = x0 + kSize, y1 = y0 + kSize;
      const double z = (i + j) % 2 == 0 ? 0.0 : kLift, h = z + kSize;
      const auto raised = [&](const char* name, double ax, double ay, double bx, double by) {
        return quad(name, {ax, ay, z}, {bx, by, z}, {bx, by, h}, {ax, ay, h}, 0.5);
      };
      scene.surfaces.push_back(raised("south", x0, y0, x1, y0));
      scene.surfaces.push_back(raised("east", x1, y0, x1, y1));
      scene.surfaces.push_back(raised("north", x1, y1, x0, y1));
      scene.surfaces.push_back(raised("west", x0, y1, x0, y0));
      scene.surfaces.push_back(quad("top", {x0, y0, h}, {x1, y0, h}, {x1, y1, h}, {x0, y1, h}, 0.5));
    }
  const ContactFinder finder(scene);
  const SideContactSet floor = finder.at(SideRef{0, false});
  ASSERT_EQ(floor.lines.size(), 4u * kBoxes * kBoxes);
  ASSERT_EQ(floor.excluded.size(), static_cast<size_t>(kBoxes * kBoxes));
  double area_m2 = 0;  // the squares' total, by the shoelace formula
  for (const Polyline& r : floor.excluded)
    for (size_t k = 0; k < r.size(); ++k) area_m2 += 0.5 * (r[k].x() * r[(k + 1) % r.size()].y() - r[(k + 1) % r.size()].x() * r[k].y());
  EXPECT_NEAR(area_m2, kBoxes * kBoxes * kSize * kSize, 1e-9);
  // A box's faces touch only their own neighbours, along their borders: nothing.
  for (size_t k = 1; k < scene.surfaces.size(); ++k) {
    const SideContactSet face = finder.at(SideRef{k, false});
    EXPECT_TRUE(face.lines.empty() && face.excluded.empty()) << k;
  }
}

}  // namespace contacts_test
}  // namespace radrecon
