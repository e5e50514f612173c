// Bilinear interpolation of nodal values, against the functions it must reproduce exactly.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "reconstruct/bilinear.h"

namespace radrecon {
namespace bilinear_test {

// Bilinear interpolation of exactly-representable data is a handful of multiply-adds per point:
// results agree with the closed form to a few ulps. 1e-12 relative leaves ample margin while
// catching any wrong weight (which would be off by O(1)).
constexpr double kRelative = 1e-12;

constexpr unsigned kSeed = 20240611;

using Fn = std::function<double(double, double)>;

/// A 5 x 4 node grid on [-1, 1] x [2, 3.5] with the values of the given functions at the nodes.
GridNodes Sampled(const std::vector<Fn>& fns) {
  GridNodes n;
  n.nx = 5;
  n.ny = 4;
  n.x0 = -1.0;
  n.y0 = 2.0;
  n.dx = 0.5;
  n.dy = 0.5;
  n.channels = static_cast<int>(fns.size());
  for (int j = 0; j < n.ny; ++j)
    for (int i = 0; i < n.nx; ++i)
      for (const Fn& f : fns) n.values.push_back(f(n.x0 + i * n.dx, n.y0 + j * n.dy));
  return n;
}

double X1(const GridNodes& n) { return n.x0 + (n.nx - 1) * n.dx; }
double Y1(const GridNodes& n) { return n.y0 + (n.ny - 1) * n.dy; }

std::vector<double> Eval(const Interpolant& f, const std::vector<Vec2>& points) {
  std::vector<double> out(points.size() * f.channels());
  f.evaluate(points, out);
  return out;
}

void ExpectClose(double got, double want, const std::string& what) {
  EXPECT_NEAR(got, want, kRelative * std::max(1.0, std::abs(want))) << what;
}

std::vector<Vec2> RandomInside(const GridNodes& n, int count) {
  std::mt19937 rng(kSeed);
  std::uniform_real_distribution<double> ux(n.x0, X1(n)), uy(n.y0, Y1(n));
  std::vector<Vec2> p;
  for (int k = 0; k < count; ++k) p.emplace_back(ux(rng), uy(rng));
  return p;
}

TEST(Bilinear, ExactAtTheNodes) {
  // Arbitrary (non-smooth) node values: interpolation must still pass through them.
  GridNodes n = Sampled({[](double x, double y) { return std::sin(7 * x) + std::cos(5 * y) * 3; }});
  const Bilinear b(n);
  std::vector<Vec2> pts;
  for (int j = 0; j < n.ny; ++j)
    for (int i = 0; i < n.nx; ++i) pts.emplace_back(n.x0 + i * n.dx, n.y0 + j * n.dy);
  const std::vector<double> out = Eval(b, pts);
  for (size_t k = 0; k < pts.size(); ++k) ExpectClose(out[k], n.values[k], "node " + std::to_string(k));
}

TEST(Bilinear, ReproducesLinearFunctionsEverywhereInside) {
  const Fn f = [](double x, double y) { return 2.75 - 1.5 * x + 0.625 * y; };
  const GridNodes n = Sampled({f});
  const Bilinear b(n);
  const std::vector<Vec2> pts = RandomInside(n, 2000);
  const std::vector<double> out = Eval(b, pts);
  for (size_t k = 0; k < pts.size(); ++k)
    ExpectClose(out[k], f(pts[k].x(), pts[k].y()), "at (" + std::to_string(pts[k].x()) + ", " + std::to_string(pts[k].y()) + ")");
}

TEST(Bilinear, ReproducesTheBilinearFunctionXY) {
  // x y is bilinear on every cell, so interpolating its nodal values gives it back exactly.
  const Fn f = [](double x, double y) { return x * y; };
  const GridNodes n = Sampled({f});
  const Bilinear b(n);
  const std::vector<Vec2> pts = RandomInside(n, 2000);
  const std::vector<double> out = Eval(b, pts);
  for (size_t k = 0; k < pts.size(); ++k)
    ExpectClose(out[k], f(pts[k].x(), pts[k].y()), "at (" + std::to_string(pts[k].x()) + ", " + std::to_string(pts[k].y()) + ")");
}

TEST(Bilinear, ClampsOutsideTheGridToTheBorderValue) {
  const Fn f = [](double x, double y) { return 1.0 + 3.0 * x - 2.0 * y + x * y; };
  const GridNodes n = Sampled({f});
  const Bilinear b(n);
  const double x0 = n.x0, x1 = X1(n), y0 = n.y0, y1 = Y1(n);
  struct Case {
    Vec2 query, border;
  };
  const std::vector<Case> cases = {
      {{x0 - 3.0, 2.6}, {x0, 2.6}},      // left
      {{x1 + 0.01, 3.1}, {x1, 3.1}},     // right
      {{-0.3, y0 - 10.0}, {-0.3, y0}},   // below
      {{0.7, y1 + 1.0}, {0.7, y1}},      // above
      {{x0 - 1, y0 - 1}, {x0, y0}},      // corners
      {{x1 + 1, y0 - 1}, {x1, y0}},
      {{x1 + 5, y1 + 5}, {x1, y1}},
      {{x0 - 1e6, y1 + 1e6}, {x0, y1}},
  };
  for (const Case& c : cases) {
    const std::vector<double> out = Eval(b, {c.query});
    // The border points are on the grid, where the interpolant is exactly f (f is bilinear).
    ExpectClose(out[0], f(c.border.x(), c.border.y()),
                "query (" + std::to_string(c.query.x()) + ", " + std::to_string(c.query.y()) + ")");
  }
}

TEST(Bilinear, InterpolatesEveryChannelIndependently) {
  const std::vector<Fn> fns = {[](double x, double y) { return 4.0 + x - y; },
                               [](double x, double) { return -2.0 * x; },
                               [](double x, double y) { return x * y - 1.0; }};
  const GridNodes n = Sampled(fns);
  const Bilinear b(n);
  ASSERT_EQ(b.channels(), 3);
  const std::vector<Vec2> pts = RandomInside(n, 500);
  const std::vector<double> out = Eval(b, pts);
  for (size_t k = 0; k < pts.size(); ++k)
    for (int c = 0; c < 3; ++c)
      ExpectClose(out[k * 3 + c], fns[c](pts[k].x(), pts[k].y()),
                  "point " + std::to_string(k) + " channel " + std::to_string(c));
}

TEST(Bilinear, NanQueryGivesNan) {
  const GridNodes n = Sampled({[](double x, double y) { return x + y; }, [](double, double) { return 1.0; }});
  const Bilinear b(n);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<double> out = Eval(b, {Vec2(nan, 2.5), Vec2(0.0, nan), Vec2(0.0, 2.5)});
  EXPECT_TRUE(std::isnan(out[0]));
  EXPECT_TRUE(std::isnan(out[1]));
  EXPECT_TRUE(std::isnan(out[2]));
  EXPECT_TRUE(std::isnan(out[3]));
  // A NaN query does not spoil its neighbours in the batch.
  ExpectClose(out[4], 2.5, "finite query after NaN ones");
  ExpectClose(out[5], 1.0, "finite query after NaN ones");
}

}  // namespace bilinear_test
}  // namespace radrecon
