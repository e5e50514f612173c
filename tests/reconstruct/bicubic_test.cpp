// Natural bicubic spline against an independent construction: 1-D natural splines solved as a
// dense linear system of their defining conditions, applied rows first, then along y (the
// paper's and Numerical Recipes' recipe).

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "reconstruct/bicubic.h"

namespace radrecon {
namespace bicubic_test {

constexpr double kAgree = 1e-11;  ///< two exact constructions in double precision

/// The natural cubic spline through (x_i, y_i), i < n, equally spaced from x0 by h, evaluated at
/// t: unknowns are the 4 coefficients of each interval's cubic, fixed by interpolation at both
/// ends, C1 and C2 continuity inside, and zero second derivatives at the ends.
double natural_spline_dense(const std::vector<double>& y, double x0, double h, double t) {
  const int n = static_cast<int>(y.size()), m = n - 1;
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(4 * m, 4 * m);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(4 * m);
  int row = 0;
  // Interval k: s_k(u) = a + b u + c u^2 + d u^3 with u = x - x_k in [0, h].
  for (int k = 0; k < m; ++k) {
    A(row, 4 * k) = 1;
    b(row++) = y[k];
    A(row, 4 * k) = 1, A(row, 4 * k + 1) = h, A(row, 4 * k + 2) = h * h, A(row, 4 * k + 3) = h * h * h;
    b(row++) = y[k + 1];
  }
  for (int k = 0; k + 1 < m; ++k) {
    A(row, 4 * k + 1) = 1, A(row, 4 * k + 2) = 2 * h, A(row, 4 * k + 3) = 3 * h * h, A(row, 4 * (k + 1) + 1) = -1;
    ++row;
    A(row, 4 * k + 2) = 2, A(row, 4 * k + 3) = 6 * h, A(row, 4 * (k + 1) + 2) = -2;
    ++row;
  }
  A(row++, 2) = 2;                                            // s_0''(0) = 0
  A(row, 4 * (m - 1) + 2) = 2, A(row++, 4 * (m - 1) + 3) = 6 * h;  // s_m-1''(h) = 0
  const Eigen::VectorXd c = A.fullPivLu().solve(b);
  const int k = std::clamp(static_cast<int>((t - x0) / h), 0, m - 1);
  const double u = t - (x0 + k * h);
  return c(4 * k) + u * (c(4 * k + 1) + u * (c(4 * k + 2) + u * c(4 * k + 3)));
}

GridNodes random_grid(int nx, int ny, std::mt19937& rng) {
  std::uniform_real_distribution<double> value(-1, 2);
  GridNodes g;
  g.nx = nx, g.ny = ny, g.x0 = 0.3, g.y0 = -0.2, g.dx = 0.5, g.dy = 0.7, g.channels = 1;
  g.values.resize(static_cast<size_t>(nx) * ny);
  for (double& v : g.values) v = value(rng);
  return g;
}

TEST(Bicubic, MatchesRowsThenColumnOfDenseNaturalSplines) {
  std::mt19937 rng(17);
  const GridNodes g = random_grid(6, 5, rng);
  const Bicubic spline(g);
  std::uniform_real_distribution<double> ux(g.x0, g.x0 + (g.nx - 1) * g.dx), uy(g.y0, g.y0 + (g.ny - 1) * g.dy);
  for (int k = 0; k < 50; ++k) {
    const Vec2 q(ux(rng), uy(rng));
    std::vector<double> column(static_cast<size_t>(g.ny));
    for (int j = 0; j < g.ny; ++j) {
      std::vector<double> row(g.values.begin() + j * g.nx, g.values.begin() + (j + 1) * g.nx);
      column[static_cast<size_t>(j)] = natural_spline_dense(row, g.x0, g.dx, q.x());
    }
    const double expected = natural_spline_dense(column, g.y0, g.dy, q.y());
    double got;
    spline.evaluate(std::span(&q, 1), std::span(&got, 1));
    EXPECT_NEAR(got, expected, kAgree) << "at " << q.transpose();
  }
}

TEST(Bicubic, ExactAtNodesAndReproducesLinearFunctions) {
  GridNodes g;
  g.nx = 5, g.ny = 4, g.x0 = 1, g.y0 = 2, g.dx = 0.25, g.dy = 0.5, g.channels = 2;
  auto f = [](double x, double y) { return 2 - 3 * x + 0.5 * y; };
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      g.values.push_back(f(g.x0 + i * g.dx, g.y0 + j * g.dy));
      g.values.push_back(7.0);
    }
  const Bicubic spline(g);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> ux(1, 2), uy(2, 3.5);
  std::vector<Vec2> q;
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) q.emplace_back(g.x0 + i * g.dx, g.y0 + j * g.dy);
  for (int k = 0; k < 100; ++k) q.emplace_back(ux(rng), uy(rng));
  std::vector<double> out(q.size() * 2);
  spline.evaluate(q, out);
  for (size_t k = 0; k < q.size(); ++k) {
    EXPECT_NEAR(out[2 * k], f(q[k].x(), q[k].y()), 1e-12);
    EXPECT_NEAR(out[2 * k + 1], 7.0, 1e-12);
  }
}

TEST(Bicubic, SecondDerivativeVanishesAtTheEnds) {
  std::mt19937 rng(5);
  const GridNodes g = random_grid(7, 3, rng);
  const Bicubic spline(g);
  // Along x at the ends of a row: the second difference over a tiny step shrinks like the step.
  const double h = 1e-4, y = g.y0 + g.dy;  // on a node row
  for (double x : {g.x0, g.x0 + (g.nx - 1) * g.dx}) {
    const double s = x == g.x0 ? 1 : -1;
    std::vector<Vec2> q = {Vec2(x, y), Vec2(x + s * h, y), Vec2(x + 2 * s * h, y)};
    std::vector<double> v(3);
    spline.evaluate(q, v);
    const double second = (v[0] - 2 * v[1] + v[2]) / (h * h);
    EXPECT_NEAR(second, 0.0, 1e-2) << "second derivative at x = " << x;
  }
}

TEST(NaturalSplineSecondDerivatives, SatisfyTheTridiagonalSystem) {
  const std::vector<double> y = {1, 3, 2, 5, 4, 4};
  std::vector<double> m(y.size());
  natural_spline_second_derivatives(y.data(), m.data(), 6, 0.5, 1);
  EXPECT_EQ(m.front(), 0.0);
  EXPECT_EQ(m.back(), 0.0);
  for (size_t i = 1; i + 1 < y.size(); ++i)
    EXPECT_NEAR(m[i - 1] + 4 * m[i] + m[i + 1], 6 * (y[i - 1] - 2 * y[i] + y[i + 1]) / 0.25, 1e-12);
}

}  // namespace bicubic_test
}  // namespace radrecon
