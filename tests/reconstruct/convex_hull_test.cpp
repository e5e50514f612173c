// ConvexHull2 against brute force: every point lies in the hull, the vertices are extreme and
// counter-clockwise, and nearest() is the closest point of the hull (dense sampling of its edges
// and of its inside cannot beat it).

#include <gtest/gtest.h>

#include <random>

#include "reconstruct/convex_hull.h"

namespace radrecon {
namespace convex_hull_test {

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

TEST(ConvexHull2, HoldsEveryPointWithExtremeCounterClockwiseVertices) {
  std::mt19937 rng(31);
  std::normal_distribution<double> g(0, 1);
  for (int trial = 0; trial < 50; ++trial) {
    std::vector<Vec2> p(5 + trial);
    for (Vec2& x : p) x = Vec2(g(rng), g(rng));
    const ConvexHull2 hull(p, {});
    const auto& v = hull.vertices();
    ASSERT_GE(v.size(), 3u);
    for (size_t i = 0; i < v.size(); ++i) {
      const Vec2 &a = v[i], &b = v[(i + 1) % v.size()];
      EXPECT_GT(cross(b - a, v[(i + 2) % v.size()] - b), 0) << "not strictly convex, counter-clockwise";
      for (const Vec2& x : p) EXPECT_GE(cross(b - a, x - a), -1e-12) << "a point outside edge " << i;
    }
    for (const Vec2& x : p) EXPECT_EQ(hull.nearest(x), x);
  }
}

TEST(ConvexHull2, NearestIsTheClosestPointOfTheHull) {
  std::mt19937 rng(32);
  std::uniform_real_distribution<double> u(-1, 1), far(-4, 4);
  std::vector<Vec2> p(30);
  for (Vec2& x : p) x = Vec2(u(rng), 0.5 * u(rng));
  const ConvexHull2 hull(p, {});
  const auto& v = hull.vertices();
  // Brute force: points along every edge (the nearest point of a convex polygon to a point
  // outside it lies on its boundary).
  std::vector<Vec2> boundary;
  for (size_t i = 0; i < v.size(); ++i)
    for (int t = 0; t <= 2000; ++t) boundary.push_back(v[i] + (t / 2000.0) * (v[(i + 1) % v.size()] - v[i]));
  for (int trial = 0; trial < 300; ++trial) {
    const Vec2 q(far(rng), far(rng));
    const Vec2 n = hull.nearest(q);
    double brute = 1e300;
    for (const Vec2& b : boundary) brute = std::min(brute, (b - q).norm());
    bool inside = true;
    for (size_t i = 0; i < v.size(); ++i) inside = inside && cross(v[(i + 1) % v.size()] - v[i], q - v[i]) >= 0;
    if (inside) {
      EXPECT_EQ(n, q);
    } else {
      EXPECT_LE((n - q).norm(), brute + 1e-12);
      EXPECT_GE((n - q).norm(), brute - 2e-3);  // the sampling's spacing bounds how much closer
    }
  }
}

TEST(ConvexHull2, DepthIsTheDistanceToTheBoundary) {
  // The unit square: depth = distance to the nearest side inside, 0 outside.
  const std::vector<Vec2> square = {Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1), Vec2(0.3, 0.6)};
  const ConvexHull2 hull(square, {});
  EXPECT_NEAR(hull.depth(Vec2(0.5, 0.5)), 0.5, 1e-15);
  EXPECT_NEAR(hull.depth(Vec2(0.2, 0.7)), 0.2, 1e-15);
  EXPECT_NEAR(hull.depth(Vec2(0.9, 0.95)), 0.05, 1e-15);
  EXPECT_EQ(hull.depth(Vec2(1.5, 0.5)), 0);
  EXPECT_EQ(hull.depth(Vec2(1, 0.5)), 0);
}

TEST(ConvexHull2, SegmentsAndPointsOfDegenerateSets) {
  const std::vector<Vec2> line = {Vec2(0, 0), Vec2(1, 1), Vec2(2, 2), Vec2(0.5, 0.5)};
  const ConvexHull2 segment(line, {});
  ASSERT_EQ(segment.vertices().size(), 2u);
  EXPECT_TRUE(segment.nearest(Vec2(2, 0)).isApprox(Vec2(1, 1)));
  EXPECT_TRUE(segment.nearest(Vec2(5, 5)).isApprox(Vec2(2, 2)));
  const std::vector<Vec2> same = {Vec2(3, 4), Vec2(3, 4)};
  const ConvexHull2 point(same, {});
  ASSERT_EQ(point.vertices().size(), 1u);
  EXPECT_EQ(point.nearest(Vec2(0, 0)), Vec2(3, 4));
  // A subset: only the chosen points count.
  const std::vector<unsigned> pick = {0, 2};
  const ConvexHull2 part(line, pick);
  EXPECT_TRUE(part.nearest(Vec2(3, 3)).isApprox(Vec2(2, 2)));
}

}  // namespace convex_hull_test
}  // namespace radrecon
