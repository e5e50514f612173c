// KdTree2::nearest against brute force: for every k the k smallest squared distances exactly,
// every point strictly closer than the k-th found, ordered by (dist_sq, index); on random points
// and on an integer lattice, where equal distances are everywhere. CoherentNearest against the
// same brute force: exactly the k smallest by (dist_sq, index), ties at the k-th included.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <utility>
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

/// The integer lattice 0..39 x 0..29, in a shuffled order so that index order differs from any
/// spatial order. Squared distances from lattice points, cell centres and edge midpoints are
/// exact, and 4 or 8 points share most of them.
std::vector<Vec2> shuffled_lattice(unsigned seed) {
  std::vector<Vec2> points;
  for (int j = 0; j < 30; ++j)
    for (int i = 0; i < 40; ++i) points.emplace_back(double(i), double(j));
  std::mt19937 rng(seed);
  std::shuffle(points.begin(), points.end(), rng);
  return points;
}

TEST(KdTree2, MatchesBruteForceOnALatticeFullOfTies) {
  const std::vector<Vec2> points = shuffled_lattice(7);
  const KdTree2 tree(points);
  for (const Vec2& q : {Vec2(0, 0), Vec2(39, 29), Vec2(20, 15), Vec2(5, 0), Vec2(0, 17), Vec2(13, 22)}) {
    check_query(tree, points, q);
    check_query(tree, points, q + Vec2(0.5, 0.5));
    check_query(tree, points, q - Vec2(0.5, 0.5));
  }
  check_query(tree, points, Vec2(-3, -3));     // outside, beyond a corner
  check_query(tree, points, Vec2(19.5, -2));   // outside, equidistant from two columns
}

/// within(): exactly the points with dist_sq < radius_sq, by (dist_sq, index), against brute force.
void check_within(const KdTree2& tree, const std::vector<Vec2>& points, const Vec2& q, double radius_sq) {
  std::vector<std::pair<unsigned, double>> expected;
  for (size_t i = 0; i < points.size(); ++i)
    if (dist_sq(points[i], q) < radius_sq) expected.emplace_back(static_cast<unsigned>(i), dist_sq(points[i], q));
  std::sort(expected.begin(), expected.end(), [](const auto& a, const auto& b) {
    return a.second < b.second || (a.second == b.second && a.first < b.first);
  });
  std::vector<std::pair<unsigned, double>> found = {{7u, -1.0}};  // cleared by within()
  tree.within(q, radius_sq, found);
  EXPECT_EQ(found, expected) << "q = (" << q.x() << ", " << q.y() << "), radius_sq " << radius_sq;
}

TEST(KdTree2, WithinMatchesBruteForceOnRandomPointsAndOnALattice) {
  std::mt19937 rng(20261203);
  std::uniform_real_distribution<double> xy(-2, 3), radius(0, 0.4);
  std::vector<Vec2> points;
  for (int i = 0; i < 5000; ++i) points.emplace_back(xy(rng), xy(rng));
  const KdTree2 tree(points);
  for (int t = 0; t < 100; ++t) {
    const double r = radius(rng);
    check_within(tree, points, Vec2(xy(rng), xy(rng)), r * r);
  }
  check_within(tree, points, Vec2(0, 0), 0);    // nothing below 0
  check_within(tree, points, Vec2(0, 0), 100);  // everything
  // On the lattice squared distances are integers or quarters: a radius_sq equal to one of them
  // leaves those points out (strictly below), and many are tied.
  const std::vector<Vec2> lattice = shuffled_lattice(11);
  const KdTree2 lattice_tree(lattice);
  for (const Vec2& q : {Vec2(20, 15), Vec2(0, 0), Vec2(7.5, 3.5), Vec2(-1, 12)})
    for (const double r2 : {1.0, 2.0, 4.5, 25.0, 25.5})
      check_within(lattice_tree, lattice, q, r2);
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

/// Checks CoherentNearest on every query against brute force: the set of the k smallest
/// (dist_sq, index) pairs exactly, each distance its point's, the nearest flagged, every finite
/// query visited once and no other. Returns the number of queries visited.
size_t check_coherent(const std::vector<Vec2>& points, const std::vector<Vec2>& queries, int k) {
  const KdTree2 tree(points);
  const CoherentNearest nearest(tree, points, k);
  const CoherentNearest::Tiles tiles = nearest.tile(queries);
  CoherentNearest::Scratch scratch;
  std::vector<int> visits(queries.size(), 0);
  std::vector<unsigned> last_order;  // the order of a query's answer, to compare with the next's
  for (size_t t = 0; t < tiles.count(); ++t)
    nearest.visit_tile(tiles, queries, t, scratch,
                       [&](size_t q, std::span<const unsigned> idx, std::span<const double> d2, size_t at) {
                         ++visits[q];
                         std::vector<std::pair<double, unsigned>> brute(points.size());
                         for (size_t i = 0; i < points.size(); ++i)
                           brute[i] = {dist_sq(points[i], queries[q]), static_cast<unsigned>(i)};
                         std::sort(brute.begin(), brute.end());
                         brute.resize(static_cast<size_t>(k));
                         std::vector<std::pair<double, unsigned>> got;
                         for (size_t j = 0; j < idx.size(); ++j) {
                           ASSERT_LT(idx[j], points.size());
                           EXPECT_EQ(d2[j], dist_sq(points[idx[j]], queries[q]));
                           got.emplace_back(d2[j], idx[j]);
                         }
                         ASSERT_LT(at, got.size());
                         EXPECT_EQ(got[at], brute.front()) << "the nearest, query " << q;
                         std::sort(got.begin(), got.end());
                         EXPECT_EQ(got, brute) << "query " << q << " (" << queries[q].x() << ", " << queries[q].y() << ")";
                       });
  size_t visited = 0;
  for (size_t q = 0; q < queries.size(); ++q) {
    EXPECT_EQ(visits[q], queries[q].allFinite() ? 1 : 0) << "query " << q;
    visited += static_cast<size_t>(visits[q]);
  }
  return visited;
}

/// A raster's cell centres over [x0, x1] x [y0, y1], row by row.
std::vector<Vec2> raster(int w, int h, double x0, double y0, double x1, double y1) {
  std::vector<Vec2> out;
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) out.emplace_back(x0 + (i + 0.5) * (x1 - x0) / w, y0 + (j + 0.5) * (y1 - y0) / h);
  return out;
}

TEST(CoherentNearest, MatchesBruteForceOnARasterOverRandomPoints) {
  std::mt19937 rng(20261202);
  std::uniform_real_distribution<double> xy(0, 1);
  std::vector<Vec2> points;
  for (int i = 0; i < 3000; ++i) points.emplace_back(xy(rng), xy(rng));
  // The raster reaches beyond the points on every side, and a few queries are far away.
  std::vector<Vec2> queries = raster(70, 60, -0.2, -0.1, 1.1, 1.2);
  queries.emplace_back(40, -30);
  queries.emplace_back(0.5, 1e6);
  for (const int k : {1, 2, 7, 32, 100}) EXPECT_EQ(check_coherent(points, queries, k), queries.size()) << "k=" << k;
}

// Queries far from many points: their tiles' candidate discs cover more buckets than a tile
// gathers, so they search the tree, and their answers are put in the same order.
TEST(CoherentNearest, MatchesBruteForceWhereFarTilesSearchTheTree) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> xy(0, 1);
  std::vector<Vec2> points;
  for (int i = 0; i < 20000; ++i) points.emplace_back(xy(rng), xy(rng));
  std::vector<Vec2> queries = raster(4, 4, 0.2, 0.2, 0.8, 0.8);
  queries.emplace_back(1e6, 0), queries.emplace_back(-3e5, 4e5), queries.emplace_back(0.5, -2e6);
  for (const int k : {1, 4}) EXPECT_EQ(check_coherent(points, queries, k), queries.size()) << "k=" << k;
}

TEST(CoherentNearest, TiesAtTheKthGoToTheLowestIndicesOnALattice) {
  // A shuffled integer lattice, queried at lattice points, cell centres and edge midpoints:
  // most k-th distances are shared by 4 or 8 points.
  const std::vector<Vec2> points = shuffled_lattice(11);
  std::vector<Vec2> queries;
  for (int j = -2; j < 62; ++j)
    for (int i = -2; i < 82; ++i) queries.emplace_back(0.5 * i, 0.5 * j);
  for (const int k : {1, 4, 5, 9, 13, 32}) EXPECT_EQ(check_coherent(points, queries, k), queries.size()) << "k=" << k;
}

TEST(CoherentNearest, HandlesPointsOnALineAllPointsAndNonFiniteQueries) {
  std::vector<Vec2> line;
  for (int i = 0; i < 500; ++i) line.emplace_back(0.01 * i, 0.5 + 0.002 * i);  // no area at all
  std::vector<Vec2> queries = raster(40, 40, -1, -1, 6, 3);
  queries.emplace_back(std::numeric_limits<double>::quiet_NaN(), 0.3);
  queries.emplace_back(0.3, std::numeric_limits<double>::infinity());
  EXPECT_EQ(check_coherent(line, queries, 16), queries.size() - 2);
  // k = every point, and a single point.
  const std::vector<Vec2> few = {{0, 0}, {1, 0}, {0, 1}, {1, 1}, {0.5, 0.5}};
  EXPECT_EQ(check_coherent(few, raster(9, 9, -1, -1, 2, 2), 5), 81u);
  EXPECT_EQ(check_coherent({Vec2(0.25, 0.75)}, raster(5, 5, 0, 0, 1, 1), 1), 25u);
  // Queries spread over 1e150: still a few tiles, and the right answers.
  std::vector<Vec2> spread = raster(7, 7, 0, 0, 1, 1);
  spread.emplace_back(-1e150, 0), spread.emplace_back(1e150, 1e150);
  EXPECT_EQ(check_coherent(few, spread, 2), spread.size());
  {
    // Queries whose box has no finite extent (its width overflows): one tile.
    const KdTree2 tree(few);
    const CoherentNearest nearest(tree, few, 3);
    const std::vector<Vec2> wide = {Vec2(-1.7e308, 0), Vec2(1.7e308, 0), Vec2(0.5, 0.5)};
    const CoherentNearest::Tiles tiles = nearest.tile(wide);
    ASSERT_EQ(tiles.count(), 1u);
    EXPECT_EQ(tiles.first[1] - tiles.first[0], 3u);
  }
  // No finite query: no tile.
  const KdTree2 tree(few);
  const CoherentNearest nearest(tree, few, 3);
  EXPECT_EQ(nearest.tile(std::vector<Vec2>{Vec2(std::nan(""), 0)}).count(), 0u);
  EXPECT_EQ(nearest.tile(std::vector<Vec2>{}).count(), 0u);
}

}  // namespace kdtree_test
}  // namespace radrecon
