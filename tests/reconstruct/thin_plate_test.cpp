// RBFs with a linear polynomial (the thin-plate spline, the multiquadric with poly = 1), against
// independent answers: the augmented system built here in plain loops, in raw coordinates (no
// centring, no scaling, no value centring) and solved by full-pivoting LU; exact at the samples;
// linear functions reproduced everywhere (inside and outside the hull, global and local, with
// barriers); what subsets on one line and single samples give; the thin-plate spline's
// independence of the unit of length; with barriers, the RBF through the visible samples alone.

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <functional>
#include <random>
#include <string>

#include "reconstruct/local_multiquadric.h"
#include "reconstruct/methods.h"
#include "reconstruct/multiquadric.h"
#include "support/barrier_cases.h"

namespace radrecon {
namespace thin_plate_test {

using namespace testing_support;

/// The library and the independent solve agree to this, relative to the values' size: both solve
/// the same system by backward-stable LU, in differently scaled frames, so their answers differ
/// by some eps / rcond: measured at most 4e-11 (mu = 1.5, the worst conditioned; thin-plate 1e-11).
constexpr double kIndependentRelative = 1e-9;
/// Linear functions are reproduced to the rounding of the solve and of the sums: measured at most
/// 8e-15 of the function's magnitude over the queries (up to 3 box widths out), a factor of 100.
constexpr double kLinearRelative = 1e-12;
/// With barriers, a visible subset's fit may be derived from a nearby one's factorisation
/// (fit_rbf_near(), accepted at a backward error of tol::kRbfNearFitBackwardError, 1e-10): less
/// exact than a fit of its own. Measured 8e-15 (x86-64-v3 build) and 1.1e-12 (x86-64-v4) of the
/// magnitude, a factor of 9; 2.5e-15 in the x86-64-v4 build with no fit derived (all direct).
constexpr double kLinearDerivedRelative = 1e-11;

ScatteredSamples random_samples(int n, unsigned seed, int channels = 1) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> xy(0, 4), value(0, 1);
  ScatteredSamples s;
  s.channels = channels;
  for (int i = 0; i < n; ++i) {
    s.points.emplace_back(xy(rng), xy(rng));
    for (int c = 0; c < channels; ++c) s.values.push_back(value(rng));
  }
  return s;
}

std::vector<Vec2> random_points(int n, unsigned seed, double lo, double hi) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> xy(lo, hi);
  std::vector<Vec2> q;
  for (int i = 0; i < n; ++i) q.emplace_back(xy(rng), xy(rng));
  return q;
}

std::vector<double> values_at(const Interpolant& f, const std::vector<Vec2>& q) {
  std::vector<double> out(q.size() * static_cast<size_t>(f.channels()));
  f.evaluate(q, out);
  return out;
}

/// The textbook interpolant sum_j alpha_j phi(|q - p_j|) + a + b x + c y, with [A P; P^T 0]
/// [alpha; a b c] = [f; 0] in raw coordinates, by Eigen's FullPivLU. phi(d^2, j) is the basis.
struct DenseRbf {
  std::vector<Vec2> p;
  std::function<double(double, size_t)> phi;
  Eigen::MatrixXd coef;  ///< (n + 3) x channels

  DenseRbf(const ScatteredSamples& s, std::function<double(double, size_t)> basis) : p(s.points), phi(std::move(basis)) {
    const Eigen::Index n = static_cast<Eigen::Index>(p.size());
    Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n + 3, n + 3), F = Eigen::MatrixXd::Zero(n + 3, s.channels);
    for (Eigen::Index i = 0; i < n; ++i) {
      for (Eigen::Index j = 0; j < n; ++j) M(i, j) = phi((p[i] - p[j]).squaredNorm(), static_cast<size_t>(j));
      M(i, n) = M(n, i) = 1;
      M(i, n + 1) = M(n + 1, i) = p[i].x();
      M(i, n + 2) = M(n + 2, i) = p[i].y();
      for (int c = 0; c < s.channels; ++c) F(i, c) = s.values[static_cast<size_t>(i) * s.channels + c];
    }
    coef = M.fullPivLu().solve(F);
  }
  double operator()(const Vec2& q, int c) const {
    const Eigen::Index n = static_cast<Eigen::Index>(p.size());
    double v = coef(n, c) + coef(n + 1, c) * q.x() + coef(n + 2, c) * q.y();
    for (Eigen::Index j = 0; j < n; ++j) v += coef(j, c) * phi((q - p[j]).squaredNorm(), static_cast<size_t>(j));
    return v;
  }
};

double thin_plate_phi(double d2) { return d2 > 0 ? 0.5 * d2 * std::log(d2) : 0.0; }

void expect_agreement(const Interpolant& f, const DenseRbf& dense, const ScatteredSamples& s, const std::string& what) {
  const int C = s.channels;
  // Exact at the samples.
  const std::vector<double> at = values_at(f, s.points);
  for (size_t k = 0; k < at.size(); ++k) ASSERT_NEAR(at[k], s.values[k], 1e-10) << what << ", value " << k;
  // The independent solve, inside the samples' box and up to one box width out of it.
  const std::vector<Vec2> q = random_points(300, 5, -4, 8);
  const std::vector<double> got = values_at(f, q);
  double worst = 0, scale = 0;
  for (size_t k = 0; k < q.size(); ++k)
    for (int c = 0; c < C; ++c) {
      const double want = dense(q[k], c);
      scale = std::max(scale, std::abs(want));
      worst = std::max(worst, std::abs(got[k * C + c] - want));
    }
  std::printf("%s: largest difference from the independent solve %.2e (values up to %.2g)\n", what.c_str(), worst, scale);
  EXPECT_LE(worst, kIndependentRelative * scale) << what;
}

TEST(ThinPlate, AgreesWithAnIndependentDenseSolve) {
  const ScatteredSamples s = random_samples(120, 31, 2);
  const Multiquadric f(s, RbfKernel::thin_plate(), std::nullopt);
  expect_agreement(f, DenseRbf(s, [](double d2, size_t) { return thin_plate_phi(d2); }), s, "thin-plate");
}

TEST(MultiquadricWithPolynomial, AgreesWithAnIndependentDenseSolve) {
  const ScatteredSamples s = random_samples(120, 32, 2);
  for (double mu : {0.5, -0.5, 1.5}) {  // 1.5 is conditionally positive definite of order 2: needs the polynomial
    const Multiquadric f(s, RbfKernel::multiquadric(mu, 1), std::nullopt);
    const std::vector<double> r_sq = f.r_sq();
    expect_agreement(f, DenseRbf(s, [&](double d2, size_t j) { return std::pow(d2 + r_sq[j], mu); }), s,
                     "multiquadric poly=1 mu=" + std::to_string(mu));
  }
}

/// A linear function of the samples and of queries up to 3 box widths out.
double linear(const Vec2& p) { return 2 + 3 * p.x() - 1.5 * p.y(); }

ScatteredSamples with_linear_values(ScatteredSamples s) {
  s.channels = 1;
  s.values.resize(s.points.size());
  for (size_t i = 0; i < s.points.size(); ++i) s.values[i] = linear(s.points[i]);
  return s;
}

void expect_linear(const Interpolant& f, const std::vector<Vec2>& q, const std::string& what, size_t allowed_nan = 0,
                   double relative = kLinearRelative) {
  const std::vector<double> got = values_at(f, q);
  double worst = 0, scale = 0;
  size_t nan = 0;
  for (size_t k = 0; k < q.size(); ++k) {
    if (std::isnan(got[k])) {
      ++nan;
      continue;
    }
    scale = std::max(scale, std::abs(linear(q[k])));
    worst = std::max(worst, std::abs(got[k] - linear(q[k])));
  }
  std::printf("%s: linear function reproduced to %.2e (values up to %.3g)\n", what.c_str(), worst, scale);
  EXPECT_LE(worst, relative * scale) << what;
  EXPECT_LE(nan, allowed_nan) << what;
}

TEST(RbfWithPolynomial, ReproducesLinearFunctionsEverywhereGlobalAndLocal) {
  const ScatteredSamples s = with_linear_values(random_samples(600, 33));
  const std::vector<Vec2> q = random_points(3000, 6, -12, 16);  // the box is [0, 4]^2
  expect_linear(Multiquadric(s, RbfKernel::thin_plate(), std::nullopt), q, "thin-plate");
  expect_linear(Multiquadric(s, RbfKernel::multiquadric(0.5, 1), std::nullopt), q, "multiquadric poly=1");
  expect_linear(Multiquadric(s, RbfKernel::multiquadric(-0.5, 1), 0.3), q, "multiquadric poly=1 mu=-0.5 r=0.3");
  // A partition of unity of patches that each reproduce linear functions reproduces them too.
  expect_linear(LocalMultiquadric(s, RbfKernel::thin_plate(), std::nullopt, 24), q, "thin-plate k=24");
  expect_linear(LocalMultiquadric(s, RbfKernel::multiquadric(0.5, 1), std::nullopt, 24), q, "multiquadric poly=1 k=24");
}

TEST(RbfWithPolynomial, ReproducesLinearFunctionsWithBarriers) {
  // Each visible subset has its own polynomial: every query that sees a sample gets the plane.
  const ScatteredSamples s = with_linear_values(two_sided_samples(0, 0));
  const std::vector<Vec2> q = random_points(2000, 7, -0.5, 1.5);
  for (const Barriers& b : {wall(), wall_and_corner()}) {
    expect_linear(Multiquadric(s, RbfKernel::thin_plate(), std::nullopt, b), q, "thin-plate with barriers", 0,
                  kLinearDerivedRelative);
    expect_linear(Multiquadric(s, RbfKernel::multiquadric(0.5, 1), std::nullopt, b), q,
                  "multiquadric poly=1 with barriers", 0, kLinearDerivedRelative);
    expect_linear(LocalMultiquadric(s, RbfKernel::thin_plate(), std::nullopt, 12, b), q, "thin-plate k=12 with barriers",
                  0, kLinearDerivedRelative);
  }
}

TEST(ThinPlate, WithBarriersIsTheThinPlateThroughTheVisibleSamples) {
  const ScatteredSamples s = two_sided_samples(1.0, 5.0);
  const Barriers barriers = wall_and_corner();
  const Multiquadric f(s, RbfKernel::thin_plate(), std::nullopt, barriers);
  const std::vector<Vec2> q = random_points(200, 8, -0.1, 1.1);
  const std::vector<double> got = values_at(f, q);
  for (size_t k = 0; k < q.size(); ++k) {
    ScatteredSamples visible;
    for (const auto& [d2, j] : visible_by_distance(s, barriers, q[k])) {
      visible.points.push_back(s.points[j]);
      visible.values.push_back(s.values[j]);
    }
    const double want = DenseRbf(visible, [](double d2, size_t) { return thin_plate_phi(d2); })(q[k], 0);
    ASSERT_NEAR(got[k], want, 1e-9 * std::max(1.0, std::abs(want))) << "query " << k << " at " << q[k].transpose();
  }
}

TEST(ThinPlate, DoesNotDependOnTheUnitOfLength) {
  // d^2 log(s d) = d^2 log d + log(s) d^2, and the side conditions turn the d^2 term into a
  // constant: the same function in any unit and origin.
  const ScatteredSamples s = random_samples(150, 34);
  ScatteredSamples scaled = s;
  const Vec2 shift(5e3, -2e3);
  for (Vec2& p : scaled.points) p = 1000 * p + shift;
  const Multiquadric f(s, RbfKernel::thin_plate(), std::nullopt), g(scaled, RbfKernel::thin_plate(), std::nullopt);
  std::vector<Vec2> q = random_points(500, 9, -2, 6), q_scaled = q;
  for (Vec2& p : q_scaled) p = 1000 * p + shift;
  const std::vector<double> a = values_at(f, q), b = values_at(g, q_scaled);
  for (size_t k = 0; k < q.size(); ++k) ASSERT_NEAR(a[k], b[k], 1e-9) << "query " << k;
}

TEST(RbfWithPolynomial, SamplesOnOneLineGetAPolynomialAlongIt) {
  // Collinear samples cannot determine a plane: the polynomial is linear along the line and
  // constant across it. Data linear along the line then give that line's function at the
  // query's projection onto it, everywhere.
  const Vec2 origin(1, 2), direction = Vec2(3, 4) / 5;
  ScatteredSamples s;
  for (double t : {-2.0, -1.3, -0.2, 0.5, 1.1, 2.6, 3.0}) {
    s.points.push_back(origin + t * direction);
    s.values.push_back(0.7 - 1.2 * t);
  }
  for (int poly_kind = 0; poly_kind < 2; ++poly_kind) {
    const RbfKernel kernel = poly_kind == 0 ? RbfKernel::thin_plate() : RbfKernel::multiquadric(0.5, 1);
    const Multiquadric f(s, kernel, std::nullopt);
    EXPECT_EQ(f.fit().terms, 2) << kernel.name();
    const std::vector<Vec2> q = random_points(200, 10, -4, 6);
    const std::vector<double> got = values_at(f, q);
    for (size_t k = 0; k < q.size(); ++k) {
      const double t = direction.dot(q[k] - origin);
      ASSERT_NEAR(got[k], 0.7 - 1.2 * t, 1e-10 * (1 + std::abs(t))) << kernel.name() << " query " << k;
    }
  }
  // A plane through the samples with a slope across the line: its slope across is unknowable,
  // the samples still exact.
  for (size_t i = 0; i < s.points.size(); ++i) s.values[i] = linear(s.points[i]);
  const Multiquadric f(s, RbfKernel::thin_plate(), std::nullopt);
  const std::vector<double> at = values_at(f, s.points);
  for (size_t i = 0; i < at.size(); ++i) EXPECT_NEAR(at[i], s.values[i], 1e-12);
}

TEST(RbfWithPolynomial, OneOrTwoSamples) {
  ScatteredSamples one;
  one.points = {Vec2(1, 1)};
  one.values = {2.5};
  const Multiquadric f(one, RbfKernel::thin_plate(), std::nullopt);  // the constant
  EXPECT_EQ(f.fit().terms, 1);
  for (double v : values_at(f, {Vec2(1, 1), Vec2(-7, 3), Vec2(100, 1e3)})) EXPECT_EQ(v, 2.5);
  ScatteredSamples two = one;
  two.points.emplace_back(3, 1);
  two.values.push_back(4.5);
  for (const RbfKernel& kernel : {RbfKernel::thin_plate(), RbfKernel::multiquadric(0.5, 1)}) {
    const Multiquadric g(two, kernel, std::nullopt);  // linear along the line through both: 1.5 + x
    const std::vector<Vec2> q = {Vec2(1, 1), Vec2(3, 1), Vec2(2, 5), Vec2(-4, -2)};
    const std::vector<double> got = values_at(g, q);
    for (size_t k = 0; k < q.size(); ++k) EXPECT_NEAR(got[k], 1.5 + q[k].x(), 1e-12) << kernel.name() << " query " << k;
  }
  ScatteredSamples dup = two;
  dup.points.push_back(two.points[1]);
  dup.values.push_back(1);
  EXPECT_THROW(Multiquadric(dup, RbfKernel::thin_plate(), std::nullopt), ReconstructionError);
}

TEST(ThinPlate, BorderSamplesWithBarriersStayOnTheDomainsBorder) {
  // The paper's ground: 16 x 16 cell centres over 4 m and two wall feet meeting in a corner;
  // brighter on the open side. With --border-samples, samples beside the walls too made a point
  // past a wall's free end see two of them 2e-6 m apart with values a step apart, and the spline
  // through both swung from -303 to 333 for data in [0, 1.04] (a docs audit). The thin-plate
  // spline takes border samples on the domain's border only: its values stay within a fraction
  // of the data's range of it. Its border samples are those of the domain's border (4 sides of 16
  // parts at the data's spacing, 64), none beside a wall.
  const testing_support::WallCornerGround ground = testing_support::wall_corner_ground();
  const ScatteredSamples& s = ground.samples;
  const Barriers barriers = Barriers::from_polylines(ground.walls).value();
  MethodParams params;
  params.barriers = barriers;
  ScatteredSamples bordered = s;
  const Result<size_t> added = add_border_samples(Method::thin_plate, bordered, Rect{0, 0, 4, 4}, params);
  ASSERT_TRUE(added) << added.reason();
  EXPECT_EQ(added.value(), 64u);
  const InterpolantResult f = make_point_interpolant(Method::thin_plate, bordered, params);
  ASSERT_TRUE(f) << f.reason();
  const std::vector<Vec2>& q = ground.queries;
  std::vector<double> v(q.size());
  f.value()->evaluate(q, v);
  const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
  EXPECT_GT(*lo, 0.4 - 0.5 * (1.02 - 0.4));
  EXPECT_LT(*hi, 1.02 + 0.5 * (1.02 - 0.4));
  // The other scattered methods keep theirs beside the walls.
  ScatteredSamples with_walls = s;
  EXPECT_GT(add_border_samples(Method::multiquadric, with_walls, Rect{0, 0, 4, 4}, params).value(), 64u);
}

}  // namespace thin_plate_test
}  // namespace radrecon
