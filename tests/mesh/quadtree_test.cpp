// The quadtree of a surface side against closed forms and brute force: nodes are the images of
// their (u,v) rectangles, leaves tile the side, locate() finds the one leaf that holds a point.

#include <gtest/gtest.h>

#include <random>

#include "mesh/quadtree.h"

namespace radrecon {
namespace quadtree_test {

Surface trapezoid() {
  // A planar, non-parallelogram quad (z = 0), so that (u,v) -> point is truly bilinear.
  Surface s;
  s.name = "trapezoid";
  s.corners = {Vec3(0, 0, 0), Vec3(4, 0, 0), Vec3(3, 2, 0), Vec3(1, 2, 0)};
  s.reflectance = Rgb::Constant(0.5);
  return s;
}

/// Splits random leaves, fixed seed: an irregular tree.
Quadtree random_tree(const Surface& s, bool back, int splits, unsigned seed) {
  Quadtree t(s, back);
  std::mt19937 rng(seed);
  for (int k = 0; k < splits; ++k) {
    const std::vector<int> leaves = t.leaves();
    t.split(leaves[std::uniform_int_distribution<size_t>(0, leaves.size() - 1)(rng)]);
  }
  return t;
}

TEST(Quadtree, NodesAreTheImagesOfTheirParameterRectangles) {
  const Surface s = trapezoid();
  const Quadtree t = random_tree(s, false, 30, 7);
  for (int k = 0; k < t.node_count(); ++k) {
    const QuadNode& n = t.node(k);
    EXPECT_TRUE(n.corners[0].isApprox(s.point(n.u0, n.v0), 1e-14));
    EXPECT_TRUE(n.corners[1].isApprox(s.point(n.u1, n.v0), 1e-14));
    EXPECT_TRUE(n.corners[2].isApprox(s.point(n.u1, n.v1), 1e-14));
    EXPECT_TRUE(n.corners[3].isApprox(s.point(n.u0, n.v1), 1e-14));
    EXPECT_TRUE(n.center.isApprox(s.point(0.5 * (n.u0 + n.u1), 0.5 * (n.v0 + n.v1)), 1e-14));
  }
}

TEST(Quadtree, BackSideNodesAreCounterClockwiseFromBehind) {
  const Surface s = trapezoid();
  const Quadtree t(s, true);
  const QuadNode& root = t.node(0);
  // Seen from -z the corners must turn counter-clockwise: their Newell normal points to -z.
  const Vec3 n = (root.corners[2] - root.corners[0]).cross(root.corners[3] - root.corners[1]);
  EXPECT_LT(n.z(), 0);
}

TEST(Quadtree, LeavesTileTheSide) {
  const Surface s = trapezoid();
  for (unsigned seed : {1u, 2u, 3u}) {
    const Quadtree t = random_tree(s, false, 40, seed);
    const std::vector<int> leaves = t.leaves();
    ASSERT_EQ(static_cast<int>(leaves.size()), t.leaf_count());
    EXPECT_EQ((t.leaf_count() - 1) % 3, 0);
    double area = 0, uv_area = 0;
    for (int k : leaves) {
      area += t.node(k).area_m2;
      uv_area += (t.node(k).u1 - t.node(k).u0) * (t.node(k).v1 - t.node(k).v0);
    }
    EXPECT_NEAR(uv_area, 1.0, 1e-14);
    EXPECT_NEAR(area, s.area_m2(), 1e-12 * s.area_m2());  // the trapezoid's area: (4 + 2) / 2 * 2 = 6
    EXPECT_NEAR(s.area_m2(), 6.0, 1e-14);
  }
}

TEST(Quadtree, LocateFindsTheOneLeafHoldingThePointAsBruteForceDoes) {
  const Surface s = trapezoid();
  const Quadtree t = random_tree(s, false, 60, 11);
  const std::vector<int> leaves = t.leaves();
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(0, 1);
  std::vector<std::pair<double, double>> queries = {{0, 0}, {1, 1}, {1, 0}, {0, 1}, {0.5, 0.5}, {0.25, 0.75}};
  for (int k = 0; k < 2000; ++k) queries.emplace_back(unit(rng), unit(rng));
  for (const auto& [u, v] : queries) {
    // Brute force: half-open leaves, closed on the far border.
    int holder = -1, holders = 0;
    for (int k : leaves) {
      const QuadNode& n = t.node(k);
      const bool in_u = n.u0 <= u && (u < n.u1 || (n.u1 == 1 && u == 1));
      const bool in_v = n.v0 <= v && (v < n.v1 || (n.v1 == 1 && v == 1));
      if (in_u && in_v) holder = k, ++holders;
    }
    ASSERT_EQ(holders, 1) << "(" << u << ", " << v << ")";
    EXPECT_EQ(t.locate(u, v), holder) << "(" << u << ", " << v << ")";
  }
}

TEST(Quadtree, SplittingAnInnerNodeKeepsItsChildren) {
  const Surface s = trapezoid();
  Quadtree t(s, false);
  const int first = t.split(0);
  EXPECT_EQ(first, 1);
  EXPECT_EQ(t.split(0), first);
  EXPECT_EQ(t.leaf_count(), 4);
  EXPECT_EQ(t.node_count(), 5);
}

}  // namespace quadtree_test
}  // namespace radrecon
