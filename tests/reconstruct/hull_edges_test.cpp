// Queries on the hull, as users compute them: p0 + t (p1 - p0) on a hull edge lands within
// rounding of it, inside or outside. Every triangulation method must give the value on the edge
// there: a linear function exactly (up to rounding), never NaN with outside=none, never another
// sample's value (scipy's most reported griddata bug). Random and sliver configurations; the
// hull found here by brute force.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include "reconstruct/methods.h"

namespace radrecon {
namespace hull_edges_test {

double f(const Vec2& p) { return 2 + 3 * p.x() - 5 * p.y(); }

/// The hull's edges by brute force: (i, j) with every other point strictly to the left.
std::vector<std::pair<size_t, size_t>> hull_edges(const std::vector<Vec2>& p) {
  std::vector<std::pair<size_t, size_t>> out;
  for (size_t i = 0; i < p.size(); ++i)
    for (size_t j = 0; j < p.size(); ++j) {
      if (i == j) continue;
      bool all_left = true;
      for (size_t k = 0; k < p.size() && all_left; ++k) {
        if (k == i || k == j) continue;
        const Vec2 a = p[j] - p[i], b = p[k] - p[i];
        all_left = a.x() * b.y() - a.y() * b.x() > 0;
      }
      if (all_left) out.emplace_back(i, j);
    }
  return out;
}

/// Every triangulation method, each on the hull the same way.
constexpr std::array<Method, 5> kTriangulationMethods = {Method::natural_neighbour, Method::sibson_c1, Method::laplace,
                                                         Method::linear, Method::clough_tocher};

/// The method's values at q with outside=none; NaN everywhere (and a failure) if it cannot be made.
std::vector<double> values_with_no_outside(Method m, const ScatteredSamples& s, const std::vector<Vec2>& q) {
  MethodParams params;
  params.outside = OutsideHull::none;
  const InterpolantResult interpolant = make_scattered_interpolant(m, s, params);
  std::vector<double> v(q.size(), std::numeric_limits<double>::quiet_NaN());
  if (!interpolant) {
    ADD_FAILURE() << method_name(m) << ": " << interpolant.reason();
    return v;
  }
  interpolant.value()->evaluate(q, v);
  return v;
}

TEST(HullEdges, EveryTriangulationMethodReproducesALinearFunctionOnEveryHullEdge) {
  std::mt19937 rng(2026);
  std::uniform_real_distribution<double> u(0, 1);
  int queries = 0;
  for (int trial = 0; trial < 16; ++trial) {
    // Even trials random; odd trials slivers: most points within 1e-3 of a line, so that the
    // hull has long thin triangles; every fourth far from the origin (UTM-like offsets).
    const Vec2 offset = trial % 4 == 3 ? Vec2(500000, 5400000) : Vec2(0, 0);
    ScatteredSamples s;
    for (int k = 0; k < 14; ++k) {
      const double x = u(rng);
      const double y = trial % 2 ? 0.3 * x + 1e-3 * u(rng) + (k < 3 ? u(rng) : 0) : u(rng);
      s.points.push_back(offset + Vec2(x, y));
      s.values.push_back(f(Vec2(x, y)));
    }
    s.channels = 1;
    const std::vector<std::pair<size_t, size_t>> edges = hull_edges(s.points);
    ASSERT_GE(edges.size(), 3u);
    std::vector<Vec2> q;
    for (const auto& [i, j] : edges)
      for (int k = 1; k < 16; ++k) q.push_back(s.points[i] + (k / 16.0) * (s.points[j] - s.points[i]));
    for (const Method m : kTriangulationMethods) {
      const std::vector<double> v = values_with_no_outside(m, s, q);
      for (size_t k = 0; k < q.size(); ++k) {
        const double expected = f(q[k] - offset);
        // Far from the origin the coordinates carry ~1e-9 m of rounding (5.4e6 m x 2^-52), which
        // clough-tocher's fitted gradients amplify: 1e-6 there still tells a wrong value (the
        // bug gave errors of order 1) from rounding.
        const double tolerance = offset.norm() > 0 ? 1e-6 : 1e-11;
        ASSERT_FALSE(std::isnan(v[k])) << method_name(m) << " trial " << trial << ": no value on the hull";
        ASSERT_NEAR(v[k], expected, tolerance) << method_name(m) << " trial " << trial << " at " << q[k].transpose();
      }
      queries += static_cast<int>(q.size());
    }
  }
  EXPECT_GT(queries, 3000);
}

TEST(HullEdges, APointJustOutsideALatticesSideGetsTheSameValueInABatchAsAlone) {
  // An 11 x 11 lattice: each side of its hull is ten collinear hull edges, and CGAL's walk to a
  // point just outside one may end at any of them (it depends on where the walk began, here the
  // query before). The value must be the edge's, alone or after any other query (an outside-in
  // trial: NaN after (0, 9.95), 2.5 alone, for every triangulation method).
  ScatteredSamples s;
  for (int j = 0; j <= 10; ++j)
    for (int i = 0; i <= 10; ++i) s.points.emplace_back(i, j), s.values.push_back(f(Vec2(i, j)));
  s.channels = 1;
  const double above = std::nextafter(10.0, 11.0), beyond = std::nextafter(10.0, 11.0);
  const std::vector<Vec2> outside = {{2.5, above}, {7.25, above}, {beyond, 3.5}, {0.5, -1e-15}, {-1e-15, 8.75}};
  const std::vector<Vec2> before = {{0, 9.95}, {9.95, 0.2}, {5, 5}, {0.01, 0.01}, {9.99, 9.99}};
  for (const Method m : kTriangulationMethods)
    for (const Vec2& q : outside) {
      const double alone = values_with_no_outside(m, s, {q})[0];
      ASSERT_NEAR(alone, f(q), 1e-9) << method_name(m) << " at " << q.transpose();
      for (const Vec2& b : before)
        EXPECT_EQ(values_with_no_outside(m, s, {b, q})[1], alone)
            << method_name(m) << " at " << q.transpose() << " after " << b.transpose();
    }
}

TEST(HullEdges, APointOutsideGetsTheValueAtTheNearestPointOfAHullOfManyEdges) {
  // 150 samples on a circle (every one a hull vertex) and 100 inside: the nearest point of the
  // hull is found by walking along it from where CGAL's walk left it (a scan of the whole hull
  // took 422 s for a raster around 100,000 such samples). Against brute force: the nearest point
  // over every hull edge, where a linear function's value is known.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  ScatteredSamples s;
  for (int k = 0; k < 150; ++k) {
    const double a = 2 * std::numbers::pi * (k + 0.3 * u(rng)) / 150;
    s.points.emplace_back(std::cos(a), std::sin(a));
  }
  for (int k = 0; k < 100; ++k) {
    const double a = 2 * std::numbers::pi * u(rng), r = 0.95 * std::sqrt(u(rng));
    s.points.emplace_back(r * std::cos(a), r * std::sin(a));
  }
  for (const Vec2& p : s.points) s.values.push_back(f(p));
  s.channels = 1;
  const std::vector<std::pair<size_t, size_t>> edges = hull_edges(s.points);
  ASSERT_EQ(edges.size(), 150u);
  std::vector<Vec2> q;
  std::vector<double> expected;
  while (q.size() < 400) {
    const Vec2 p(-3 + 6 * u(rng), -3 + 6 * u(rng));
    if (p.norm() < 1.05) continue;
    double best = INFINITY;
    Vec2 nearest;
    for (const auto& [i, j] : edges) {
      const Vec2 a = s.points[i], b = s.points[j];
      const double t = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
      if ((a + t * (b - a) - p).norm() < best) best = (a + t * (b - a) - p).norm(), nearest = a + t * (b - a);
    }
    q.push_back(p);
    expected.push_back(f(nearest));
  }
  for (const Method m : kTriangulationMethods) {
    const InterpolantResult interpolant = make_scattered_interpolant(m, s, MethodParams{});
    ASSERT_TRUE(interpolant) << interpolant.reason();
    std::vector<double> v(q.size());
    interpolant.value()->evaluate(q, v);
    for (size_t k = 0; k < q.size(); ++k)
      ASSERT_NEAR(v[k], expected[k], 1e-9) << method_name(m) << " at " << q[k].transpose();
  }
}

TEST(HullEdges, ALineThroughASliverFaceOfThreeSamplesCollinearToRounding) {
  // Three samples collinear to 3e-17 (the middle one a rounding error off the line of the other
  // two) make a Delaunay face of that thickness. Points computed on the line between the outer
  // two land in it or beside it: each method gives the linear function's value there. The
  // inverse of the face's matrix cancelled catastrophically: linear and clough-tocher erred by
  // 0.02 (found by an outside-in trial; scipy's griddata is exact there).
  ScatteredSamples s;
  s.channels = 1;
  s.points = {Vec2(1, 0.2), Vec2(0.5, 0.55), Vec2(0.75, 0.575), Vec2(1, 0.6)};
  for (const Vec2& p : s.points) s.values.push_back(f(p));
  std::vector<Vec2> q;
  for (int k = 0; k <= 996; ++k) q.push_back(s.points[1] + (k / 996.0) * (s.points[3] - s.points[1]));
  for (const Method m : kTriangulationMethods) {
    const std::vector<double> v = values_with_no_outside(m, s, q);
    for (size_t k = 0; k < q.size(); ++k) {
      ASSERT_FALSE(std::isnan(v[k])) << method_name(m) << " at " << q[k].transpose();
      ASSERT_NEAR(v[k], f(q[k]), 1e-12) << method_name(m) << " at " << q[k].transpose();
    }
  }
}

/// Values along a row that are no linear function: the hull rule must take them sample by sample.
double g(const Vec2& p) { return 10 * (p.x() - 0.4) * (p.x() - 0.4); }

TEST(HullEdges, ARowOfSamplesOnTheHullUpToRoundingIsTakenSampleBySample) {
  // 23 samples meant to lie on one line (as a triangle's centroids along its hypotenuse), each
  // a rounding error inside or outside it, and samples inside. CGAL's exact predicates made one
  // hull edge from one end of the row to the other over those just inside, and the value at the
  // nearest point of the hull blended the row's two ends: an export's texels by the red wall's
  // hypotenuse erred by 32 of 255 levels (an outside-in trial). On the hull between two
  // neighbouring samples of the row, linear, natural-neighbour and laplace are linear between
  // the two (their coordinates on a hull edge), inside by rounding or outside.
  const Vec2 a(0.1, 0.7), b(0.83, 0.05);
  const int row = 23;
  ScatteredSamples s;
  s.channels = 1;
  for (int k = 0; k < row; ++k) s.points.push_back(a + (k / 22.0) * (b - a));
  for (const Vec2& p : s.points) s.values.push_back(g(p));
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) {
      const Vec2 p(0.02 + 0.1 * i, 0.02 + 0.1 * j);
      if ((p - a).x() * (b - a).y() - (p - a).y() * (b - a).x() < -0.01) s.points.push_back(p), s.values.push_back(f(p));
    }
  const Vec2 outward = Vec2((b - a).y(), -(b - a).x()).normalized();
  std::vector<Vec2> on, off;
  std::vector<double> expected;
  for (int k = 0; k + 1 < row; ++k)
    for (int j = 1; j < 100; ++j) {  // 99 points between each two, at fractions no power of two divides
      const double f = j / 100.0;
      const Vec2 p = s.points[k] + f * (s.points[k + 1] - s.points[k]);
      on.push_back(p);
      off.push_back(p + 1e-3 * outward);
      expected.push_back((1 - f) * s.values[k] + f * s.values[k + 1]);
    }
  for (const Method m : {Method::linear, Method::natural_neighbour, Method::laplace}) {
    const std::vector<double> v = values_with_no_outside(m, s, on);
    MethodParams nearest;
    nearest.outside = OutsideHull::nearest;
    const InterpolantResult beyond = make_scattered_interpolant(m, s, nearest);
    ASSERT_TRUE(beyond) << beyond.reason();
    std::vector<double> w(off.size());
    beyond.value()->evaluate(off, w);
    for (size_t k = 0; k < on.size(); ++k) {
      ASSERT_NEAR(v[k], expected[k], 1e-9) << method_name(m) << " on the row at " << on[k].transpose();
      ASSERT_NEAR(w[k], expected[k], 1e-9) << method_name(m) << " beyond the row at " << off[k].transpose();
    }
  }
}

TEST(HullEdges, APointOnAHullEdgeOverASampleJustInsideItGetsTheEdgesValue) {
  // A review's case: a sample 5e-9 inside the hull edge (0, 0)-(1, 0), far beyond rounding, so
  // the edge stays whole. Points on the edge get its linear value and never a conflict zone that
  // reaches the infinite vertex (which read an unset sample index: a crash, or another sample's
  // value); sibson-c1 gets a finite value. Points 1e-10 outside get the edge's value from linear
  // (its band there is the edge's), NaN or the edge's value from the others (outside=none).
  ScatteredSamples s;
  s.channels = 1;
  s.points = {{0, 0}, {1, 0}, {0.5, 5e-9}, {0, 1}, {1, 1}, {0.5, 0.6}};
  for (const Vec2& p : s.points) s.values.push_back(f(p));
  std::vector<Vec2> q;
  for (int k = 1; k < 100; ++k) q.emplace_back(k / 100.0, 0);
  for (const Method m : kTriangulationMethods) {
    const std::vector<double> v = values_with_no_outside(m, s, q);
    for (size_t k = 0; k < q.size(); ++k) {
      ASSERT_TRUE(std::isfinite(v[k])) << method_name(m) << " at " << q[k].transpose();
      if (m != Method::sibson_c1 && m != Method::clough_tocher)
        ASSERT_NEAR(v[k], f(q[k]), 1e-9) << method_name(m) << " at " << q[k].transpose();
    }
  }
}

TEST(HullEdges, AThinSetWhoseHullVerticesLieOnTheEdgesAcrossIsTriangulated) {
  // A fuzzer's input: ten samples of v = x on the line y = 2x, two of them a few ulps off it.
  // The hull is two long edges, each split at samples on the other side's hull within rounding:
  // a hull vertex also split the edge across, and an internal check that no sample ends more
  // than two hull edges failed (an abort). Each method builds and is near v = x on the line;
  // clough-tocher may refuse the set instead, naming why (its edges at a sample lie on one line to rounding).
  ScatteredSamples s;
  s.channels = 1;
  for (const auto& [x, y] : std::vector<std::pair<double, double>>{
           {0.0, 0.0}, {0.1111111111111111, 0.2222222222222222}, {0.2222222222222221, 0.4444444444444444},
           {0.3333333333333333, 0.6666666666666666}, {0.4444444444444444, 0.8888888888888888},
           {0.5555555555555556, 1.1111111111111112}, {0.6666666666666666, 1.3333333333333333},
           {0.7777777777777778, 1.5555555555511112}, {0.8888888888888888, 1.7777777777777777}, {1.0, 2.0}}) {
    s.points.emplace_back(x, y);
    s.values.push_back(x);
  }
  std::vector<Vec2> q;
  for (int k = 1; k < 20; ++k) q.emplace_back(k / 20.0, k / 10.0);
  for (const Method m : kTriangulationMethods) {
    MethodParams nearest;
    const InterpolantResult f = make_scattered_interpolant(m, s, nearest);
    if (m == Method::clough_tocher && !f) {
      EXPECT_NE(f.reason().find("lie on one line to rounding"), std::string::npos) << f.reason();
      continue;
    }
    ASSERT_TRUE(f) << method_name(m) << ": " << f.reason();
    std::vector<double> v(q.size());
    f.value()->evaluate(q, v);
    for (size_t k = 0; k < q.size(); ++k) EXPECT_NEAR(v[k], q[k].x(), 1e-3) << method_name(m) << " at " << q[k].transpose();
  }
}

TEST(HullEdges, OutsideTheHullEveryQueryTakesTheNearestHullPointWhateverTheQueriesBefore) {
  // A long, thin hull (the element centroids of a triangle sheared by 0.9999, rows collinear
  // along its base): the distance from a point outside it to its edges has two local minima,
  // and a walk along the hull from where the point was located stopped at the wrong one. The
  // second of the queries (0, 0), (1, 0) took 0.515 where the nearest hull point's x is 0.970,
  // and 0.970 when asked alone (an outside-in trial). The values are x, linear along every hull
  // edge: the nearest hull point's x, by brute force over every pair of samples with all the
  // others on or left of their line.
  constexpr int n = 11;
  constexpr double shear = 0.9999;
  ScatteredSamples s;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n - j; ++i) {
      for (const double k : {1.0 / 3, 2.0 / 3}) {
        if (k > 0.5 && i == n - j - 1) continue;
        const Vec2 uv((i + k) / n, (j + k) / n);
        s.points.emplace_back(uv.x() + shear * uv.y(), uv.y());
        s.values.push_back(s.points.back().x());
      }
    }
  const auto nearest_hull_x = [&](const Vec2& q) {
    double best = std::numeric_limits<double>::infinity(), x = 0;
    for (size_t i = 0; i < s.points.size(); ++i)
      for (size_t j = 0; j < s.points.size(); ++j) {
        if (i == j) continue;
        const Vec2 a = s.points[i], ab = s.points[j] - a;
        bool hull = true;
        for (size_t k = 0; k < s.points.size() && hull; ++k) hull = ab.x() * (s.points[k] - a).y() - ab.y() * (s.points[k] - a).x() >= 0;
        if (!hull) continue;
        const double t = std::clamp((q - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
        if (const double d = (a + t * ab - q).squaredNorm(); d < best) best = d, x = (a + t * ab).x();
      }
    return x;
  };
  std::mt19937 rng(20261208);
  std::uniform_real_distribution<double> ux(-0.5, 2.5), uy(-0.5, 1.5);
  std::vector<Vec2> q = {{0, 0}, {1, 0}};
  while (q.size() < 400) q.emplace_back(ux(rng), uy(rng));
  for (const Method m : kTriangulationMethods) {
    const InterpolantResult interpolant = make_scattered_interpolant(m, s, MethodParams{});
    ASSERT_TRUE(interpolant) << interpolant.reason();
    std::vector<double> v(q.size());
    interpolant.value()->evaluate(q, v);
    for (size_t k = 0; k < q.size(); ++k) {
      std::vector<double> alone(1);
      interpolant.value()->evaluate(std::span(&q[k], 1), alone);
      EXPECT_EQ(v[k], alone[0]) << method_name(m) << " at (" << q[k].transpose() << ")";
      // Inside the hull x itself (the methods reproduce linear functions); outside, the nearest
      // hull point's.
      if (std::abs(v[k] - q[k].x()) > 1e-9) EXPECT_NEAR(v[k], nearest_hull_x(q[k]), 1e-12) << method_name(m) << " at (" << q[k].transpose() << ")";
    }
  }
}

}  // namespace hull_edges_test
}  // namespace radrecon
