// Piecewise linear interpolation on the Delaunay triangulation: its defining properties, and the
// value against a brute-force Delaunay triangulation (every triple whose circumcircle holds no
// other sample), independent of CGAL.

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <random>

#include "reconstruct/delaunay_linear.h"
#include "reconstruct/methods.h"
#include "support/scattered.h"

namespace radrecon {
namespace linear_test {

using testing::eval1;
using testing::random_samples;

/// Interpolating a linear function costs a few roundings of values O(1-10): barycentric
/// coordinates from a 2 x 2 inverse, then a three-term sum.
constexpr double kLinearRounding = 1e-12;

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

TEST(Linear, ExactAtTheSamples) {
  std::mt19937 rng(31);
  ScatteredSamples s = random_samples(60, rng);
  s.channels = 2;
  s.values.clear();
  std::uniform_real_distribution<double> value(-5, 5);
  for (size_t i = 0; i < 2 * s.points.size(); ++i) s.values.push_back(value(rng));
  const DelaunayLinear f(s, OutsideHull::nearest);
  std::vector<double> out(s.values.size());
  f.evaluate(s.points, out);
  for (size_t k = 0; k < out.size(); ++k) EXPECT_EQ(out[k], s.values[k]) << "value " << k;
}

TEST(Linear, ReproducesLinearFunctionsInsideTheHull) {
  std::mt19937 rng(32);
  ScatteredSamples s = random_samples(80, rng);
  auto g = [](const Vec2& p) { return 2 + 3 * p.x() - 1.5 * p.y(); };
  for (size_t i = 0; i < s.points.size(); ++i) s.values[i] = g(s.points[i]);
  const DelaunayLinear f(s, OutsideHull::none);
  std::uniform_real_distribution<double> inner(0.5, 3.5);
  for (int t = 0; t < 2000; ++t) {
    const Vec2 q(inner(rng), inner(rng));
    const double v = eval1(f, q);
    ASSERT_FALSE(std::isnan(v)) << q.transpose();
    EXPECT_NEAR(v, g(q), kLinearRounding * 10) << q.transpose();
  }
}

TEST(Linear, EqualsBarycentricInterpolationOnABruteForceDelaunayTriangulation) {
  std::mt19937 rng(33);
  const ScatteredSamples s = random_samples(25, rng);
  const size_t n = s.points.size();
  // Brute force: a triple is a Delaunay triangle iff no other sample lies inside its circumcircle
  // (random points: no four co-circular, the triangulation is unique).
  struct Tri {
    size_t a, b, c;
  };
  std::vector<Tri> tris;
  for (size_t a = 0; a < n; ++a)
    for (size_t b = a + 1; b < n; ++b)
      for (size_t c = b + 1; c < n; ++c) {
        const Vec2 &pa = s.points[a], &pb = s.points[b], &pc = s.points[c];
        const double d = 2 * cross(pb - pa, pc - pa);
        if (d == 0) continue;
        const Vec2 ab = pb - pa, ac = pc - pa;
        const Vec2 centre = pa + Vec2(ac.y() * ab.squaredNorm() - ab.y() * ac.squaredNorm(),
                                      ab.x() * ac.squaredNorm() - ac.x() * ab.squaredNorm()) / d;
        const double r2 = (centre - pa).squaredNorm();
        bool empty = true;
        for (size_t o = 0; o < n && empty; ++o)
          if (o != a && o != b && o != c && (s.points[o] - centre).squaredNorm() < r2) empty = false;
        if (empty) tris.push_back({a, b, c});
      }
  ASSERT_GE(tris.size(), n - 2);
  const DelaunayLinear f(s, OutsideHull::none);
  std::uniform_real_distribution<double> xy(0, 4);
  int inside = 0;
  for (int t = 0; t < 3000; ++t) {
    const Vec2 q(xy(rng), xy(rng));
    for (const Tri& tr : tris) {
      const Vec2 &pa = s.points[tr.a], &pb = s.points[tr.b], &pc = s.points[tr.c];
      const double area = cross(pb - pa, pc - pa);
      const double la = cross(pb - q, pc - q) / area, lb = cross(pc - q, pa - q) / area, lc = cross(pa - q, pb - q) / area;
      if (la < 0 || lb < 0 || lc < 0) continue;
      ++inside;
      EXPECT_NEAR(eval1(f, q), la * s.values[tr.a] + lb * s.values[tr.b] + lc * s.values[tr.c], kLinearRounding)
          << q.transpose();
      break;
    }
  }
  EXPECT_GT(inside, 1000);
}

TEST(Linear, OutsideTheHull) {
  // The unit square's corners and random points strictly inside: the hull is the square.
  std::mt19937 rng(34);
  ScatteredSamples s = random_samples(30, rng, 0.05, 0.95);
  const Vec2 corners[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const double corner_values[4] = {1, 2, -3, 0.5};
  for (int c = 0; c < 4; ++c) s.points.push_back(corners[c]), s.values.push_back(corner_values[c]);
  const DelaunayLinear nearest(s, OutsideHull::nearest), none(s, OutsideHull::none);
  // Beside the edge x = 1: the value at (1, y), linear between the corners (1, 0) and (1, 1).
  EXPECT_NEAR(eval1(nearest, Vec2(1.5, 0.3)), 0.7 * 2 + 0.3 * -3, kLinearRounding);
  EXPECT_EQ(eval1(nearest, Vec2(1.5, 0.3)), eval1(nearest, Vec2(1, 0.3)));  // the hull point itself
  // Beyond a corner: the corner's value.
  EXPECT_EQ(eval1(nearest, Vec2(1.5, 1.25)), -3);
  EXPECT_EQ(eval1(nearest, Vec2(-2, -0.5)), 1);
  EXPECT_TRUE(std::isnan(eval1(none, Vec2(1.5, 0.3))));
  EXPECT_TRUE(std::isnan(eval1(none, Vec2(-1e-7, 0.5))));  // outside the edge's rounding band
  // Outside by less than tol::kHullEdgeBandRelative of the edge: on it (a point computed on an
  // edge lands within rounding of it), the value on the edge.
  EXPECT_EQ(eval1(none, Vec2(-1e-12, 0.5)), eval1(nearest, Vec2(0, 0.5)));
  EXPECT_EQ(eval1(none, Vec2(1, 0.3)), eval1(nearest, Vec2(1, 0.3)));  // on the hull: a value
}

/// Equal bit for bit.
bool same(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }

TEST(Linear, AQueryOnAnEdgeDoesNotDependOnWhereTheWalkStarted) {
  // A lattice: every query at the midpoint of two neighbours lies on a Delaunay edge (or on the
  // diagonal of a co-circular square). Evaluated after a query on either side (the walk starts
  // near the batch's first query), the value must be the same to the bit.
  ScatteredSamples s;
  std::mt19937 rng(35);
  std::uniform_real_distribution<double> value(-1, 1);
  for (int j = 0; j < 7; ++j)
    for (int i = 0; i < 7; ++i) s.points.emplace_back(0.1 * i, 0.1 * j), s.values.push_back(value(rng));
  const DelaunayLinear f(s, OutsideHull::nearest);
  for (int j = 0; j < 6; ++j)
    for (int i = 0; i < 6; ++i) {
      const Vec2 p(0.1 * i, 0.1 * j);
      for (const Vec2& q : {Vec2(p + Vec2(0.05, 0)), Vec2(p + Vec2(0, 0.05)), Vec2(p + Vec2(0.05, 0.05))}) {
        double reference = eval1(f, q);
        for (const Vec2& from : {Vec2(q + Vec2(0.03, 0.01)), Vec2(q - Vec2(0.03, 0.01)), Vec2(q + Vec2(-0.01, 0.03)),
                                 Vec2(q + Vec2(0.01, -0.03))}) {
          const Vec2 batch[2] = {from, q};
          double out[2];
          f.evaluate(batch, out);
          EXPECT_TRUE(same(out[1], reference)) << q.transpose() << " after " << from.transpose();
        }
      }
    }
}

TEST(Linear, RefusesTooFewCollinearOrDuplicateSamples) {
  ScatteredSamples two;
  two.points = {{0, 0}, {1, 0}};
  two.values = {1, 2};
  const auto r2 = make_scattered_interpolant(Method::linear, two);
  ASSERT_FALSE(r2.ok());
  EXPECT_NE(r2.reason().find("at least 3 samples"), std::string::npos) << r2.reason();

  ScatteredSamples line;
  for (int i = 0; i < 5; ++i) line.points.emplace_back(i, 2 * i), line.values.push_back(i);
  const auto rl = make_scattered_interpolant(Method::linear, line);
  ASSERT_FALSE(rl.ok());
  EXPECT_NE(rl.reason().find("one line"), std::string::npos) << rl.reason();

  ScatteredSamples dup;
  dup.points = {{0, 0}, {1, 0}, {0, 1}, {1, 0}};
  dup.values = {1, 2, 3, 4};
  const auto rd = make_scattered_interpolant(Method::linear, dup);
  ASSERT_FALSE(rd.ok());
  EXPECT_NE(rd.reason().find("duplicate"), std::string::npos) << rd.reason();
}

TEST(Linear, ParametersAndBarriers) {
  EXPECT_EQ(parse_params(Method::linear, {"outside=none"}, "--param").outside, OutsideHull::none);
  EXPECT_ANY_THROW(parse_params(Method::linear, {"barrier-samples=on"}, "--param"));
  std::mt19937 rng(36);
  MethodParams p;
  p.barriers = Barriers::from_polylines(std::vector<Polyline>{{{0, 0}, {1, 1}}}).value();
  const auto r = make_scattered_interpolant(Method::linear, random_samples(10, rng), p);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.reason().find("does not take barriers"), std::string::npos) << r.reason();
}

}  // namespace linear_test
}  // namespace radrecon
