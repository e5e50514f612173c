// Natural neighbours and multiquadrics with barriers, against independent answers: the plain
// method built on the brute-force visible set alone (each query its own), exactly zero influence
// across a wall, linear functions reproduced on each side of it.

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "reconstruct/local_multiquadric.h"
#include "reconstruct/multiquadric.h"
#include "reconstruct/natural_neighbour.h"
#include "reconstruct/shepard.h"
#include "support/barrier_cases.h"

namespace radrecon {
namespace barrier_methods_test {

using namespace testing_support;

/// The samples of s with the given indices.
ScatteredSamples subset(const ScatteredSamples& s, const std::vector<std::pair<double, size_t>>& which) {
  ScatteredSamples out;
  out.channels = s.channels;
  for (const auto& [d2, j] : which) {
    out.points.push_back(s.points[j]);
    for (int c = 0; c < s.channels; ++c) out.values.push_back(s.values[j * s.channels + c]);
  }
  return out;
}

double at(const Interpolant& f, const Vec2& q) { return evaluate(f, {q})[0]; }

/// Queries over the unit square and a margin around it (outside the samples' hull).
std::vector<Vec2> queries_with_margin(unsigned seed, int count) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-0.1, 1.1);
  std::vector<Vec2> q;
  for (int i = 0; i < count; ++i) q.emplace_back(u(rng), u(rng));
  q.emplace_back(0.5, 0.69);  // just below the wall's free end
  q.emplace_back(0.5, 0.71);  // just above it
  return q;
}

TEST(NaturalNeighbourWithBarriers, IsSibsonOverTheVisibleSamplesAlone) {
  const ScatteredSamples s = two_sided_samples(1.0, 5.0);
  const Barriers barriers = wall_and_corner();
  const NaturalNeighbour f(s, OutsideHull::nearest, barriers);
  const std::vector<Vec2> q = queries_with_margin(3, 600);
  const std::vector<double> got = evaluate(f, q);
  size_t hidden_some = 0;
  for (size_t k = 0; k < q.size(); ++k) {
    const auto visible = visible_by_distance(s, barriers, q[k]);
    hidden_some += visible.size() < s.points.size();
    // Independent answer: Sibson over exactly the samples q sees, built for q alone (with the
    // same rule outside their hull).
    const NaturalNeighbour alone(subset(s, visible), OutsideHull::nearest);
    const double want = at(alone, q[k]);
    ASSERT_NEAR(got[k], want, 1e-12 * std::max(1.0, std::abs(want))) << "query " << k << " at " << q[k].transpose();
  }
  EXPECT_GT(hidden_some, q.size() / 4);  // the barriers matter for many queries
}

// Past kMaxWholeVisibleSamples a query's coordinates come from the triangulation of its k
// nearest visible samples, certified (natural_neighbour.h): the same independent answer, away
// from the wall (hard against it, without barrier samples, a query's cell among the samples it
// sees reaches past the kMaxVisibleNeighbours nearest: the header's documented limit).
TEST(NaturalNeighbourWithBarriers, ManySamplesTakeTheirNearestVisibleAndAreSibsonOverTheVisible) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0, 1);
  ScatteredSamples s;
  const size_t n = NaturalNeighbour::kMaxWholeVisibleSamples + 300;
  while (s.points.size() < n) {
    const Vec2 p(u(rng), u(rng));
    if (std::abs(p.x() - 0.5) < 1e-4) continue;
    s.points.push_back(p);
    s.values.push_back(std::sin(5 * p.x()) + p.y());
  }
  const Barriers barriers = wall_and_corner();
  const NaturalNeighbour f(s, OutsideHull::nearest, barriers);
  std::vector<Vec2> q;
  for (const Vec2& p : queries_with_margin(9, 200))
    if (std::abs(p.x() - 0.5) > 0.03) q.push_back(p);
  const std::vector<double> got = evaluate(f, q);
  for (size_t k = 0; k < q.size(); ++k) {
    const NaturalNeighbour alone(subset(s, visible_by_distance(s, barriers, q[k])), OutsideHull::nearest);
    const double want = at(alone, q[k]);
    ASSERT_NEAR(got[k], want, 1e-12 * std::max(1.0, std::abs(want))) << "query " << k << " at " << q[k].transpose();
  }
}

// A lattice (the paper's grid data: co-circular samples everywhere) with barriers, on a raster:
// each query the coordinates over exactly the samples it sees, and the same bits whether the
// raster comes at once (neighbours sharing their visible sets' triangulations and their walks)
// or one point at a time.
TEST(NaturalNeighbourWithBarriers, OnALatticeARasterGivesSibsonOverTheVisibleAndEachPointsOwnBits) {
  ScatteredSamples s;
  for (int j = 0; j < 16; ++j)
    for (int i = 0; i < 16; ++i) {
      const Vec2 p((i + 0.5) / 16, (j + 0.5) / 16);
      s.points.push_back(p);
      s.values.push_back(p.x() < 0.5 ? 2 + p.y() : -1 + 3 * p.x() * p.y());
    }
  const Barriers barriers = wall_and_corner();
  for (const NeighbourRule rule : {NeighbourRule::sibson, NeighbourRule::laplace}) {
    const NaturalNeighbour f(s, OutsideHull::nearest, barriers, rule);
    std::vector<Vec2> q;
    for (int j = 0; j < 50; ++j)
      for (int i = 0; i < 50; ++i) q.emplace_back((i + 0.5) / 50, (j + 0.5) / 50);
    const std::vector<double> together = evaluate(f, q);
    size_t hidden_some = 0;
    for (size_t k = 0; k < q.size(); ++k) {
      ASSERT_EQ(together[k], at(f, q[k])) << "query " << k << " at " << q[k].transpose();
      const auto visible = visible_by_distance(s, barriers, q[k]);
      hidden_some += visible.size() < s.points.size();
      if (k % 7 != 0) continue;  // the independent answer for every 7th query
      const NaturalNeighbour alone(subset(s, visible), OutsideHull::nearest, Barriers{}, rule);
      const double want = at(alone, q[k]);
      ASSERT_NEAR(together[k], want, 1e-12 * std::max(1.0, std::abs(want))) << "query " << k << " at " << q[k].transpose();
    }
    EXPECT_GT(hidden_some, q.size() / 4);
  }
}

TEST(NaturalNeighbourWithBarriers, CoordinatesAreOverVisibleSamplesAndSumToOne) {
  const ScatteredSamples s = two_sided_samples(1.0, 5.0);
  const Barriers barriers = wall_and_corner();
  const NaturalNeighbour f(s, OutsideHull::none, barriers);
  for (const Vec2& q : random_queries(11, 300)) {
    const auto coords = f.coordinates(q);
    if (coords.empty()) continue;  // outside the hull of what q sees
    double sum = 0;
    Vec2 centroid = Vec2::Zero();
    for (const auto& [j, w] : coords) {
      ASSERT_FALSE(barriers.blocks(q, s.points[j])) << "a hidden sample has a coordinate";
      ASSERT_GT(w, 0);
      sum += w;
      centroid += w * s.points[j];
    }
    EXPECT_NEAR(sum, 1.0, 1e-12);
    EXPECT_NEAR((centroid - q).norm(), 0.0, 1e-12);  // Sibson's coordinates are linearly precise
  }
}

TEST(NaturalNeighbourWithBarriers, ASampleAcrossABarrierHasExactlyZeroInfluence) {
  const std::vector<Vec2> q = left_queries();
  const NaturalNeighbour a(two_sided_samples(1.0, 5.0), OutsideHull::nearest, wall());
  const NaturalNeighbour b(two_sided_samples(1.0, -300.0), OutsideHull::nearest, wall());
  const std::vector<double> va = evaluate(a, q), vb = evaluate(b, q);
  for (size_t k = 0; k < q.size(); ++k) ASSERT_EQ(va[k], vb[k]) << "query " << k;
}

TEST(NaturalNeighbourWithBarriers, ReproducesALinearFunctionOnEachSide) {
  // Two planes, one each side of a wall across the domain: each side exactly its own plane,
  // wherever the query is inside the hull of the samples it sees.
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> u(0, 1);
  ScatteredSamples s;
  const auto plane = [](const Vec2& p) { return p.x() < 0.5 ? 1 + 2 * p.x() - p.y() : -4 + 0.5 * p.x() + 3 * p.y(); };
  for (int k = 0; k < 300; ++k) {
    const Vec2 p(u(rng), u(rng));
    s.points.push_back(p);
    s.values.push_back(plane(p));
  }
  const NaturalNeighbour f(s, OutsideHull::none, wall());
  size_t inside = 0;
  for (const Vec2& q : random_queries(21, 500)) {
    const double v = at(f, q);
    if (std::isnan(v)) continue;
    ++inside;
    ASSERT_NEAR(v, plane(q), 1e-12) << q.transpose();
  }
  EXPECT_GT(inside, 400u);
}

TEST(MultiquadricWithBarriers, IsTheMultiquadricThroughTheVisibleSamples) {
  const ScatteredSamples s = two_sided_samples(1.0, 5.0);
  const Barriers barriers = wall_and_corner();
  constexpr double r = 0.1;  // a fixed radius: the same basis for the subset's own system
  const Multiquadric f(s, 0.5, r, barriers);
  const std::vector<Vec2> q = random_queries(4, 80);
  const std::vector<double> got = evaluate(f, q);
  for (size_t k = 0; k < q.size(); ++k) {
    const Multiquadric alone(subset(s, visible_by_distance(s, barriers, q[k])), 0.5, r);
    const double want = at(alone, q[k]);
    ASSERT_NEAR(got[k], want, 1e-9 * std::max(1.0, std::abs(want))) << "query " << k;
  }
}

TEST(MultiquadricWithBarriers, ASampleAcrossABarrierHasExactlyZeroInfluenceGlobalAndLocal) {
  const std::vector<Vec2> q = left_queries();
  for (const int k : {0, 12}) {
    const auto make = [&](double right) -> std::unique_ptr<Interpolant> {
      if (k == 0) return std::make_unique<Multiquadric>(two_sided_samples(1.0, right), 0.5, std::nullopt, wall());
      return std::make_unique<LocalMultiquadric>(two_sided_samples(1.0, right), 0.5, std::nullopt, k, wall());
    };
    const std::vector<double> va = evaluate(*make(5.0), q), vb = evaluate(*make(-300.0), q);
    for (size_t i = 0; i < q.size(); ++i) ASSERT_EQ(va[i], vb[i]) << "k = " << k << ", query " << i;
  }
}

TEST(MultiquadricWithBarriers, ExactAtTheSamples) {
  const ScatteredSamples s = two_sided_samples(1.0, 5.0);
  const Multiquadric global(s, 0.5, std::nullopt, wall_and_corner());
  const LocalMultiquadric local(s, 0.5, std::nullopt, 12, wall_and_corner());
  const std::vector<double> g = evaluate(global, s.points), l = evaluate(local, s.points);
  for (size_t i = 0; i < s.points.size(); ++i) {
    ASSERT_NEAR(g[i], s.values[i], 1e-8) << "sample " << i;
    ASSERT_NEAR(l[i], s.values[i], 1e-8) << "sample " << i;
  }
}

/// The samples left of the wall (x < 0.5).
ScatteredSamples left_side(const ScatteredSamples& all) {
  ScatteredSamples left;
  left.channels = all.channels;
  for (size_t k = 0; k < all.points.size(); ++k)
    if (all.points[k].x() < 0.5) {
      left.points.push_back(all.points[k]);
      left.values.push_back(all.values[k]);
    }
  return left;
}

TEST(BarrierMethods, EachSideOfAFullWallIsReconstructedAsIfTheOtherDidNotExist) {
  const ScatteredSamples all = two_sided_samples(1.0, 5.0);
  const ScatteredSamples left = left_side(all);
  const std::vector<Vec2> q = left_queries();
  const auto compare = [&](const Interpolant& walled, const Interpolant& alone, double tol, const char* name) {
    const std::vector<double> a = evaluate(walled, q), b = evaluate(alone, q);
    for (size_t k = 0; k < q.size(); ++k) ASSERT_NEAR(a[k], b[k], tol * std::max(1.0, std::abs(b[k]))) << name << ", query " << k;
  };
  compare(NaturalNeighbour(all, OutsideHull::nearest, wall()), NaturalNeighbour(left, OutsideHull::nearest), 1e-12,
          "natural-neighbour");
  compare(Multiquadric(all, 0.5, 0.1, wall()), Multiquadric(left, 0.5, 0.1), 1e-9, "multiquadric");
}

/// The largest difference between the values at consecutive points of n + 1 equally spaced
/// points from a to b.
double largest_step(const Interpolant& f, const Vec2& a, const Vec2& b, int n) {
  std::vector<Vec2> path;
  for (int i = 0; i <= n; ++i) path.push_back(a + (b - a) * (static_cast<double>(i) / n));
  const std::vector<double> v = evaluate(f, path);
  double step = 0;
  for (int i = 0; i < n; ++i) step = std::max(step, std::abs(v[i + 1] - v[i]));
  return step;
}

TEST(BarrierMethods, ContinuousOnEachSideAndJumpingAcrossTheWall) {
  // A wall across the whole domain (no free end inside it, so no sight line grazes an end):
  // along paths on one side, the largest step between neighbouring points shrinks with the
  // spacing (continuous); across the wall the values jump by about the step in the data.
  const ScatteredSamples s = two_sided_samples(1.0, 5.0);
  const std::vector<std::pair<std::string, std::unique_ptr<Interpolant>>> methods = [&] {
    std::vector<std::pair<std::string, std::unique_ptr<Interpolant>>> m;
    m.emplace_back("shepard", std::make_unique<Shepard>(s, 4.0, 0, wall()));
    m.emplace_back("natural-neighbour", std::make_unique<NaturalNeighbour>(s, OutsideHull::nearest, wall()));
    m.emplace_back("multiquadric", std::make_unique<Multiquadric>(s, 0.5, std::nullopt, wall()));
    m.emplace_back("local multiquadric", std::make_unique<LocalMultiquadric>(s, 0.5, std::nullopt, 12, wall()));
    return m;
  }();
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> u(0.02, 0.98), left(0.02, 0.48);
  for (const auto& [name, f] : methods) {
    for (int path = 0; path < 6; ++path) {
      const Vec2 a(left(rng), u(rng)), b(left(rng), u(rng));
      const double coarse = largest_step(*f, a, b, 1000), fine = largest_step(*f, a, b, 100000);
      EXPECT_LT(fine, coarse / 20 + 1e-12) << name << ": a jump on a path that crosses no barrier";
    }
    // Across the wall: a jump of about 4 (the data's step) between 0.5 - 1e-9 and 0.5 + 1e-9.
    const double jump = std::abs(evaluate(*f, {Vec2(0.5 + 1e-9, 0.5)})[0] - evaluate(*f, {Vec2(0.5 - 1e-9, 0.5)})[0]);
    EXPECT_GT(jump, 2.0) << name;
  }
}

}  // namespace barrier_methods_test
}  // namespace radrecon
