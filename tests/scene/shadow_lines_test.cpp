// The direct light's D1/D2 lines against hand-computed projections on the paper scene's ground.

#include <gtest/gtest.h>

#include <algorithm>

#include "scene/scene.h"
#include "scene/shadow_lines.h"

namespace radrecon {
namespace shadow_lines_test {

bool has_segment(const std::vector<Segment2>& lines, Vec2 a, Vec2 b, double tol = 1e-12) {
  if (std::tie(b.x(), b.y()) < std::tie(a.x(), a.y())) std::swap(a, b);
  return std::any_of(lines.begin(), lines.end(),
                     [&](const Segment2& s) { return (s.a - a).norm() <= tol && (s.b - b).norm() <= tol; });
}

TEST(ShadowLines, PaperGroundHasTheProjectionsOfTheWallTops) {
  const Scene scene = paper_scene();
  const std::vector<Segment2> lines = shadow_lines(scene, *find_side(scene, "ground"));
  // wall1's top edge, x = 2.6, z = 1, y in [0.6, 2.6], seen from the light's vertices at z = 2.5:
  // from x = 1 it lands at x = 2.6 + 1.6 / 1.5 = 3.6667 and from x = 2 at x = 2.6 + 0.6 / 1.5 = 3;
  // from y = 1 the ends land at y = 1 + (0.6 - 1) * 2.5 / 1.5 = 1 / 3 and 1 + 1.6 * 2.5 / 1.5 = 11 / 3.
  EXPECT_TRUE(has_segment(lines, {11.0 / 3, 1.0 / 3}, {11.0 / 3, 11.0 / 3}));
  EXPECT_TRUE(has_segment(lines, {3.0, 1.0 / 3}, {3.0, 11.0 / 3}));
  // wall2's top edge (y = 2.6) by symmetry.
  EXPECT_TRUE(has_segment(lines, {1.0 / 3, 11.0 / 3}, {11.0 / 3, 11.0 / 3}));
  EXPECT_TRUE(has_segment(lines, {1.0 / 3, 3.0}, {11.0 / 3, 3.0}));
  // EV: the light's edge x = 1 (y in [1, 2]) through wall1's top corner (2.6, 0.6, 1) lands on
  // x = 11/3 between y = 0.6 + (0.6 - 1) / 1.5 = 1/3 and 0.6 + (0.6 - 2) / 1.5 = -1/3, clipped to 0.
  EXPECT_TRUE(has_segment(lines, {11.0 / 3, 0.0}, {11.0 / 3, 1.0 / 3}));
  for (const Segment2& s : lines) {
    for (const Vec2& p : {s.a, s.b}) {
      EXPECT_GE(p.x(), 0);
      EXPECT_LE(p.x(), 4);
      EXPECT_GE(p.y(), 0);
      EXPECT_LE(p.y(), 4);
    }
    EXPECT_GT((s.b - s.a).norm(), 0);
  }
  // No contact line among them: the walls' feet are D0 lines (contacts.h).
  EXPECT_FALSE(has_segment(lines, {2.6, 0.6}, {2.6, 2.6}, 1e-9));
}

TEST(ShadowLines, ALightFacingAwayOrAnUnlitSideCastsNone) {
  Scene scene = paper_scene();
  // The light faces -z (down at the ground); turned to face up, it lights nothing below it.
  std::swap(scene.surfaces[1].corners[1], scene.surfaces[1].corners[3]);
  EXPECT_TRUE(shadow_lines(scene, *find_side(scene, "ground")).empty());
  // The light itself receives no shadow line from occluders below it.
  const Scene paper = paper_scene();
  EXPECT_TRUE(shadow_lines(paper, *find_side(paper, "light")).empty());
}

}  // namespace shadow_lines_test
}  // namespace radrecon
