// Border samples against independent answers: a linear function reproduced by every added sample,
// the added points on the border or beside a barrier on the side the visibility test says,
// a step across a barrier kept exactly on each side, the counts of the documented spacing rule
// on grids of cell centres, and the refusals and degenerate cases.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>

#include "core/tolerances.h"
#include "reconstruct/border_samples.h"
#include "reconstruct/methods.h"

namespace radrecon {
namespace border_samples_test {

constexpr Rect kUnit{0, 0, 1, 1};

/// The samples added to `interior` (they follow it).
std::vector<Vec2> added_points(const ScatteredSamples& out, const ScatteredSamples& interior) {
  return {out.points.begin() + static_cast<std::ptrdiff_t>(interior.points.size()), out.points.end()};
}

/// Values (channels per point) of f at the points.
template <typename F>
ScatteredSamples sampled(const std::vector<Vec2>& points, int channels, F f) {
  ScatteredSamples s;
  s.channels = channels;
  s.points = points;
  for (const Vec2& p : points)
    for (int c = 0; c < channels; ++c) s.values.push_back(f(p, c));
  return s;
}

std::vector<Vec2> cell_centres(int nx, int ny, const Rect& r) {
  std::vector<Vec2> p;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      p.emplace_back(r.x0 + (i + 0.5) * (r.x1 - r.x0) / nx, r.y0 + (j + 0.5) * (r.y1 - r.y0) / ny);
  return p;
}

std::vector<Vec2> random_points(int n, const Rect& r, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Vec2> p;
  for (int k = 0; k < n; ++k) p.emplace_back(r.x0 + u(rng) * (r.x1 - r.x0), r.y0 + u(rng) * (r.y1 - r.y0));
  return p;
}

bool on_border(const Vec2& p, const Rect& r) {
  const bool in_x = p.x() >= r.x0 && p.x() <= r.x1, in_y = p.y() >= r.y0 && p.y() <= r.y1;
  return (in_y && (p.x() == r.x0 || p.x() == r.x1)) || (in_x && (p.y() == r.y0 || p.y() == r.y1));
}

double distance_to(const Vec2& p, const BarrierSegment& s) {
  const Vec2 d = s.b - s.a;
  const double t = std::clamp((p - s.a).dot(d) / d.squaredNorm(), 0.0, 1.0);
  return (s.a + t * d - p).norm();
}

/// +1 left of a -> b, -1 right (the sign of the cross product, in long double).
int side_of(const Vec2& p, const BarrierSegment& s) {
  const long double c = (static_cast<long double>(s.b.x()) - s.a.x()) * (static_cast<long double>(p.y()) - s.a.y()) -
                        (static_cast<long double>(s.b.y()) - s.a.y()) * (static_cast<long double>(p.x()) - s.a.x());
  return c > 0 ? 1 : (c < 0 ? -1 : 0);
}

Barriers make_barriers(const std::vector<Polyline>& lines) { return Barriers::from_polylines(lines).value(); }

/// An L-shaped wall foot with free ends inside the domain, and a wall crossing its right border.
const std::vector<Polyline> kWalls = {{{0.8, 0.2}, {0.8, 0.7}, {1.5, 0.7}}, {{1.7, -0.5}, {1.9, 1.5}}};
constexpr Rect kWide{0, 0, 2, 1};

double linear(const Vec2& p, int c) { return c == 0 ? 3 + 2 * p.x() - 5 * p.y() : -1 + 0.5 * p.x() + 4 * p.y(); }

TEST(BorderSamples, ADomainInsideTheSamplesPutsNoneAmongThemAndAWindowGetsTheWholesValues) {
  // interpolate's domain is the raster's; a window of the samples (a domain inside their extent)
  // put border samples among them, made-up values that moved the interpolant (an outside-in
  // trial: 0.054 on data of range 2). The border is now that of the rectangle holding the
  // domain and every sample: none inside the samples' extent, and the same samples, so the
  // same values, for a window as for the whole.
  const Rect whole{0, 0, 1, 1}, window{0.25, 0.25, 0.75, 0.75};
  const ScatteredSamples interior =
      sampled(random_points(300, whole, 11), 1, [](const Vec2& p, int) { return std::sin(6 * p.x()) * p.y() + p.x(); });
  Vec2 lo = interior.points[0], hi = lo;
  for (const Vec2& p : interior.points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const Rect extent{lo.x(), lo.y(), hi.x(), hi.y()};
  ScatteredSamples for_window = interior, for_whole = interior;
  MethodParams params_window, params_whole;
  ASSERT_GT(add_border_samples(Method::shepard, for_window, window, params_window).value(), 0u);
  ASSERT_GT(add_border_samples(Method::shepard, for_whole, extent, params_whole).value(), 0u);
  for (const Vec2& p : added_points(for_window, interior)) EXPECT_TRUE(on_border(p, extent)) << p.transpose();
  EXPECT_EQ(for_window.points, for_whole.points);
  EXPECT_EQ(for_window.values, for_whole.values);
}

TEST(BorderSamples, EveryAddedSampleReproducesALinearFunction) {
  const ScatteredSamples interior = sampled(random_points(400, kWide, 11), 2, linear);
  for (const bool walls : {false, true})
    for (const double spacing : {0.0, 0.1, 0.37}) {
      const Barriers barriers = walls ? make_barriers(kWalls) : Barriers();
      const auto r = with_border_samples(interior, kWide, barriers, {.spacing_m = spacing});
      ASSERT_TRUE(r.ok()) << r.reason();
      const ScatteredSamples& out = r.value();
      ASSERT_EQ(out.channels, 2);
      ASSERT_EQ(out.values.size(), out.points.size() * 2);
      // The interior first, unchanged.
      ASSERT_TRUE(std::equal(interior.points.begin(), interior.points.end(), out.points.begin()));
      ASSERT_TRUE(std::equal(interior.values.begin(), interior.values.end(), out.values.begin()));
      size_t beside_barrier = 0;
      for (size_t k = interior.points.size(); k < out.points.size(); ++k) {
        const Vec2& p = out.points[k];
        beside_barrier += !on_border(p, kWide);
        for (int c = 0; c < 2; ++c)
          ASSERT_NEAR(out.values[2 * k + c], linear(p, c), 1e-12 * 10)
              << "sample at (" << p.transpose() << "), channel " << c << ", spacing " << spacing << ", walls " << walls;
        // Each carries its plane's slope, the linear function's gradient.
        ASSERT_EQ(out.slopes.size(), out.values.size() * 2);
        const double gradient[2][2] = {{2, -5}, {0.5, 4}};
        for (int c = 0; c < 2; ++c)
          for (int d = 0; d < 2; ++d) ASSERT_NEAR(out.slopes[(2 * k + c) * 2 + d], gradient[c][d], 1e-9) << p.transpose();
      }
      for (size_t k = 0; k < interior.values.size() * 2; ++k) ASSERT_TRUE(std::isnan(out.slopes[k]));  // not known
      EXPECT_GE(out.points.size() - interior.points.size(), 18u);  // 2 x (6 + 3) at 0.37
      EXPECT_EQ(beside_barrier > 0, walls);
    }
}

TEST(BorderSamples, AddedPointsLieOnTheBorderOrBesideABarrierOnItsSide) {
  const ScatteredSamples interior = sampled(random_points(400, kWide, 12), 1, linear);
  const Barriers barriers = make_barriers(kWalls);
  const auto r = with_border_samples(interior, kWide, barriers, {.spacing_m = 0.1});
  ASSERT_TRUE(r.ok()) << r.reason();
  const double delta = border_offset_m(kWide);
  EXPECT_DOUBLE_EQ(delta, tol::kBorderOffsetRelative * 2);
  size_t border = 0;
  std::vector<int> per_side(2 * barriers.segments().size(), 0);
  for (const Vec2& p : added_points(r.value(), interior)) {
    // Inside the closed domain.
    ASSERT_TRUE(p.x() >= kWide.x0 && p.x() <= kWide.x1 && p.y() >= kWide.y0 && p.y() <= kWide.y1) << p.transpose();
    size_t nearest = 0;
    double nearest_d = std::numeric_limits<double>::infinity();
    for (size_t s = 0; s < barriers.segments().size(); ++s)
      if (distance_to(p, barriers.segments()[s]) < nearest_d) nearest_d = distance_to(p, barriers.segments()[s]), nearest = s;
    if (on_border(p, kWide)) {
      ++border;
      EXPECT_GT(nearest_d, delta) << "a border sample on a barrier at (" << p.transpose() << ")";
      continue;
    }
    // Beside a barrier: delta from it, and on the side that sees a point clearly on that side
    // (0.01 from the barrier, level with the sample) and not the point opposite it.
    const BarrierSegment& s = barriers.segments()[nearest];
    ASSERT_NEAR(nearest_d, delta, 1e-6 * delta) << p.transpose();
    const Vec2 along = (s.b - s.a).normalized(), left(-along.y(), along.x());
    const Vec2 foot = s.a + (p - s.a).dot(along) * along;
    const int side = side_of(p, s);
    ASSERT_NE(side, 0);
    EXPECT_FALSE(barriers.blocks(p, foot + side * 0.01 * left)) << p.transpose();
    EXPECT_TRUE(barriers.blocks(p, foot - side * 0.01 * left)) << p.transpose();
    ++per_side[2 * nearest + (side > 0)];
  }
  EXPECT_GT(border, 0u);
  // Both sides of every segment have samples; the crossing wall as many on each.
  for (int count : per_side) EXPECT_GT(count, 0);
  EXPECT_EQ(per_side[4], per_side[5]);
}

TEST(BorderSamples, ABarrierSampleTakesItsValuesFromItsOwnSideOnly) {
  // A step across a wall that cuts the unit square (and goes beyond it), two channels.
  const BarrierSegment wall{{0.3, -0.2}, {0.7, 1.2}};
  const Barriers barriers = make_barriers({{wall.a, wall.b}});
  std::vector<Vec2> points;
  for (const Vec2& p : random_points(600, kUnit, 13))
    if (distance_to(p, wall) > 1e-3) points.push_back(p);
  const auto step = [&](const Vec2& p, int c) { return side_of(p, wall) > 0 ? (c == 0 ? 1.0 : 10.0) : (c == 0 ? 5.0 : -3.0); };
  const ScatteredSamples interior = sampled(points, 2, step);
  for (const double spacing : {0.0, 0.05}) {
    const auto r = with_border_samples(interior, kUnit, barriers, {.spacing_m = spacing});
    ASSERT_TRUE(r.ok()) << r.reason();
    const ScatteredSamples& out = r.value();
    size_t beside = 0;
    for (size_t k = interior.points.size(); k < out.points.size(); ++k) {
      const Vec2& p = out.points[k];
      beside += distance_to(p, wall) < 2 * border_offset_m(kUnit);
      for (int c = 0; c < 2; ++c) ASSERT_EQ(out.values[2 * k + c], step(p, c)) << "at (" << p.transpose() << ")";
    }
    EXPECT_GT(beside, 10u);
    // Without the wall the values blend across it.
    const auto leaky = with_border_samples(interior, kUnit, Barriers(), {.spacing_m = spacing});
    size_t blended = 0;
    for (size_t k = interior.points.size(); k < leaky.value().points.size(); ++k)
      blended += leaky.value().values[2 * k] != step(leaky.value().points[k], 0);
    EXPECT_GT(blended, 0u);
  }
}

TEST(BorderSamples, SamplesAtASharpCornerTakeTheValueOfTheRegionTheyStandIn) {
  // A closed triangle of barriers with an 11-degree corner at (0.8, 0.5): 1 inside, 5 outside.
  const Vec2 t[3] = {{0.8, 0.5}, {0.1, 0.2}, {0.1, 0.35}};
  const Barriers barriers = make_barriers({{t[0], t[1], t[2], t[0]}});
  const auto in_triangle = [&](const Vec2& p) {
    const int s0 = side_of(p, {t[0], t[1]}), s1 = side_of(p, {t[1], t[2]}), s2 = side_of(p, {t[2], t[0]});
    return s0 == s1 && s1 == s2;
  };
  std::vector<Vec2> points;
  for (const Vec2& p : random_points(4000, kUnit, 15))
    if (distance_to(p, {t[0], t[1]}) > 1e-3 && distance_to(p, {t[1], t[2]}) > 1e-3 && distance_to(p, {t[2], t[0]}) > 1e-3)
      points.push_back(p);
  const ScatteredSamples interior = sampled(points, 1, [&](const Vec2& p, int) { return in_triangle(p) ? 1.0 : 5.0; });
  const auto r = with_border_samples(interior, kUnit, barriers, {.spacing_m = 0.02});
  ASSERT_TRUE(r.ok()) << r.reason();
  size_t inside = 0;
  for (size_t k = interior.points.size(); k < r.value().points.size(); ++k) {
    const Vec2& p = r.value().points[k];
    inside += in_triangle(p);
    ASSERT_EQ(r.value().values[k], in_triangle(p) ? 1.0 : 5.0) << "at (" << p.transpose() << ")";
  }
  EXPECT_GT(inside, 50u);
}

TEST(BorderSamples, CountsFollowTheSpacingRuleWithoutDuplicates) {
  const auto count = [](const ScatteredSamples& interior, const Rect& domain, double spacing, const Barriers& b = {}) {
    const auto r = with_border_samples(interior, domain, b, {.spacing_m = spacing});
    EXPECT_TRUE(r.ok()) << r.reason();
    return r.ok() ? r.value().points.size() - interior.points.size() : size_t{0};
  };
  const auto f = [](const Vec2& p, int) { return p.x() + p.y(); };
  // 4 x 4 cell centres: spacing 0.25 (the typical one) cuts each side into 4 parts.
  const ScatteredSamples grid = sampled(cell_centres(4, 4, kUnit), 1, f);
  const auto r = with_border_samples(grid, kUnit, Barriers());
  ASSERT_TRUE(r.ok());
  std::vector<Vec2> got = added_points(r.value(), grid), expected;
  for (int i = 0; i < 4; ++i) expected.push_back({0.25 * i, 0});
  for (int i = 0; i < 4; ++i) expected.push_back({1, 0.25 * i});
  for (int i = 0; i < 4; ++i) expected.push_back({1 - 0.25 * i, 1});
  for (int i = 0; i < 4; ++i) expected.push_back({0, 1 - 0.25 * i});
  EXPECT_EQ(got, expected);
  EXPECT_EQ(count(grid, kUnit, 0.3), 16u);  // ceil(1 / 0.3) = 4 parts a side
  EXPECT_EQ(count(grid, kUnit, 0.5), 8u);
  EXPECT_EQ(count(grid, kUnit, 5.0), 4u);  // the corners always
  EXPECT_EQ(count(grid, Rect{0, 0, 2, 1}, 0.25), 24u);
  // 10 x 10 centres 0.1 apart: their distance 0.09999999999999998 still gives 10 parts a side.
  EXPECT_EQ(count(sampled(cell_centres(10, 10, kUnit), 1, f), kUnit, 0), 40u);
  // Nodes of a 5 x 5 grid already stand at every border point: nothing is added.
  std::vector<Vec2> nodes;
  for (int j = 0; j <= 4; ++j)
    for (int i = 0; i <= 4; ++i) nodes.emplace_back(0.25 * i, 0.25 * j);
  EXPECT_EQ(count(sampled(nodes, 1, f), kUnit, 0), 0u);
  // A sample within delta of a corner replaces it; one 2 delta away does not.
  ScatteredSamples near = grid;
  near.points.push_back({0.5 * border_offset_m(kUnit), 0});
  near.values.push_back(0);
  EXPECT_EQ(count(near, kUnit, 0.25), 15u);
  near.points.back() = {2 * border_offset_m(kUnit), 0};
  EXPECT_EQ(count(near, kUnit, 0.25), 16u);
  // A wall at x = 0.5 across the square: the two border points on it go, and its 1 m inside the
  // square gets 5 positions (inset delta at both ends, 4 parts between) with a sample each side.
  const Barriers wall = make_barriers({{{0.5, -1}, {0.5, 2}}});
  const auto walled = with_border_samples(grid, kUnit, wall);
  ASSERT_TRUE(walled.ok());
  const std::vector<Vec2> w = added_points(walled.value(), grid);
  ASSERT_EQ(w.size(), 14u + 10u);
  const double delta = border_offset_m(kUnit);
  for (int i = 0; i < 5; ++i)
    for (int side = 0; side < 2; ++side) {
      const Vec2 p = w[14 + 2 * i + side];
      EXPECT_DOUBLE_EQ(p.x(), 0.5 + (side == 0 ? -delta : delta));  // a -> b upward: left is -x
      EXPECT_NEAR(p.y(), delta + i * (1 - 2 * delta) / 4, 1e-15);
    }
  // Two walls meeting at a right angle share the sample in their corner: it is added once.
  const Barriers corner = make_barriers({{{0.6, 0.2}, {0.6, 0.6}}, {{0.6, 0.6}, {0.2, 0.6}}});
  const auto cornered = with_border_samples(grid, kUnit, corner, {.spacing_m = 0.2});
  ASSERT_TRUE(cornered.ok());
  // Border 4 x 5; each wall 0.4 long: 3 positions x 2 sides; minus the shared one.
  EXPECT_EQ(cornered.value().points.size() - grid.points.size(), 20u + 12u - 1u);
  // No added sample within delta of another sample.
  for (const auto* s : {&r.value(), &walled.value(), &cornered.value()})
    for (size_t i = grid.points.size(); i < s->points.size(); ++i)
      for (size_t j = 0; j < i; ++j)
        ASSERT_GT((s->points[i] - s->points[j]).norm(), delta) << s->points[i].transpose();
}

TEST(BorderSamples, ADomainApartFromTheSamplesIsWarnedOfWithTheCountAdded) {
  // Samples in [0, 1]^2 and a 1 x 1 domain 500 away: the border goes around both, with a
  // warning that names both boxes and the count; a domain over the samples gets none.
  ScatteredSamples s;
  for (const Vec2& p : {Vec2(0, 0), Vec2(1, 0), Vec2(0, 1), Vec2(1, 1), Vec2(0.4, 0.6)}) {
    s.points.push_back(p);
    s.values.push_back(p.x() + 2 * p.y());
  }
  for (const auto& [domain, apart] : {std::pair{Rect{500, 500, 501, 501}, true}, std::pair{Rect{0.5, 0.5, 3, 3}, false}}) {
    ScatteredSamples bordered = s;
    MethodParams params;
    ::testing::internal::CaptureStderr();
    const Result<size_t> added = add_border_samples(Method::natural_neighbour, bordered, domain, params);
    const std::string warned = ::testing::internal::GetCapturedStderr();
    ASSERT_TRUE(added) << added.reason();
    EXPECT_EQ(bordered.points.size(), s.points.size() + added.value());
    if (!apart) {
      EXPECT_EQ(warned, "");
      continue;
    }
    EXPECT_NE(warned.find("the domain [500, 500, 501, 501] does not meet the samples' bounding box [0, 0, 1, 1]"),
              std::string::npos) << warned;
    EXPECT_NE(warned.find("(" + std::to_string(added.value()) + " added)"), std::string::npos) << warned;
  }
}

TEST(BorderSamples, RefusesWhatItCannotExtrapolateFrom) {
  const ScatteredSamples grid = sampled(cell_centres(4, 4, kUnit), 1, [](const Vec2& p, int) { return p.x(); });
  const auto refused = [](const ScatteredSamples& s, const Rect& d, BorderSampleSettings settings, const std::string& words) {
    const auto r = with_border_samples(s, d, Barriers(), settings);
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.reason().find(words), std::string::npos) << r.reason();
  };
  refused(ScatteredSamples{}, kUnit, {}, "no samples");
  ScatteredSamples nan_value = grid;
  nan_value.values[5] = std::nan("");
  refused(nan_value, kUnit, {}, "sample 6 has a value that is not a finite number");
  ScatteredSamples inf_value = grid;
  inf_value.values[0] = std::numeric_limits<double>::infinity();
  refused(inf_value, kUnit, {}, "sample 1 has a value");
  ScatteredSamples nan_point = grid;
  nan_point.points[2].y() = std::nan("");
  refused(nan_point, kUnit, {}, "sample 3: coordinates");
  refused(grid, Rect{0, 0, 0, 1}, {}, "has no area");
  refused(grid, Rect{0, 1, 1, 0}, {}, "has no area");
  refused(grid, Rect{0, 0, std::nan(""), 1}, {}, "finite");
  refused(grid, kUnit, {.spacing_m = -1}, "spacing");
  refused(grid, kUnit, {.spacing_m = std::nan("")}, "spacing");
  refused(grid, kUnit, {.fit_neighbours = 0}, "at least 1 neighbour");
  refused(grid, kUnit, {.spacing_m = 1e-8}, "would place");
}

TEST(BorderSamples, FewOrCollinearNeighboursGiveTheNearestValue) {
  // One sample: the corners only (no typical spacing), each with its value.
  const ScatteredSamples one = sampled({{0.3, 0.6}}, 2, [](const Vec2&, int c) { return 7.0 + c; });
  const auto r1 = with_border_samples(one, kUnit, Barriers());
  ASSERT_TRUE(r1.ok());
  ASSERT_EQ(r1.value().points.size(), 5u);
  for (size_t k = 1; k < 5; ++k) {
    EXPECT_EQ(r1.value().values[2 * k], 7.0);
    EXPECT_EQ(r1.value().values[2 * k + 1], 8.0);
    for (int d = 0; d < 4; ++d) EXPECT_EQ(r1.value().slopes[4 * k + d], 0.0);  // a constant's slope
  }
  // Three samples on a line (values linear along it): the nearest one's value, not a plane.
  const ScatteredSamples line = sampled({{0.2, 0.5}, {0.5, 0.5}, {0.8, 0.5}}, 1, [](const Vec2& p, int) { return 10 * p.x(); });
  const auto r3 = with_border_samples(line, kUnit, Barriers(), {.spacing_m = 0.5});
  ASSERT_TRUE(r3.ok());
  for (size_t k = 3; k < r3.value().points.size(); ++k) {
    const Vec2& p = r3.value().points[k];
    const double nearest = p.x() < 0.35 ? 2 : (p.x() < 0.65 ? 5 : 8);
    EXPECT_EQ(r3.value().values[k], nearest) << p.transpose();
  }
  // Two samples: fewer than 3, the nearest.
  const ScatteredSamples two = sampled({{0.25, 0.5}, {0.75, 0.5}}, 1, [](const Vec2& p, int) { return p.x(); });
  const auto r2 = with_border_samples(two, kUnit, Barriers(), {.spacing_m = 1});
  ASSERT_TRUE(r2.ok());
  ASSERT_EQ(r2.value().points.size(), 6u);
  EXPECT_EQ(r2.value().values[2], 0.25);  // (0, 0)
  EXPECT_EQ(r2.value().values[4], 0.75);  // (1, 1)
  // fit_neighbours = 1: always the nearest visible sample.
  const ScatteredSamples grid = sampled(cell_centres(4, 4, kUnit), 1, [](const Vec2& p, int) { return p.x() + 2 * p.y(); });
  const auto rn = with_border_samples(grid, kUnit, Barriers(), {.fit_neighbours = 1});
  ASSERT_TRUE(rn.ok());
  EXPECT_EQ(rn.value().values[16], 0.125 + 2 * 0.125);  // (0, 0): the centre (0.125, 0.125)
}

TEST(BorderSamples, APlaceTheBarriersCutOffFromEverySampleGetsNoSample) {
  // Samples on the left half only, a wall across the square at x = 0.5: nothing on the right.
  const ScatteredSamples left = sampled(cell_centres(2, 4, Rect{0, 0, 0.5, 1}), 1, [](const Vec2& p, int) { return p.y(); });
  const auto r = with_border_samples(left, kUnit, make_barriers({{{0.5, -1}, {0.5, 2}}}), {.spacing_m = 0.25});
  ASSERT_TRUE(r.ok());
  const std::vector<Vec2> added = added_points(r.value(), left);
  // Border: 16 points minus the 2 on the wall minus the 7 right of it; wall: 5 on its left.
  EXPECT_EQ(added.size(), 7u + 5u);
  for (const Vec2& p : added) EXPECT_LT(p.x(), 0.5) << p.transpose();
}

TEST(BorderSamples, AHundredThousandSamplesGetBorderSamplesOnTheirLinearFunction) {
  // At scale (its time is a benchmark's business, not a test's): every added sample on the
  // linear function the interior samples hold.
  const Rect domain{0, 0, 4, 4};
  const ScatteredSamples interior = sampled(random_points(100000, domain, 14), 3, [](const Vec2& p, int c) { return c + p.x() - 0.5 * p.y(); });
  const Barriers walls = make_barriers({{{2.6, 0.6}, {2.6, 2.6}}, {{0.6, 2.6}, {2.6, 2.6}}});
  const auto r = with_border_samples(interior, domain, walls);
  ASSERT_TRUE(r.ok());
  const ScatteredSamples& out = r.value();
  // About 4 sqrt(n) border samples and 2 x 4 sqrt(n) / 4 along the walls.
  EXPECT_GT(out.points.size() - interior.points.size(), 1500u);
  for (size_t k = interior.points.size(); k < out.points.size(); ++k)
    for (int c = 0; c < 3; ++c)
      ASSERT_NEAR(out.values[3 * k + c], c + out.points[k].x() - 0.5 * out.points[k].y(), 1e-11);
}

}  // namespace border_samples_test
}  // namespace radrecon
