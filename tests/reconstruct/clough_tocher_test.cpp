// Clough-Tocher interpolation: its defining properties (exact at the samples, linear functions
// reproduced, quadratics reproduced given their gradients, C1 across the triangles' edges and
// across the split edges inside them), the gradients as the minimiser of the edge-curvature
// functional computed here from its definition, and the outside rule. scipy_agreement.py
// compares it with scipy's CloughTocher2DInterpolator.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "reconstruct/clough_tocher.h"
#include "reconstruct/delaunay_linear.h"
#include "reconstruct/methods.h"
#include "support/scattered.h"

namespace radrecon {
namespace clough_tocher_test {

using testing::eval1;
using testing::random_samples;

/// Random samples plus the corners of the square [0, 4]^2, so that the hull is the square.
ScatteredSamples covering_samples(int n, std::mt19937& rng) {
  ScatteredSamples s = random_samples(n, rng);
  for (const Vec2& c : {Vec2(0, 0), Vec2(4, 0), Vec2(4, 4), Vec2(0, 4)}) s.points.push_back(c), s.values.push_back(0);
  return s;
}

/// Reproducing a polynomial costs rounding only: the control net from the values and gradients
/// (a few operations each), then a ten-term Bernstein sum, on values O(10).
constexpr double kPolynomialRounding = 1e-11;

TEST(CloughTocher, ExactAtTheSamples) {
  std::mt19937 rng(41);
  ScatteredSamples s = random_samples(60, rng);
  s.channels = 2;
  s.values.clear();
  std::uniform_real_distribution<double> value(-5, 5);
  for (size_t i = 0; i < 2 * s.points.size(); ++i) s.values.push_back(value(rng));
  const CloughTocher f(s, OutsideHull::nearest);
  std::vector<double> out(s.values.size());
  f.evaluate(s.points, out);
  for (size_t k = 0; k < out.size(); ++k) EXPECT_EQ(out[k], s.values[k]) << "value " << k;
}

TEST(CloughTocher, ReproducesLinearFunctionsWithTheirGradientsPerChannel) {
  std::mt19937 rng(42);
  ScatteredSamples s = covering_samples(80, rng);
  s.channels = 2;
  s.values.clear();
  auto g0 = [](const Vec2& p) { return 2 + 3 * p.x() - 1.5 * p.y(); };
  auto g1 = [](const Vec2& p) { return -1 + 0.25 * p.x() + 4 * p.y(); };
  for (const Vec2& p : s.points) s.values.push_back(g0(p)), s.values.push_back(g1(p));
  const CloughTocher f(s, OutsideHull::none);
  // Nielson's functional is zero for the true gradients of a linear function: its minimiser.
  for (size_t i = 0; i < s.points.size(); ++i) {
    EXPECT_NEAR(f.gradients()[(i * 2 + 0) * 2 + 0], 3, kPolynomialRounding);
    EXPECT_NEAR(f.gradients()[(i * 2 + 0) * 2 + 1], -1.5, kPolynomialRounding);
    EXPECT_NEAR(f.gradients()[(i * 2 + 1) * 2 + 0], 0.25, kPolynomialRounding);
    EXPECT_NEAR(f.gradients()[(i * 2 + 1) * 2 + 1], 4, kPolynomialRounding);
  }
  std::uniform_real_distribution<double> inner(0.5, 3.5);
  for (int t = 0; t < 2000; ++t) {
    const Vec2 q(inner(rng), inner(rng));
    double out[2];
    f.evaluate(std::span(&q, 1), out);
    EXPECT_NEAR(out[0], g0(q), kPolynomialRounding) << q.transpose();
    EXPECT_NEAR(out[1], g1(q), kPolynomialRounding) << q.transpose();
  }
}

TEST(CloughTocher, ReproducesQuadraticsGivenTheirGradients) {
  std::mt19937 rng(43);
  ScatteredSamples s = covering_samples(70, rng);
  auto g = [](const Vec2& p) { return 1 + p.x() - 2 * p.y() + 0.5 * p.x() * p.x() - 0.75 * p.x() * p.y() + 0.3 * p.y() * p.y(); };
  std::vector<double> gradients;
  for (size_t i = 0; i < s.points.size(); ++i) {
    const Vec2& p = s.points[i];
    s.values[i] = g(p);
    gradients.push_back(1 + p.x() - 0.75 * p.y());
    gradients.push_back(-2 - 0.75 * p.x() + 0.6 * p.y());
  }
  const CloughTocher f(s, OutsideHull::none, gradients);
  std::uniform_real_distribution<double> inner(0.5, 3.5);
  for (int t = 0; t < 2000; ++t) {
    const Vec2 q(inner(rng), inner(rng));
    EXPECT_NEAR(eval1(f, q), g(q), kPolynomialRounding) << q.transpose();
  }
  // Not cubics: the reduced element's cross derivative is linear along each edge.
  for (size_t i = 0; i < s.points.size(); ++i) {
    const Vec2& p = s.points[i];
    s.values[i] = p.x() * p.x() * p.x();
    gradients[2 * i] = 3 * p.x() * p.x(), gradients[2 * i + 1] = 0;
  }
  const CloughTocher cubic(s, OutsideHull::none, gradients);
  double worst = 0;
  for (int t = 0; t < 2000; ++t) {
    const Vec2 q(inner(rng), inner(rng));
    worst = std::max(worst, std::abs(eval1(cubic, q) - q.x() * q.x() * q.x()));
  }
  EXPECT_GT(worst, 1e-6);
}

/// One-sided derivative of f at x in direction d (unit), from four points on that side: exact for
/// cubics, which is what f is on each sub-triangle.
double one_sided(const Interpolant& f, const Vec2& x, const Vec2& d, double h) {
  const Vec2 q[4] = {x, x + h * d, x + 2 * h * d, x + 3 * h * d};
  double v[4];
  f.evaluate(q, v);
  return (-11 * v[0] + 18 * v[1] - 9 * v[2] + 2 * v[3]) / (6 * h);
}

/// The largest jump, across the given segments, of the derivative normal to them: the two
/// one-sided derivatives at random points of each segment (away from its ends), relative to the
/// largest derivative seen. The step is 1e-5 of the segment's length: the four points stay inside
/// the sub-triangles next to it, and the difference's rounding (some 20 ulps of the values over
/// 6 steps) stays below 1e-9 of the derivative.
double normal_derivative_jump(const Interpolant& f, const std::vector<std::pair<Vec2, Vec2>>& segments, std::mt19937& rng) {
  std::uniform_real_distribution<double> along(0.2, 0.8);
  double jump = 0, scale = 0;
  for (const auto& [a, b] : segments)
    for (int t = 0; t < 4; ++t) {
      const Vec2 x = a + along(rng) * (b - a);
      const Vec2 n = Vec2(a.y() - b.y(), b.x() - a.x()).normalized();
      const double h = 1e-5 * (b - a).norm();
      const double plus = one_sided(f, x, n, h), minus = -one_sided(f, x, -n, h);
      jump = std::max(jump, std::abs(plus - minus));
      scale = std::max({scale, std::abs(plus), std::abs(minus)});
    }
  return jump / scale;
}

/// C1 holds to the finite differences' rounding: measured, the jumps are 4e-10 of the
/// derivatives across Delaunay edges and 1e-11 across split edges (rounding of values O(1) over
/// steps of 1e-5 x an edge, times the difference's coefficients); a C0 interpolant's are O(1).
constexpr double kC1JumpRelative = 1e-6;

TEST(CloughTocher, FirstDerivativesAreContinuousAcrossEdgesAndSplitEdges) {
  std::mt19937 rng(44);
  const ScatteredSamples s = random_samples(40, rng);
  const CloughTocher f(s, OutsideHull::none);
  const DelaunayMesh& mesh = f.mesh();
  std::vector<std::pair<Vec2, Vec2>> edges, splits;
  for (size_t face = 0; face < mesh.faces(); ++face) {
    const auto& v = mesh.face(face);
    const Vec2 centroid = (s.points[v[0]] + s.points[v[1]] + s.points[v[2]]) / 3;
    for (int k = 0; k < 3; ++k) {
      splits.emplace_back(s.points[v[k]], centroid);
      const std::int64_t nb = mesh.neighbour(face, k);
      if (nb > static_cast<std::int64_t>(face)) edges.emplace_back(s.points[v[(k + 1) % 3]], s.points[v[(k + 2) % 3]]);
    }
  }
  ASSERT_GT(edges.size(), 50u);
  const double edge_jump = normal_derivative_jump(f, edges, rng), split_jump = normal_derivative_jump(f, splits, rng);
  EXPECT_LT(edge_jump, kC1JumpRelative);
  EXPECT_LT(split_jump, kC1JumpRelative);
  std::cout << "largest relative jump of the normal derivative: " << edge_jump << " across Delaunay edges, "
            << split_jump << " across split edges\n";
  // The test sees a kink: linear interpolation's derivative jumps across the Delaunay edges.
  const DelaunayLinear linear(s, OutsideHull::none);
  EXPECT_GT(normal_derivative_jump(linear, edges, rng), 0.01);
}

/// Nielson's functional, from its definition: for each Delaunay edge from p_i to p_j, the cubic
/// W(s), s in [0, 1], with W(0) = f_i, W(1) = f_j, W'(0) = g_i.E, W'(1) = g_j.E; its second
/// derivative in arc length is W''(s) / L^2, linear in s, so int_E |d2W/dl2|^2 dl =
/// (A^2 + A B + B^2) / (3 L^3) with A, B = W''(0), W''(1).
double edge_curvature(const DelaunayMesh& mesh, const std::vector<double>& f, const std::vector<double>& g) {
  const auto& p = mesh.points();
  double total = 0;
  for (size_t face = 0; face < mesh.faces(); ++face)
    for (int k = 0; k < 3; ++k) {
      const std::int64_t nb = mesh.neighbour(face, k);
      if (nb >= 0 && nb < static_cast<std::int64_t>(face)) continue;
      const unsigned i = mesh.face(face)[(k + 1) % 3], j = mesh.face(face)[(k + 2) % 3];
      const Vec2 e = p[j] - p[i];
      const double m0 = g[2 * i] * e.x() + g[2 * i + 1] * e.y(), m1 = g[2 * j] * e.x() + g[2 * j + 1] * e.y();
      const double a = -6 * f[i] - 4 * m0 + 6 * f[j] - 2 * m1;  // Hermite basis: W''(0)
      const double b = 6 * f[i] + 2 * m0 - 6 * f[j] + 4 * m1;   // W''(1)
      total += (a * a + a * b + b * b) / (3 * std::pow(e.norm(), 3));
    }
  return total;
}

TEST(CloughTocher, GradientsMinimiseTheEdgeCurvature) {
  std::mt19937 rng(45);
  const ScatteredSamples s = random_samples(50, rng);
  const CloughTocher f(s, OutsideHull::none);
  std::vector<double> g = f.gradients();
  // The functional is quadratic in g, so a central difference gives its derivative up to
  // rounding; at the minimiser every component is zero, compared with the derivative at g = 0.
  const double delta = 1e-3;
  const std::vector<double> zero(g.size(), 0.0);
  double worst = 0, scale = 0;
  for (size_t k = 0; k < g.size(); ++k) {
    auto derivative = [&](std::vector<double> at) {
      at[k] += delta;
      const double up = edge_curvature(f.mesh(), s.values, at);
      at[k] -= 2 * delta;
      return (up - edge_curvature(f.mesh(), s.values, at)) / (2 * delta);
    };
    worst = std::max(worst, std::abs(derivative(g)));
    scale = std::max(scale, std::abs(derivative(zero)));
  }
  EXPECT_LT(worst, 1e-8 * scale) << "largest derivative at the gradients found: " << worst << ", at zero: " << scale;
  const double at_minimum = edge_curvature(f.mesh(), s.values, g);
  std::uniform_real_distribution<double> small(-0.01, 0.01);
  for (int t = 0; t < 20; ++t) {
    std::vector<double> other = g;
    for (double& x : other) x += small(rng);
    EXPECT_GT(edge_curvature(f.mesh(), s.values, other), at_minimum);
  }
}

TEST(CloughTocher, OutsideTheHull) {
  std::mt19937 rng(46);
  ScatteredSamples s = random_samples(30, rng, 0.05, 0.95);
  const Vec2 corners[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const double corner_values[4] = {1, 2, -3, 0.5};
  for (int c = 0; c < 4; ++c) s.points.push_back(corners[c]), s.values.push_back(corner_values[c]);
  const CloughTocher nearest(s, OutsideHull::nearest), none(s, OutsideHull::none);
  // Beside the edge x = 1 from (1, 0) to (1, 1): the surface's value at (1, y), the cubic
  // Hermite of the corners' values and y-derivatives.
  const auto& g = nearest.gradients();
  const size_t c1 = s.points.size() - 3, c2 = s.points.size() - 2;  // (1, 0), (1, 1)
  for (const double y : {0.1, 0.3, 0.75}) {
    const double h00 = 2 * y * y * y - 3 * y * y + 1, h10 = y * y * y - 2 * y * y + y, h01 = -2 * y * y * y + 3 * y * y,
                 h11 = y * y * y - y * y;
    const double hermite = h00 * 2 + h10 * g[2 * c1 + 1] + h01 * -3 + h11 * g[2 * c2 + 1];
    EXPECT_NEAR(eval1(nearest, Vec2(1.5, y)), hermite, kPolynomialRounding) << y;
    EXPECT_EQ(eval1(nearest, Vec2(1.5, y)), eval1(nearest, Vec2(1, y)));
    EXPECT_TRUE(std::isnan(eval1(none, Vec2(1.5, y))));
    EXPECT_EQ(eval1(none, Vec2(1, y)), eval1(nearest, Vec2(1, y)));
  }
  EXPECT_EQ(eval1(nearest, Vec2(1.5, 1.25)), -3);  // beyond a corner: the corner's value
  EXPECT_EQ(eval1(nearest, Vec2(-2, -0.5)), 1);
}

TEST(CloughTocher, ScalesWithTheValuesAtAnyMagnitude) {
  // The interpolant is linear in the values: values times c give c times the result, for any c
  // the values stay finite and normal with. A linear function's values times 1e-300 and 1e100
  // (the largest accepted) are reproduced, and on non-linear data the result for c V is c times
  // that for V to rounding (bit for bit when c is a power of two). Before, the solver's squared
  // residuals underflowed: values of 1e-165 to 1e-300 got zero gradients (a linear function off
  // by 0.0745 of its range), 1e-160 non-finite ones (refused as if the points were at fault).
  std::mt19937 rng(51);
  ScatteredSamples s = random_samples(200, rng, 0, 1);
  std::vector<Vec2> q;
  std::uniform_real_distribution<double> inner(0.1, 0.9);
  for (int t = 0; t < 500; ++t) q.emplace_back(inner(rng), inner(rng));
  const auto values_at = [&](const ScatteredSamples& samples) {
    const CloughTocher f(samples, OutsideHull::none);
    std::vector<double> out(q.size());
    f.evaluate(q, out);
    return out;
  };
  auto linear = [](const Vec2& p) { return 3 * p.x() - 2 * p.y(); };
  for (const double c : {1e-300, 1e-160, 1.0, 1e100}) {
    ScatteredSamples scaled = s;
    for (size_t i = 0; i < s.points.size(); ++i) scaled.values[i] = c * linear(s.points[i]);
    const std::vector<double> got = values_at(scaled);
    for (size_t k = 0; k < q.size(); ++k)
      ASSERT_NEAR(got[k] / c, linear(q[k]), 1e-13) << "values times " << c << ", query " << k;
  }
  for (size_t i = 0; i < s.points.size(); ++i)
    s.values[i] = std::sin(5 * s.points[i].x()) + s.points[i].y() * s.points[i].y();
  const std::vector<double> reference = values_at(s);
  for (const double c : {1e-300, 1e-200, 1e-160, 1e-100, 1e50, 1e100, std::ldexp(1.0, -990), std::ldexp(1.0, 330)}) {
    ScatteredSamples scaled = s;
    for (double& v : scaled.values) v *= c;
    const std::vector<double> got = values_at(scaled);
    const bool exact = std::ilogb(c) == std::log2(c);  // a power of two: no rounding at all
    for (size_t k = 0; k < q.size(); ++k) {
      if (exact) ASSERT_EQ(got[k] / c, reference[k]) << "values times " << c << ", query " << k;
      else ASSERT_NEAR(got[k] / c, reference[k], 1e-13) << "values times " << c << ", query " << k;
    }
  }
}

TEST(CloughTocher, RefusesTooFewCollinearOrDuplicateSamples) {
  ScatteredSamples two;
  two.points = {{0, 0}, {1, 0}};
  two.values = {1, 2};
  const auto r2 = make_scattered_interpolant(Method::clough_tocher, two);
  ASSERT_FALSE(r2.ok());
  EXPECT_NE(r2.reason().find("at least 3 samples"), std::string::npos) << r2.reason();

  ScatteredSamples line;
  for (int i = 0; i < 5; ++i) line.points.emplace_back(i, 2 * i), line.values.push_back(i);
  const auto rl = make_scattered_interpolant(Method::clough_tocher, line);
  ASSERT_FALSE(rl.ok());
  EXPECT_NE(rl.reason().find("one line"), std::string::npos) << rl.reason();

  ScatteredSamples dup;
  dup.points = {{0, 0}, {1, 0}, {0, 1}, {1, 0}};
  dup.values = {1, 2, 3, 4};
  const auto rd = make_scattered_interpolant(Method::clough_tocher, dup);
  ASSERT_FALSE(rd.ok());
  EXPECT_NE(rd.reason().find("duplicate"), std::string::npos) << rd.reason();
}

}  // namespace clough_tocher_test
}  // namespace radrecon
