// The direct light's D1/D2 lines against hand-computed projections on the paper scene's ground: the
// whole set of thirty, each to 1e-12.

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

TEST(ShadowLines, PaperGroundHasExactlyTheThirtyLinesDerivedByHand) {
  // Projected from a light point L (z = 2.5) through a wall point P at z = 1, the ground point is
  // L + (P - L) 5/3 = (5 P - 2 L) / 3 in (x, y). The light's corners have x, y in {1, 2}; the
  // walls' tops run along x = 2.6 (y in [0.6, 2.6]) and y = 2.6 (x in [0.6, 2.6]), sharing the
  // corner (2.6, 2.6); the ground is [0, 4]^2 and segments are clipped to it.
  // - VE, the tops from each light corner: x = 11/3 or 3 (lx = 1 or 2), y from 1/3 to 11/3
  //   (ly = 1) or from -1/3 (clipped to 0) to 3 (ly = 2); wall2's the same mirrored: 8.
  // - VE, the three vertical edges from each light corner: from the foot to the top's image: 12
  //   (the shared edge counted once).
  // - EV, the light's edges through the three top corners: through (2.6, 0.6, 1) the edges x = 1
  //   and x = 2 land on x = 11/3 and x = 3 for y in [-1/3, 1/3] (clipped to [0, 1/3]) and the
  //   edge y = 1 on y = 1/3 for x in [3, 11/3], while y = 2 lands at y = -1/3, off the ground: 3;
  //   through (0.6, 2.6, 1) the mirror image: 3; through (2.6, 2.6, 1) all four edges: 4.
  const double a = 1.0 / 3, b = 3.0, c = 11.0 / 3;
  // From p on the ground towards q, ended where it leaves the ground across x = 0 or y = 0.
  const auto cut = [](const Vec2& p, const Vec2& q) {
    const double t = q.y() < 0 ? p.y() / (p.y() - q.y()) : q.x() < 0 ? p.x() / (p.x() - q.x()) : 1.0;
    return std::pair<Vec2, Vec2>{p, p + t * (q - p)};
  };
  const Vec2 foot1(2.6, 0.6), shared(2.6, 2.6), foot2(0.6, 2.6);
  const std::vector<std::pair<Vec2, Vec2>> expected = {
      // the tops
      {{c, a}, {c, c}}, {{c, 0}, {c, b}}, {{b, a}, {b, c}}, {{b, 0}, {b, b}},
      {{a, c}, {c, c}}, {{0, c}, {b, c}}, {{a, b}, {c, b}}, {{0, b}, {b, b}},
      // the vertical edges: wall1's at y = 0.6, the shared one, wall2's at x = 0.6
      cut(foot1, {c, a}), cut(foot1, {c, -a}), cut(foot1, {b, a}), cut(foot1, {b, -a}),
      cut(shared, {c, c}), cut(shared, {c, b}), cut(shared, {b, c}), cut(shared, {b, b}),
      cut(foot2, {a, c}), cut(foot2, {-a, c}), cut(foot2, {a, b}), cut(foot2, {-a, b}),
      // EV through the three top corners
      {{c, 0}, {c, a}}, {{b, 0}, {b, a}}, {{b, a}, {c, a}},
      {{0, c}, {a, c}}, {{0, b}, {a, b}}, {{a, b}, {a, c}},
      {{c, b}, {c, c}}, {{b, b}, {b, c}}, {{b, c}, {c, c}}, {{b, b}, {c, b}},
  };
  const Scene scene = paper_scene();
  const std::vector<Segment2> lines = shadow_lines(scene, *find_side(scene, "ground"));
  for (const auto& [p, q] : expected) EXPECT_TRUE(has_segment(lines, p, q, 1e-12)) << p.transpose() << " - " << q.transpose();
  EXPECT_EQ(lines.size(), expected.size());
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
