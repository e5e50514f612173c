// Lambert's contour integral against closed forms and published area-to-area form factors.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <random>

#include "solver/form_factor.h"
#include "support/closed_forms.h"

namespace radrecon {
namespace form_factor_test {

using testing_support::parallel_corner_form_factor;
using testing_support::perpendicular_corner_form_factor;

/// Both sides evaluate the same integral exactly in double precision.
constexpr double kClosedFormRelative = 1e-12;
/// Published area-to-area values are given to 5 digits (Howell's catalogue, Cohen & Wallace 1993).
constexpr double kPublishedAbsolute = 1e-5;

ConvexPolygon quad(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  ConvexPolygon p;
  p.push(a);
  p.push(b);
  p.push(c);
  p.push(d);
  return p;
}

TEST(LambertFormFactor, MatchesParallelCornerClosedForm) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> len(0.05, 5.0);
  for (int trial = 0; trial < 200; ++trial) {
    const double a = len(rng), b = len(rng), c = len(rng);
    // Receiver at the origin facing +z; rectangle [0,a] x [0,b] at height c, facing down.
    const double f = lambert_form_factor(Vec3::Zero(), Vec3::UnitZ(),
                                         quad({0, 0, c}, {0, b, c}, {a, b, c}, {a, 0, c}));
    const double expected = parallel_corner_form_factor(a, b, c);
    EXPECT_NEAR(f, expected, kClosedFormRelative * expected) << "a=" << a << " b=" << b << " c=" << c;
  }
}

TEST(LambertFormFactor, MatchesPerpendicularCornerClosedForm) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> len(0.05, 5.0);
  for (int trial = 0; trial < 200; ++trial) {
    const double a = len(rng), b = len(rng), c = len(rng);
    // Receiver at the origin facing +z; rectangle in the plane x = c, y in [0,a], z in [0,b].
    const double f = lambert_form_factor(Vec3::Zero(), Vec3::UnitZ(),
                                         quad({c, 0, 0}, {c, a, 0}, {c, a, b}, {c, 0, b}));
    const double expected = perpendicular_corner_form_factor(a, b, c);
    EXPECT_NEAR(f, expected, kClosedFormRelative * expected) << "a=" << a << " b=" << b << " c=" << c;
  }
}

TEST(LambertFormFactors4, MatchFourCornerSumsUnderARectangle) {
  // A point below the rectangle [0, A] x [0, B] at height c sees it as four rectangles with a
  // corner above it: F is the sum of four corner closed forms.
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> len(0.1, 3.0), unit(0.01, 0.99);
  for (int trial = 0; trial < 100; ++trial) {
    const double A = len(rng), B = len(rng), c = len(rng);
    const ConvexPolygon rect = quad({0, 0, c}, {0, B, c}, {A, B, c}, {A, 0, c});
    std::array<Vec3, 4> points;
    for (Vec3& p : points) p = Vec3(unit(rng) * A, unit(rng) * B, 0);
    std::array<double, 4> f;
    lambert_form_factors4(points, Vec3::UnitZ(), rect, f);
    for (size_t k = 0; k < 4; ++k) {
      const double x = points[k].x(), y = points[k].y();
      const double expected = parallel_corner_form_factor(x, y, c) + parallel_corner_form_factor(A - x, y, c) +
                              parallel_corner_form_factor(x, B - y, c) + parallel_corner_form_factor(A - x, B - y, c);
      EXPECT_NEAR(f[k], expected, kClosedFormRelative * expected) << "trial " << trial << " point " << k;
    }
  }
}

TEST(LambertFormFactors4, PointOnAnEdgeLineAndEmptyPolygon) {
  // A point on the line of one of the square's edges: that edge adds nothing (as for one point).
  const ConvexPolygon square = quad({0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1});
  const std::array<Vec3, 4> points = {Vec3(0, -1, 1), Vec3(0.5, 0.5, 0), Vec3(2, 2, 0), Vec3(0, 0, 1)};
  std::array<double, 4> f;
  lambert_form_factors4(points, Vec3::UnitZ(), square, f);
  for (size_t k = 0; k < 4; ++k) EXPECT_NEAR(f[k], lambert_form_factor(points[k], Vec3::UnitZ(), square), 1e-15) << k;
  lambert_form_factors4(points, Vec3::UnitZ(), ConvexPolygon{}, f);
  for (const double v : f) EXPECT_EQ(v, 0.0);
}

TEST(LambertFormFactor, HemisphereCoveringPolygonGivesOne) {
  // A huge square just above the receiver covers nearly the whole hemisphere.
  const double L = 1e6;
  const double f = lambert_form_factor(Vec3::Zero(), Vec3::UnitZ(), quad({-L, -L, 1}, {-L, L, 1}, {L, L, 1}, {L, -L, 1}));
  EXPECT_NEAR(f, 1.0, 1e-5);
}

/// Composite Gauss-Legendre quadrature of g over the unit square: `panels` x `panels` panels of
/// 8 x 8 points each (the panels resolve the log singularity at a shared edge).
template <typename G>
double integrate_unit_square(G g, int panels) {
  static constexpr std::array<double, 8> x = {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290,
                                              -0.1834346424956498, 0.1834346424956498,  0.5255324099163290,
                                              0.7966664774136267,  0.9602898564975363};
  static constexpr std::array<double, 8> w = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873,
                                              0.3626837833783620, 0.3626837833783620, 0.3137066458778873,
                                              0.2223810344533745, 0.1012285362903763};
  double sum = 0;
  const double h = 1.0 / panels;
  for (int pi = 0; pi < panels; ++pi)
    for (int pj = 0; pj < panels; ++pj)
      for (int i = 0; i < 8; ++i)
        for (int j = 0; j < 8; ++j) {
          const double u = (pi + 0.5 * (x[i] + 1)) * h, v = (pj + 0.5 * (x[j] + 1)) * h;
          sum += 0.25 * h * h * w[i] * w[j] * g(u, v);
        }
  return sum;
}

TEST(LambertFormFactor, ParallelUnitSquaresAtUnitDistance) {
  // Published: F = 0.19982 for two aligned parallel unit squares one unit apart.
  const ConvexPolygon top = quad({0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1});
  const double f = integrate_unit_square(
      [&](double u, double v) { return lambert_form_factor(Vec3(u, v, 0), Vec3::UnitZ(), top); }, 4);
  EXPECT_NEAR(f, 0.19982, kPublishedAbsolute);
}

TEST(LambertFormFactor, PerpendicularUnitSquaresSharingAnEdge) {
  // Published: F = 0.20004 for perpendicular unit squares with a common edge.
  const ConvexPolygon wall = quad({0, 0, 0}, {0, 0, 1}, {0, 1, 1}, {0, 1, 0});
  // Receiver: the floor [0,1]^2 at z = 0 facing +z; the wall is the plane x = 0.
  const double f = integrate_unit_square(
      [&](double u, double v) { return lambert_form_factor(Vec3(u, v, 0), Vec3::UnitZ(), wall); }, 32);
  EXPECT_NEAR(f, 0.20004, kPublishedAbsolute);
}

TEST(ClipToHorizon, KeepsOnlyThePartAboveTheReceiver) {
  // A vertical square straddling the receiver's plane: only its upper half counts.
  const ConvexPolygon full = quad({1, -0.5, -1}, {1, 0.5, -1}, {1, 0.5, 1}, {1, -0.5, 1});
  const ConvexPolygon upper = quad({1, -0.5, 0}, {1, 0.5, 0}, {1, 0.5, 1}, {1, -0.5, 1});
  const Vec3 p = Vec3::Zero(), n = Vec3::UnitZ();
  EXPECT_NEAR(lambert_form_factor(p, n, clip_to_horizon(p, n, full)), lambert_form_factor(p, n, upper), 1e-15);
  // By symmetry, the upper half is two perpendicular-corner rectangles of 0.5 x 1 at distance 1.
  EXPECT_NEAR(lambert_form_factor(p, n, upper), 2 * perpendicular_corner_form_factor(0.5, 1, 1), 1e-14);
}

/// A convex polygon's area (vector area of a fan), m^2.
double area(const ConvexPolygon& p) {
  Vec3 sum = Vec3::Zero();
  for (int i = 1; i + 1 < p.n; ++i) sum += (p.v[i] - p.v[0]).cross(p.v[i + 1] - p.v[0]);
  return 0.5 * sum.norm();
}

TEST(Split, ThePartsTileThePolygonOnEitherSideAndAreWhatClipGives) {
  // Random convex polygons (points on a tilted circle) and random planes: the two parts' areas
  // add up to the polygon's, each lies on its side of the plane, and each is bit for bit what
  // clip() gives by the half-space and by its complement.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> U(-1, 1), angle(0, 2 * std::numbers::pi);
  int across = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const Vec3 centre(U(rng), U(rng), U(rng)), a = Vec3(U(rng), U(rng), U(rng)).normalized();
    const Vec3 b = a.cross(Vec3(U(rng), U(rng), U(rng))).normalized();
    std::vector<double> angles(3 + trial % 6);
    for (double& t : angles) t = angle(rng);
    std::sort(angles.begin(), angles.end());
    ConvexPolygon poly;
    for (const double t : angles) poly.push(centre + std::cos(t) * a + std::sin(t) * b);
    const HalfSpace h{Vec3(U(rng), U(rng), U(rng)), U(rng) * 0.5};
    ConvexPolygon inside, outside;
    split(poly, h, inside, outside);
    EXPECT_NEAR(area(inside) + area(outside), area(poly), 1e-12);
    const double slack = tol::kPlaneDistance_m * h.normal.norm();
    for (int i = 0; i < inside.n; ++i) EXPECT_GE(h.eval(inside.v[i]), -slack);
    for (int i = 0; i < outside.n; ++i) EXPECT_LE(h.eval(outside.v[i]), slack);
    across += !inside.empty() && !outside.empty();
    const ConvexPolygon in_clip = clip(poly, h), out_clip = clip(poly, h.complement());
    ASSERT_EQ(inside.n, in_clip.n);
    ASSERT_EQ(outside.n, out_clip.n);
    for (int i = 0; i < inside.n; ++i) EXPECT_EQ(inside.v[i], in_clip.v[i]);
    for (int i = 0; i < outside.n; ++i) EXPECT_EQ(outside.v[i], out_clip.v[i]);
  }
  EXPECT_GT(across, 400);
  // A polygon in the plane lies on both sides; one wholly inside, on one.
  const ConvexPolygon flat = quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0});
  ConvexPolygon inside, outside;
  split(flat, HalfSpace{Vec3::UnitZ(), 0}, inside, outside);
  EXPECT_EQ(inside.n, 4);
  EXPECT_EQ(outside.n, 4);
  split(flat, HalfSpace{Vec3::UnitZ(), -1}, inside, outside);
  EXPECT_EQ(inside.n, 4);
  EXPECT_EQ(outside.n, 0);
}

}  // namespace form_factor_test
}  // namespace radrecon
