// Barriers: the exact blocking rule on its degenerate cases, the gridded search and distance_to()
// against the brute-force definitions (every segment tested) on random barriers, and Shepard with
// barriers against its defining properties (zero influence across, each side as if alone).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "reconstruct/barriers.h"
#include "reconstruct/nearest.h"
#include "reconstruct/sample_set.h"
#include "reconstruct/shepard.h"
#include "support/barrier_cases.h"

namespace radrecon {
namespace barriers_test {

using namespace testing_support;

TEST(SegmentBlocked, FollowsTheRuleOnItsDegenerateCases) {
  const BarrierSegment wall{{0, -1}, {0, 1}};  // x = 0, y in [-1, 1]
  EXPECT_TRUE(segment_blocked({-1, 0}, {1, 0}, wall));       // a proper crossing
  EXPECT_FALSE(segment_blocked({-1, 2}, {1, 2}, wall));      // around the free end
  EXPECT_TRUE(segment_blocked({-1, 0}, {1, 2}, wall));       // through the end point (0, 1)
  EXPECT_FALSE(segment_blocked({-1, 0.5}, {-0.5, 0}, wall)); // on one side
  EXPECT_FALSE(segment_blocked({0, 0.5}, {1, 0}, wall));     // a sample on the barrier sees both sides
  EXPECT_FALSE(segment_blocked({-1, 0}, {0, 0}, wall));      // a query on the barrier too
  EXPECT_FALSE(segment_blocked({0, 3}, {1, 3}, wall));       // p on the barrier's line, beyond its end
  EXPECT_TRUE(segment_blocked({0, -2}, {0, 2}, wall));       // along the barrier, overlapping
  EXPECT_TRUE(segment_blocked({0, 0.5}, {0, 2}, wall));      // along it from a point on it
  EXPECT_FALSE(segment_blocked({0, 1}, {0, 2}, wall));       // along its line, touching its end only
  EXPECT_FALSE(segment_blocked({0, 1.5}, {0, 2}, wall));     // along its line, beyond it
  // Symmetric in p and q, and in a and b.
  EXPECT_TRUE(segment_blocked({1, 2}, {-1, 0}, BarrierSegment{{0, 1}, {0, -1}}));
}

TEST(Barriers, RefusesMalformedPolylinesWithTheirPlace) {
  const std::vector<Polyline> one_point = {{{0, 0}}};
  EXPECT_NE(Barriers::from_polylines(one_point).reason().find("barrier 1"), std::string::npos);
  const std::vector<Polyline> repeated = {{{0, 0}, {1, 0}}, {{2, 2}, {3, 3}, {3, 3}}};
  const auto r = Barriers::from_polylines(repeated);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.reason().find("barrier 2, points 2 and 3"), std::string::npos) << r.reason();
  const std::vector<Polyline> nan = {{{0, 0}, {std::nan(""), 1}}};
  EXPECT_NE(Barriers::from_polylines(nan).reason().find("point 2"), std::string::npos);
  EXPECT_TRUE(Barriers().empty());
  EXPECT_FALSE(Barriers().blocks({0, 0}, {1, 1}));
}

TEST(Barriers, GridSearchAgreesWithBruteForceOnRandomBarriers) {
  std::mt19937 rng(2026);
  std::uniform_real_distribution<double> u(0, 10), step(-1.5, 1.5);
  for (int trial = 0; trial < 4; ++trial) {
    std::vector<Polyline> lines;
    const int count = trial == 0 ? 1 : 40 * trial;
    for (int k = 0; k < count; ++k) {
      Polyline line = {Vec2(u(rng), u(rng))};
      for (int i = 0; i < 3; ++i) line.push_back(line.back() + Vec2(step(rng), step(rng)));
      lines.push_back(line);
    }
    // Lattice points too: segments through barrier end points and along grid lines.
    lines.push_back({{2, 2}, {2, 8}});
    lines.push_back({{3, 5}, {7, 5}});
    const Barriers barriers = Barriers::from_polylines(lines).value();
    std::vector<Vec2> points;
    for (int k = 0; k < 150; ++k) points.emplace_back(u(rng), u(rng));
    for (int i = 0; i <= 10; ++i)
      for (int j = 0; j <= 10; j += 5) points.emplace_back(i, j);
    points.emplace_back(2, 8);  // a barrier's end point
    size_t blocked = 0;
    for (const Vec2& p : points)
      for (const Vec2& q : points) {
        bool brute = false;
        for (const BarrierSegment& s : barriers.segments()) brute = brute || segment_blocked(p, q, s);
        ASSERT_EQ(barriers.blocks(p, q), brute) << "(" << p.transpose() << ") - (" << q.transpose() << "), trial " << trial;
        blocked += brute;
      }
    EXPECT_GT(blocked, 0u);  // the test sees both outcomes
  }
}

/// The distance from q to the closed segment [a, b] by cases: to the nearer end point when q's
/// foot on the line falls outside the segment, else the perpendicular distance (the cross
/// product over the length). Another formula than the library's clamped projection.
double segment_distance_by_cases(const Vec2& q, const BarrierSegment& s) {
  const Vec2 d = s.b - s.a, r = q - s.a;
  if (r.dot(d) <= 0) return (q - s.a).norm();
  if ((q - s.b).dot(d) >= 0) return (q - s.b).norm();
  return std::abs(d.x() * r.y() - d.y() * r.x()) / d.norm();
}

TEST(Barriers, DistanceToAgreesWithBruteForceOnRandomBarriers) {
  std::mt19937 rng(2027);
  std::uniform_real_distribution<double> u(0, 10), step(-1.5, 1.5), around(-3, 13);
  const double kInf = std::numeric_limits<double>::infinity();
  const double limits[] = {0.0, 0.05, 0.3, 1.0, 3.0, 40.0, kInf};
  for (int trial = 0; trial < 5; ++trial) {
    // A single segment, then 4 polylines (tested one by one), then enough for the grid search.
    std::vector<Polyline> lines;
    const int count = trial == 0 ? 1 : (trial == 1 ? 2 : 40 * (trial - 1));
    for (int k = 0; k < count; ++k) {
      Polyline line = {Vec2(u(rng), u(rng))};
      for (int i = 0; i < 2; ++i) line.push_back(line.back() + Vec2(step(rng), step(rng)));
      lines.push_back(line);
    }
    if (trial >= 2) {  // long segments across many grid cells, one along a cell row
      lines.push_back({{-1, 3}, {11, 4}});
      lines.push_back({{5, 0}, {5, 10}});
    }
    const Barriers barriers = Barriers::from_polylines(lines).value();
    std::vector<Vec2> points;
    for (int k = 0; k < 400; ++k) points.emplace_back(around(rng), around(rng));
    for (const Polyline& line : lines) points.push_back(line[1]);  // on a barrier: distance 0
    int below = 0, capped = 0;
    for (const Vec2& q : points) {
      double brute = kInf;
      for (const BarrierSegment& s : barriers.segments()) brute = std::min(brute, segment_distance_by_cases(q, s));
      for (double limit : limits) {
        const double want = std::min(brute, limit), got = barriers.distance_to(q, limit);
        // Distances of order 10 from coordinates of order 10: round-off some 1e-15.
        ASSERT_NEAR(got, want, 1e-12) << "(" << q.transpose() << "), limit " << limit << ", trial " << trial;
        ASSERT_LE(got, limit);
        (brute < limit ? below : capped) += 1;
      }
    }
    EXPECT_GT(below, 100);
    EXPECT_GT(capped, 100);
  }
  EXPECT_EQ(Barriers().distance_to({1, 2}, 5.0), 5.0);
  EXPECT_EQ(Barriers().distance_to({1, 2}, kInf), kInf);
}

TEST(ShepardWithBarriers, ASampleAcrossABarrierHasExactlyZeroInfluence) {
  const std::vector<Vec2> q = left_queries();
  const Shepard a(two_sided_samples(1.0, 5.0), 4.0, 0, wall());
  const Shepard b(two_sided_samples(1.0, -300.0), 4.0, 0, wall());
  // Values so large that any weight left on a hidden sample would show.
  const Shepard c(two_sided_samples(1.0, 1e140), 4.0, 0, wall());
  // Values beyond the one-pass kernel's range: the path with weights relative to the nearest's.
  const Shepard d(two_sided_samples(1.0, 1e250), 4.0, 0, wall());
  const Shepard e(two_sided_samples(1.0, -1e250), 4.0, 0, wall());
  const std::vector<double> va = evaluate(a, q), vb = evaluate(b, q), vc = evaluate(c, q), vd = evaluate(d, q),
                            ve = evaluate(e, q);
  for (size_t k = 0; k < q.size(); ++k) {
    ASSERT_EQ(va[k], vb[k]) << "query " << k;
    ASSERT_EQ(va[k], vc[k]) << "query " << k;
    ASSERT_EQ(vd[k], ve[k]) << "query " << k;
    ASSERT_NEAR(va[k], vd[k], 1e-14 * std::abs(va[k])) << "query " << k;  // the two paths' rounding apart
  }
  // Without the wall the right side's values do leak in.
  const Shepard leaky(two_sided_samples(1.0, 5.0), 4.0, 0);
  EXPECT_GT(evaluate(leaky, q)[q.size() / 2], evaluate(a, q)[q.size() / 2] + 1e-6);
}

TEST(ShepardWithBarriers, EachSideIsReconstructedAsIfTheOtherDidNotExist) {
  const ScatteredSamples all = two_sided_samples(1.0, 5.0);
  ScatteredSamples left;
  for (size_t k = 0; k < all.points.size(); ++k)
    if (all.points[k].x() < 0.5) {
      left.points.push_back(all.points[k]);
      left.values.push_back(all.values[k]);
    }
  const std::vector<Vec2> q = left_queries();
  const std::vector<double> walled = evaluate(Shepard(all, 2.0, 0, wall()), q);
  const std::vector<double> alone = evaluate(Shepard(left, 2.0, 0), q);
  // The same weights summed in another order (hidden samples contribute exact zeros).
  for (size_t k = 0; k < q.size(); ++k) ASSERT_NEAR(walled[k], alone[k], 1e-14 * std::abs(alone[k])) << "query " << k;
}

// The global method with barriers (the vector path: hidden samples' weights masked to 0) against
// the formula in long double over the brute-force visible set, mu 2 and 4, three channels,
// queries on both sides of the wall and around its free end and the corner.
TEST(ShepardWithBarriers, GlobalIsTheFormulaOverTheVisibleSamples) {
  ScatteredSamples s = two_sided_samples(1.0, 5.0);
  s.channels = 3;
  std::vector<double> values;
  for (size_t k = 0; k < s.points.size(); ++k)
    for (int c = 0; c < 3; ++c) values.push_back(s.values[k] * (c + 1) - c);
  s.values = values;
  const Barriers barriers = wall_and_corner();
  for (const double mu : {2.0, 4.0}) {
    const Shepard f(s, mu, 0, barriers);
    size_t hidden_some = 0;
    for (const Vec2& q : random_queries(31, 400)) {
      const auto visible = visible_by_distance(s, barriers, q);
      hidden_some += visible.size() < s.points.size();
      ASSERT_FALSE(visible.empty());
      const long double nearest = std::sqrt(static_cast<long double>(visible.front().first));
      long double den = 0, num[3] = {0, 0, 0};
      for (const auto& [d2, j] : visible) {
        const long double w = std::pow(nearest / std::sqrt(static_cast<long double>(d2)), static_cast<long double>(mu));
        den += w;
        for (int c = 0; c < 3; ++c) num[c] += w * s.values[j * 3 + static_cast<size_t>(c)];
      }
      const std::vector<double> got = evaluate(f, {q});
      for (int c = 0; c < 3; ++c)
        ASSERT_NEAR(got[static_cast<size_t>(c)], static_cast<double>(num[c] / den), 1e-13 * (1 + std::abs(got[static_cast<size_t>(c)])))
            << "mu " << mu << " at " << q.transpose() << " channel " << c;
    }
    EXPECT_GT(hidden_some, 100u);
  }
}

TEST(ShepardWithBarriers, AQueryThatSeesNoSampleHasNoValue) {
  // Samples inside a closed square of barriers, a query outside it.
  ScatteredSamples s;
  s.channels = 1;
  s.points = {{0.4, 0.4}, {0.6, 0.5}, {0.5, 0.6}};
  s.values = {1, 2, 3};
  const Barriers box =
      Barriers::from_polylines(std::vector<Polyline>{{{0.2, 0.2}, {0.8, 0.2}, {0.8, 0.8}, {0.2, 0.8}, {0.2, 0.2}}}).value();
  const Shepard f(s, 4.0, 0, box);
  const std::vector<double> v = evaluate(f, {Vec2(0.9, 0.9), Vec2(0.5, 0.5), Vec2(0.6, 0.5)});
  EXPECT_TRUE(std::isnan(v[0]));
  EXPECT_GE(v[1], 1.0);
  EXPECT_LE(v[1], 3.0);
  EXPECT_EQ(v[2], 2.0);  // exact at a sample
}

TEST(Barriers, FarPointsAndGrazingLinesAgreeWithBruteForce) {
  // More than a handful of segments, so that the grid is used.
  std::vector<Polyline> lines;
  for (int k = 0; k < 10; ++k) lines.push_back({Vec2(0.1 * k, 0), Vec2(0.1 * k + 0.05, 1)});
  // One barrier starting 1e-13 from a grid cell's corner region.
  lines.push_back({{0.5 + 1e-13, 0.5 + 1e-13}, {0.6, 0.55}});
  const Barriers barriers = Barriers::from_polylines(lines).value();
  const auto brute = [&](const Vec2& p, const Vec2& q) {
    bool blocked = false;
    for (const BarrierSegment& s : barriers.segments()) blocked = blocked || segment_blocked(p, q, s);
    return blocked;
  };
  // Points far beyond the grid (cell indices beyond int range before clamping).
  for (const double x : {1e9, 1e15, 1e100, -1e100})
    for (const Vec2& q : {Vec2(0.5, 0.5), Vec2(0.02, 0.3)}) {
      const Vec2 p(x, 0.5);
      ASSERT_EQ(barriers.blocks(p, q), brute(p, q)) << x;
      ASSERT_EQ(barriers.blocks(q, p), brute(q, p)) << x;
    }
  // Long sight lines grazing the barrier's start, from far away, in both directions.
  std::mt19937 rng(77);
  std::uniform_real_distribution<double> angle(0, 6.283185307179586), tiny(-1e-12, 1e-12);
  for (int k = 0; k < 20000; ++k) {
    const double a = angle(rng), r = k % 2 ? 1e4 : 1e6;
    const Vec2 target(0.5 + tiny(rng), 0.5 + tiny(rng));
    const Vec2 far = target + r * Vec2(std::cos(a), std::sin(a));
    const Vec2 beyond = target - 0.01 * Vec2(std::cos(a), std::sin(a));
    ASSERT_EQ(barriers.blocks(far, beyond), brute(far, beyond)) << k;
    ASSERT_EQ(barriers.blocks(beyond, far), brute(beyond, far)) << k;
  }
}

TEST(PointVisibility, AgreesWithBlocksPointByPoint) {
  // Few segments (the sides path) and many (the grid path); lattice points on barrier lines and
  // through end points exercise the collinear cases.
  std::mt19937 rng(404);
  std::uniform_real_distribution<double> u(0, 10);
  for (const int count : {1, 3, 30, 100}) {
    std::vector<Polyline> lines = {{{2, 2}, {2, 8}}, {{3, 5}, {7, 5}}};
    for (int k = 0; k < count; ++k) lines.push_back({Vec2(u(rng), u(rng)), Vec2(u(rng), u(rng))});
    const Barriers barriers = Barriers::from_polylines(lines).value();
    std::vector<Vec2> points;
    for (int k = 0; k < 200; ++k) points.emplace_back(u(rng), u(rng));
    for (int i = 0; i <= 10; ++i)
      for (int j = 0; j <= 10; j += 5) points.emplace_back(i, j);
    const PointVisibility visibility(points, barriers);
    std::vector<unsigned> visible;
    std::vector<char> hidden;
    size_t seen = 0;
    for (const Vec2& q : points) {
      visibility.visible_from(q, visible, hidden);
      std::vector<unsigned> expected;
      for (size_t i = 0; i < points.size(); ++i)
        if (!barriers.blocks(q, points[i])) expected.push_back(static_cast<unsigned>(i));
      ASSERT_EQ(visible, expected) << "query " << q.transpose() << ", " << barriers.segments().size() << " segments";
      seen += visible.size();
    }
    EXPECT_LT(seen, points.size() * points.size());  // some hidden
  }
}

TEST(PointVisibility, RastersOfQueriesAgreeWithBlocksThroughTheCellsVerdicts) {
  // Rows of neighbouring queries reuse their cells' verdicts (PointVisibility::kVerdictCells):
  // a raster whose step is half a cell puts queries on the cells' edges and corners, on the
  // barriers' lines and on lines through a point and a barrier's end.
  std::mt19937 rng(405);
  std::uniform_real_distribution<double> u(0, 10);
  const std::vector<Polyline> lines = {{{2, 2}, {2, 8}}, {{3, 5}, {7, 5}}, {{6, 1}, {9, 4}}};
  const Barriers barriers = Barriers::from_polylines(lines).value();
  std::vector<Vec2> points = {{0, 0}, {10, 10}, {2, 1}, {2, 9}, {5, 5}, {8, 8}, {1, 5}};
  for (int k = 0; k < 150; ++k) points.emplace_back(u(rng), u(rng));
  const PointVisibility visibility(points, barriers);
  std::vector<char> hidden;
  constexpr int kSteps = 2 * PointVisibility::kVerdictCells;
  size_t hidden_count = 0;
  for (int j = 0; j <= kSteps; ++j)
    for (int i = 0; i <= kSteps; ++i) {
      const Vec2 q(10.0 * i / kSteps, 10.0 * j / kSteps);
      visibility.hidden_from(q, hidden);
      for (size_t p = 0; p < points.size(); ++p) {
        ASSERT_EQ(hidden[p] != 0, barriers.blocks(q, points[p])) << "query " << q.transpose() << ", point " << p;
        hidden_count += hidden[p] != 0;
      }
    }
  EXPECT_GT(hidden_count, 0u);
}

TEST(NearestSampleWithBarriers, IsTheNearestVisibleSampleByBruteForce) {
  const ScatteredSamples s = two_sided_samples(1.0, 5.0);
  const Barriers barriers = wall_and_corner();
  const NearestSample f(s, barriers);
  const std::vector<Vec2> q = random_queries(5, 500);
  const std::vector<double> got = evaluate(f, q);
  for (size_t k = 0; k < q.size(); ++k) {
    const auto visible = visible_by_distance(s, barriers, q[k]);
    ASSERT_FALSE(visible.empty());
    ASSERT_EQ(got[k], s.values[visible[0].second]) << "query " << k;
  }
}

TEST(ShepardWithBarriers, KNearestUsesTheKNearestVisibleSamplesAsTheFormulaSays) {
  const ScatteredSamples s = two_sided_samples(1.0, 5.0);
  const Barriers barriers = wall_and_corner();
  constexpr int k = 8;
  constexpr double mu = 2.5;  // the general pow() path
  const Shepard f(s, mu, k, barriers);
  const std::vector<Vec2> q = random_queries(9, 400);
  const std::vector<double> got = evaluate(f, q);
  for (size_t i = 0; i < q.size(); ++i) {
    // The first k visible by (distance, index): sum d^-mu B / sum d^-mu.
    auto visible = visible_by_distance(s, barriers, q[i]);
    visible.resize(std::min<size_t>(k, visible.size()));
    ASSERT_FALSE(visible.empty());
    double num = 0, den = 0;
    for (const auto& [d2, j] : visible) {
      const double w = std::pow(std::sqrt(d2), -mu);
      num += w * s.values[j];
      den += w;
    }
    ASSERT_NEAR(got[i], num / den, 1e-13 * std::abs(num / den)) << "query " << i;
  }
}


TEST(Barriers, SamplesToBeMergedThatABarrierPartsAreRefused) {
  // Samples within 1e-9 of the extent of each other are merged into their mean; on either side of
  // a wall that mean would lie on it and be seen from both sides, carrying each side's value across
  // (an outside-in trial: 0 and 100 beside x = 0.5 came out 19.9 and 74.4). Refused, naming both,
  // the samples untouched; merged as before where no barrier parts them.
  const Barriers wall = Barriers::from_polylines(std::vector<Polyline>{{{0.5, -1}, {0.5, 2}}}).value();
  const auto samples = [](std::vector<Vec2> extra) {
    ScatteredSamples s;
    s.channels = 1;
    s.points = {{0, 0}, {1, 0}, {0, 1}, {1, 1}};
    s.values = {0, 100, 0, 100};
    for (const Vec2& p : extra) s.points.push_back(p), s.values.push_back(p.x() < 0.5 ? 0 : 100);
    return s;
  };
  ScatteredSamples across = samples({{0.5 - 1e-10, 0.3}, {0.5 + 1e-10, 0.3}});
  const ScatteredSamples before = across;
  const Result<size_t> refused = merge_duplicate_points(across, wall);
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.reason().find("samples 5 and 6"), std::string::npos) << refused.reason();
  EXPECT_NE(refused.reason().find("either side of a barrier"), std::string::npos) << refused.reason();
  EXPECT_EQ(across.points, before.points);
  EXPECT_EQ(across.values, before.values);
  // A chain through a sample on the wall: neither pair that joins it crosses, its ends do, and
  // lie 1.2e-9 apart, beyond the merge distance (1e-9 of the extent 1): no pair of their own.
  ScatteredSamples chain = samples({{0.5 - 6e-10, 0.3}, {0.5, 0.3}, {0.5 + 6e-10, 0.3}});
  const Result<size_t> chained = merge_duplicate_points(chain, wall);
  ASSERT_FALSE(chained.ok());
  EXPECT_NE(chained.reason().find("samples 5 and 7"), std::string::npos) << chained.reason();
  // Without the wall, or on one side of it, merged.
  ScatteredSamples free = samples({{0.5 - 1e-10, 0.3}, {0.5 + 1e-10, 0.3}});
  EXPECT_EQ(merge_duplicate_points(free).value(), 1u);
  ScatteredSamples one_side = samples({{0.4, 0.3}, {0.4 + 2e-10, 0.3 + 1e-10}});
  EXPECT_EQ(merge_duplicate_points(one_side, wall).value(), 1u);
  EXPECT_EQ(one_side.points.size(), 5u);
}

}  // namespace barriers_test
}  // namespace radrecon

