// Bicubic Hermite interpolation with estimated derivatives, against the closed forms it must
// reproduce (quadratics, with their derivatives at the nodes), its defining properties (exact at
// the nodes, C1 across cell edges, measured by finite differences) and an independent
// implementation of the same interpolant (Keys' cubic convolution, keys_cubic.h).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "reconstruct/hermite.h"
#include "reconstruct/keys_cubic.h"
#include "reconstruct/methods.h"

namespace radrecon {
namespace hermite_test {

// Every check below that is exact in exact arithmetic costs rounding only: a few dozen
// multiply-adds of values of the data's magnitude, derivatives divided by the spacing and
// multiplied back by it. 1e-12 of the data's magnitude leaves ample margin and still catches any
// wrong weight or estimate (off by O(1) of the magnitude).
constexpr double kRelative = 1e-12;

constexpr unsigned kSeed = 20240917;

using Fn = std::function<double(double, double)>;

/// nx x ny nodes from (x0, y0) = (-1, 2), spacing 0.5 x 0.375, with f's values.
GridNodes Sampled(int nx, int ny, const Fn& f) {
  GridNodes n;
  n.nx = nx;
  n.ny = ny;
  n.x0 = -1.0;
  n.y0 = 2.0;
  n.dx = 0.5;
  n.dy = 0.375;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) n.values.push_back(f(n.x0 + i * n.dx, n.y0 + j * n.dy));
  return n;
}

double X1(const GridNodes& n) { return n.x0 + (n.nx - 1) * n.dx; }
double Y1(const GridNodes& n) { return n.y0 + (n.ny - 1) * n.dy; }

/// The largest |value| at the nodes: the scale of rounding errors.
double Scale(const GridNodes& n) {
  double s = 1;
  for (double v : n.values) s = std::max(s, std::abs(v));
  return s;
}

std::vector<double> Eval(const Interpolant& f, const std::vector<Vec2>& points) {
  std::vector<double> out(points.size() * f.channels());
  f.evaluate(points, out);
  return out;
}

double At(const Interpolant& f, double x, double y) { return Eval(f, {Vec2(x, y)})[0]; }

std::vector<Vec2> RandomInside(const GridNodes& n, int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> ux(n.x0, X1(n)), uy(n.y0, Y1(n));
  std::vector<Vec2> p;
  for (int k = 0; k < count; ++k) p.emplace_back(ux(rng), uy(rng));
  return p;
}

/// A random quadratic a + b x + c y + d x^2 + e x y + g y^2, with its derivatives.
struct Quadratic {
  double a, b, c, d, e, g;
  double operator()(double x, double y) const { return a + b * x + c * y + d * x * x + e * x * y + g * y * y; }
  double fx(double x, double y) const { return b + 2 * d * x + e * y; }
  double fy(double x, double y) const { return c + e * x + 2 * g * y; }
  double fxy() const { return e; }
  static Quadratic Random(unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-2, 2);
    return {u(rng), u(rng), u(rng), u(rng), u(rng), u(rng)};
  }
};

/// Smooth, not a polynomial: nothing the interpolant reproduces.
double Wavy(double x, double y) { return std::sin(2.3 * x + 0.4) * std::cos(1.7 * y) + 0.5 * std::sin(3.1 * x * y); }

std::string Where(double x, double y) { return "at (" + std::to_string(x) + ", " + std::to_string(y) + ")"; }

TEST(Hermite, ExactAtTheNodes) {
  for (const auto& [nx, ny] : {std::pair{6, 5}, std::pair{2, 4}, std::pair{3, 2}, std::pair{2, 2}}) {
    SCOPED_TRACE(std::to_string(nx) + " x " + std::to_string(ny));
    const GridNodes n = Sampled(nx, ny, Wavy);
    const Hermite h(n);
    for (int j = 0; j < n.ny; ++j)
      for (int i = 0; i < n.nx; ++i) {
        const double x = n.x0 + i * n.dx, y = n.y0 + j * n.dy;
        EXPECT_NEAR(At(h, x, y), n.values[static_cast<size_t>(j) * nx + i], kRelative * Scale(n)) << Where(x, y);
      }
  }
}

TEST(Hermite, DerivativeEstimatesAreExactForQuadratics) {
  // Central and 3-point one-sided differences are exact for quadratics; f_xy = D_y (D_x f) too.
  for (unsigned s = 0; s < 5; ++s) {
    const Quadratic q = Quadratic::Random(kSeed + s);
    const GridNodes n = Sampled(5, 3, q);
    const Hermite h(n);
    const double tol = kRelative * Scale(n) / std::min(n.dx, n.dy);
    for (int j = 0; j < n.ny; ++j)
      for (int i = 0; i < n.nx; ++i) {
        const double x = n.x0 + i * n.dx, y = n.y0 + j * n.dy;
        EXPECT_NEAR(h.fx(i, j, 0), q.fx(x, y), tol) << Where(x, y);
        EXPECT_NEAR(h.fy(i, j, 0), q.fy(x, y), tol) << Where(x, y);
        EXPECT_NEAR(h.fxy(i, j, 0), q.fxy(), tol / std::min(n.dx, n.dy)) << Where(x, y);
      }
  }
}

TEST(Hermite, ReproducesQuadraticsEverywhereInTheGrid) {
  for (const auto& [nx, ny] : {std::pair{3, 3}, std::pair{7, 5}, std::pair{4, 9}}) {
    for (unsigned s = 0; s < 4; ++s) {
      SCOPED_TRACE(std::to_string(nx) + " x " + std::to_string(ny) + ", quadratic " + std::to_string(s));
      const Quadratic q = Quadratic::Random(kSeed + 10 * s + nx);
      const GridNodes n = Sampled(nx, ny, q);
      const Hermite h(n);
      const std::vector<Vec2> pts = RandomInside(n, 1000, kSeed + s);
      const std::vector<double> out = Eval(h, pts);
      for (size_t k = 0; k < pts.size(); ++k)
        EXPECT_NEAR(out[k], q(pts[k].x(), pts[k].y()), kRelative * Scale(n)) << Where(pts[k].x(), pts[k].y());
    }
  }
}

TEST(Hermite, TwoNodesAlongAnAxisReproduceWhatIsLinearAlongIt) {
  // With 2 nodes along x the estimates along x are first-order, exact for functions linear in x:
  // a + b x + c y + e x y + g y^2 is reproduced (and its mirror image on an N x 2 grid).
  Quadratic q = Quadratic::Random(kSeed + 77);
  q.d = 0;
  for (bool transposed : {false, true}) {
    SCOPED_TRACE(transposed ? "8 x 2" : "2 x 8");
    const Fn f = transposed ? Fn([&](double x, double y) { return q(y, x); }) : Fn(q);
    const GridNodes n = transposed ? Sampled(8, 2, f) : Sampled(2, 8, f);
    const Hermite h(n);
    const std::vector<Vec2> pts = RandomInside(n, 1000, kSeed);
    const std::vector<double> out = Eval(h, pts);
    for (size_t k = 0; k < pts.size(); ++k)
      EXPECT_NEAR(out[k], f(pts[k].x(), pts[k].y()), kRelative * Scale(n)) << Where(pts[k].x(), pts[k].y());
  }
}

TEST(Hermite, IsContinuouslyDifferentiableAcrossCellEdges) {
  // On each side of a point of an interior cell edge, the normal derivative by a second-order
  // one-sided difference with step delta = 1e-4 of the spacing. Its truncation error is about
  // delta^2 |f'''| / 3 (the patches' third derivatives are some 10 |f| / h^3 here: 3e-7 |f| / h)
  // and its rounding error some 4 eps |f| / delta (1e-11 |f| / h); a kink, as bilinear has,
  // shows a jump of O(|f| / h). 1e-5 |f| / h separates the two by orders of magnitude.
  const GridNodes n = Sampled(7, 6, Wavy);
  const Hermite h(n);
  std::mt19937 rng(kSeed);
  std::uniform_real_distribution<double> unit(0, 1);
  const double scale = Scale(n);
  for (int k = 0; k < 200; ++k) {
    const bool vertical = k % 2 == 0;  // an edge x = const (derivative along x), or y = const
    const double hstep = vertical ? n.dx : n.dy, delta = 1e-4 * hstep;
    const int line = 1 + static_cast<int>(unit(rng) * ((vertical ? n.nx : n.ny) - 2));
    double x = n.x0 + line * n.dx, y = n.y0 + unit(rng) * (Y1(n) - n.y0);
    if (!vertical) x = n.x0 + unit(rng) * (X1(n) - n.x0), y = n.y0 + line * n.dy;
    auto f = [&](double t) { return vertical ? At(h, x + t, y) : At(h, x, y + t); };
    const double left = (3 * f(0) - 4 * f(-delta) + f(-2 * delta)) / (2 * delta);
    const double right = (-3 * f(0) + 4 * f(delta) - f(2 * delta)) / (2 * delta);
    EXPECT_NEAR(left, right, 1e-5 * scale / hstep) << (vertical ? "d/dx " : "d/dy ") << Where(x, y);
    // And the value itself: on the edge, from both sides.
    EXPECT_NEAR(f(-1e-12 * hstep), f(1e-12 * hstep), 1e-10 * scale) << Where(x, y);
  }
}

TEST(Hermite, EqualsKeysCubicConvolution) {
  // Keys' cubic convolution (a = -1/2) along an axis is the cubic Hermite spline whose slopes are
  // the central differences, and Keys' end rule f(-1) = 3 f(0) - 3 f(1) + f(2) gives the slope
  // (-3 f(0) + 4 f(1) - f(2)) / 2 (with 2 nodes, f(-1) = 2 f(0) - f(1): f(1) - f(0)): the tensor
  // product of Keys' weights is the same interpolant, computed independently (keys_cubic.cpp).
  for (const auto& [nx, ny] : {std::pair{6, 5}, std::pair{2, 5}, std::pair{3, 2}}) {
    SCOPED_TRACE(std::to_string(nx) + " x " + std::to_string(ny));
    const GridNodes n = Sampled(nx, ny, Wavy);
    const Hermite h(n);
    const std::vector<Vec2> pts = RandomInside(n, 500, kSeed + 5);
    const std::vector<double> out = Eval(h, pts);
    for (size_t k = 0; k < pts.size(); ++k) {
      const double gx = (pts[k].x() - n.x0) / n.dx, gy = (pts[k].y() - n.y0) / n.dy;
      const int i = std::min(static_cast<int>(gx), nx - 2), j = std::min(static_cast<int>(gy), ny - 2);
      const AxisWeights wx = keys_weights(nx, i, gx - i), wy = keys_weights(ny, j, gy - j);
      double want = 0;
      for (int b = 0; b < wy.count; ++b)
        for (int a = 0; a < wx.count; ++a)
          want += wx.w[a] * wy.w[b] * n.values[static_cast<size_t>(wy.first + b) * nx + wx.first + a];
      EXPECT_NEAR(out[k], want, kRelative * Scale(n)) << Where(pts[k].x(), pts[k].y());
    }
  }
}

TEST(Hermite, ClampsOutsideTheGridOntoIt) {
  const Quadratic q = Quadratic::Random(kSeed + 3);
  const GridNodes n = Sampled(5, 4, q);
  const Hermite h(n);
  const double x0 = n.x0, x1 = X1(n), y0 = n.y0, y1 = Y1(n);
  const std::vector<std::pair<Vec2, Vec2>> cases = {
      {{x0 - 3, 2.6}, {x0, 2.6}}, {{x1 + 0.01, 3.1}, {x1, 3.1}},    {{-0.3, y0 - 10}, {-0.3, y0}},
      {{0.7, y1 + 1}, {0.7, y1}}, {{x0 - 1, y0 - 1}, {x0, y0}},      {{x1 + 1e6, y1 + 1e6}, {x1, y1}}};
  for (const auto& [query, border] : cases)  // the border points are in the grid: f there
    EXPECT_NEAR(At(h, query.x(), query.y()), q(border.x(), border.y()), kRelative * Scale(n)) << Where(query.x(), query.y());
  EXPECT_TRUE(std::isnan(At(h, std::numeric_limits<double>::quiet_NaN(), 2.5)));
}

TEST(Hermite, InterpolatesEveryChannelIndependently) {
  const Quadratic q0 = Quadratic::Random(kSeed + 21), q1 = Quadratic::Random(kSeed + 22);
  GridNodes n = Sampled(4, 4, q0);
  const GridNodes second = Sampled(4, 4, q1);
  n.channels = 2;
  n.values.clear();
  for (size_t k = 0; k < second.values.size(); ++k) {
    n.values.push_back(Sampled(4, 4, q0).values[k]);
    n.values.push_back(second.values[k]);
  }
  const Hermite h(n);
  const std::vector<Vec2> pts = RandomInside(n, 300, kSeed);
  const std::vector<double> out = Eval(h, pts);
  for (size_t k = 0; k < pts.size(); ++k) {
    EXPECT_NEAR(out[2 * k], q0(pts[k].x(), pts[k].y()), kRelative * 20);
    EXPECT_NEAR(out[2 * k + 1], q1(pts[k].x(), pts[k].y()), kRelative * 20);
  }
}

TEST(Hermite, RefusesWhatItCannotInterpolate) {
  const GridNodes good = Sampled(3, 3, Wavy);
  GridNodes one_row = Sampled(4, 1, Wavy);
  EXPECT_THROW(Hermite{one_row}, ReconstructionError);
  const InterpolantResult r = make_nodal_interpolant(Method::hermite, one_row);
  ASSERT_FALSE(r);
  EXPECT_NE(r.reason().find("at least 2 x 2"), std::string::npos) << r.reason();

  GridNodes flat = good;
  flat.dy = 0;
  EXPECT_THROW(Hermite{flat}, ReconstructionError);
  GridNodes nan_value = good;
  nan_value.values[4] = std::numeric_limits<double>::quiet_NaN();
  try {
    Hermite h(nan_value);
    ADD_FAILURE() << "a NaN sample was accepted";
  } catch (const ReconstructionError& e) {
    EXPECT_NE(std::string(e.what()).find("finite"), std::string::npos) << e.what();
  }

  MethodParams walled;
  walled.barriers = Barriers::from_polylines(std::vector<Polyline>{{{20.0, 2.0}, {20.0, 2.5}}}).value();
  // Barriers are taken (BarrierGrid's rule, barrier_grid.h); one far from every cell changes
  // nothing, to the bit.
  const InterpolantResult b = make_nodal_interpolant(Method::hermite, good, walled);
  ASSERT_TRUE(b) << b.reason();
  const Hermite plain(good);
  for (const Vec2& q : {Vec2(good.x0, good.y0), Vec2(good.x0 + 0.37 * good.dx, good.y0 + 1.61 * good.dy)}) {
    double with = 0, without = 0;
    b.value()->evaluate(std::span(&q, 1), std::span(&with, 1));
    plain.evaluate(std::span(&q, 1), std::span(&without, 1));
    EXPECT_EQ(with, without);
  }

  ScatteredSamples s;
  s.points = {{0, 0}, {1, 0}, {0, 1}};
  s.values = {1, 2, 3};
  const InterpolantResult sc = make_scattered_interpolant(Method::hermite, s);
  ASSERT_FALSE(sc);
  EXPECT_NE(sc.reason().find("regular grid"), std::string::npos) << sc.reason();

  const InterpolantResult ok = make_nodal_interpolant(Method::hermite, good);
  ASSERT_TRUE(ok) << ok.reason();
}

}  // namespace hermite_test
}  // namespace radrecon
