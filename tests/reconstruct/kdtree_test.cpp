// KdTree2::nearest against brute force: for every k the k smallest squared distances exactly,
// every point strictly closer than the k-th found, ordered by (dist_sq, index); on random points
// and on an integer lattice, where equal distances are everywhere.

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <random>
#include <vector>

#include "reconstruct/kdtree.h"

namespace radrecon {
namespace kdtree_test {

constexpr int kMaxK = 64;

/// Squared distance as the tree computes it (coordinate differences squared and summed), so that
/// the comparison below can be exact.
double dist_sq(const Vec2& a, const Vec2& b) {
  const double dx = a.x() - b.x(), dy = a.y() - b.y();
  return dx * dx + dy * dy;
}

/// Checks one query for every k in [1, kMaxK] against all points sorted by (dist_sq, index).
void check_query(const KdTree2& tree, const std::vector<Vec2>& points, const Vec2& q) {
  std::vector<std::pair<double, unsigned>> brute(points.size());
  for (size_t i = 0; i < points.size(); ++i) brute[i] = {dist_sq(points[i], q), static_cast<unsigned>(i)};
  std::sort(brute.begin(), brute.end());
  // Buffers larger than k, pre-filled with garbage: nearest() must not read or need them.
  std::vector<unsigned> indices(kMaxK + 3);
  std::vector<double> d2(kMaxK + 3);
  for (int k = 1; k <= kMaxK; ++k) {
    std::fill(indices.begin(), indices.end(), 0xdeadbeefu);
    std::fill(d2.begin(), d2.end(), -1.0);
    const size_t found = tree.nearest(q, k, indices, d2);
    ASSERT_EQ(found, static_cast<size_t>(k)) << "q = (" << q.x() << ", " << q.y() << ")";
    const double kth = brute[static_cast<size_t>(k - 1)].first;
    std::vector<bool> returned(points.size(), false);
    for (size_t j = 0; j < found; ++j) {
      ASSERT_LT(indices[j], points.size());
      EXPECT_FALSE(returned[indices[j]]) << "index " << indices[j] << " returned twice, k=" << k;
      returned[indices[j]] = true;
      // The k smallest distances, exactly, and each one is its point's.
      EXPECT_EQ(d2[j], brute[j].first) << "k=" << k << " j=" << j;
      EXPECT_EQ(d2[j], dist_sq(points[indices[j]], q)) << "k=" << k << " j=" << j;
      if (j > 0) {
        EXPECT_TRUE(d2[j - 1] < d2[j] || (d2[j - 1] == d2[j] && indices[j - 1] < indices[j]))
            << "order at j=" << j << ", k=" << k << ": (" << d2[j - 1] << ", " << indices[j - 1] << ") then (" << d2[j]
            << ", " << indices[j] << ")";
      }
    }
    // Every point strictly closer than the k-th distance is among them (ties at the k-th
    // distance may be any of the equidistant points).
    for (const auto& [d, i] : brute) {
      if (!(d < kth)) break;
      EXPECT_TRUE(returned[i]) << "point " << i << " at dist_sq " << d << " < k-th " << kth << " missing, k=" << k;
    }
  }
}

TEST(KdTree2, MatchesBruteForceOnRandomPointsForEveryK) {
  std::mt19937 rng(20240611);
  std::uniform_real_distribution<double> xy(-2, 3);
  std::vector<Vec2> points;
  for (int i = 0; i < 10000; ++i) points.emplace_back(xy(rng), xy(rng));
  const KdTree2 tree(points);
  ASSERT_EQ(tree.size(), points.size());
  std::uniform_real_distribution<double> around(-2.5, 3.5);  // inside and just outside the cloud
  for (int t = 0; t < 150; ++t) check_query(tree, points, Vec2(around(rng), around(rng)));
  for (int t = 0; t < 20; ++t) check_query(tree, points, points[static_cast<size_t>(t) * 487]);  // at a point
}

TEST(KdTree2, MatchesBruteForceOnALatticeFullOfTies) {
  // Integer lattice 0..39 x 0..29, in a shuffled order so that index order differs from the
  // tree's spatial order. Squared distances from lattice points and cell centres are exact, and
  // 4 or 8 points share most of them.
  std::vector<Vec2> points;
  for (int j = 0; j < 30; ++j)
    for (int i = 0; i < 40; ++i) points.emplace_back(double(i), double(j));
  std::mt19937 rng(7);
  std::shuffle(points.begin(), points.end(), rng);
  const KdTree2 tree(points);
  for (const Vec2& q : {Vec2(0, 0), Vec2(39, 29), Vec2(20, 15), Vec2(5, 0), Vec2(0, 17), Vec2(13, 22)}) {
    check_query(tree, points, q);
    check_query(tree, points, q + Vec2(0.5, 0.5));
    check_query(tree, points, q - Vec2(0.5, 0.5));
  }
  check_query(tree, points, Vec2(-3, -3));     // outside, beyond a corner
  check_query(tree, points, Vec2(19.5, -2));   // outside, equidistant from two columns
}

TEST(KdTree2, FindsAllPointsWhenKIsTheirNumber) {
  const std::vector<Vec2> points = {{0, 0}, {1, 0}, {0, 1}, {1, 1}, {0.5, 0.5}};
  const KdTree2 tree(points);
  unsigned indices[5];
  double d2[5];
  ASSERT_EQ(tree.nearest(Vec2(0.5, 0.5), 5, indices, d2), 5u);
  // The centre, then the four corners at 0.5 m^2, by index.
  const unsigned expected[5] = {4, 0, 1, 2, 3};
  for (int j = 0; j < 5; ++j) {
    EXPECT_EQ(indices[j], expected[j]);
    EXPECT_EQ(d2[j], j == 0 ? 0.0 : 0.5);
  }
}

}  // namespace kdtree_test
}  // namespace radrecon
