// Hardy's multiquadrics: exact at the samples, Eck's radii, and the coefficients against an
// independent solve (Householder QR with full pivoting instead of partial-pivoting LU).

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "core/error.h"
#include "reconstruct/multiquadric.h"

namespace radrecon {
namespace {

ScatteredSamples random_samples(int n, std::mt19937& rng) {
  std::uniform_real_distribution<double> xy(0, 4), value(0, 1);
  ScatteredSamples s;
  for (int i = 0; i < n; ++i) {
    s.points.emplace_back(xy(rng), xy(rng));
    s.values.push_back(value(rng));
  }
  return s;
}

TEST(Multiquadric, EckRadiusIsTheNearestOtherSample) {
  std::mt19937 rng(8);
  const ScatteredSamples s = random_samples(40, rng);
  const Multiquadric f(s, 0.5, std::nullopt);
  for (size_t i = 0; i < s.points.size(); ++i) {
    double best = std::numeric_limits<double>::infinity();
    for (size_t j = 0; j < s.points.size(); ++j)
      if (j != i) best = std::min(best, (s.points[i] - s.points[j]).squaredNorm());
    EXPECT_DOUBLE_EQ(f.r_sq()[i], best);
  }
}

TEST(Multiquadric, ExactAtTheSamplesAndAgreesWithAnIndependentSolve) {
  std::mt19937 rng(9);
  const ScatteredSamples s = random_samples(60, rng);
  for (double mu : {0.5, -0.5, 1.5}) {
    const Multiquadric f(s, mu, std::nullopt);
    std::vector<double> at(s.points.size());
    f.evaluate(s.points, at);
    for (size_t i = 0; i < s.points.size(); ++i) EXPECT_NEAR(at[i], s.values[i], 1e-8) << "mu=" << mu;
    // Independent: the same system by full-pivoting Householder QR.
    const Eigen::Index n = static_cast<Eigen::Index>(s.points.size());
    Eigen::MatrixXd A(n, n);
    Eigen::VectorXd b(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      b(i) = s.values[static_cast<size_t>(i)];
      for (Eigen::Index j = 0; j < n; ++j)
        A(i, j) = std::pow((s.points[static_cast<size_t>(i)] - s.points[static_cast<size_t>(j)]).squaredNorm() +
                               f.r_sq()[static_cast<size_t>(j)], mu);
    }
    const Eigen::VectorXd alpha = A.fullPivHouseholderQr().solve(b);
    std::uniform_real_distribution<double> xy(0, 4);
    for (int t = 0; t < 50; ++t) {
      const Vec2 q(xy(rng), xy(rng));
      double expected = 0;
      for (Eigen::Index j = 0; j < n; ++j)
        expected += alpha(j) * std::pow((q - s.points[static_cast<size_t>(j)]).squaredNorm() + f.r_sq()[static_cast<size_t>(j)], mu);
      double got;
      f.evaluate(std::span(&q, 1), std::span(&got, 1));
      EXPECT_NEAR(got, expected, 1e-7 * (1 + std::abs(expected))) << "mu=" << mu;
    }
  }
}

TEST(Multiquadric, ConstantRadiusAndRefusals) {
  std::mt19937 rng(10);
  const ScatteredSamples s = random_samples(20, rng);
  const Multiquadric f(s, 0.5, 0.3);
  for (double r2 : f.r_sq()) EXPECT_DOUBLE_EQ(r2, 0.09);
  ScatteredSamples dup = s;
  dup.points.push_back(dup.points[3]);
  dup.values.push_back(0.5);
  EXPECT_THROW(Multiquadric(dup, 0.5, std::nullopt), UserError);
  ScatteredSamples one;
  one.points = {Vec2(1, 1)};
  one.values = {2};
  EXPECT_THROW(Multiquadric(one, 0.5, std::nullopt), UserError);
  const Multiquadric single(one, 0.5, 1.0);  // one sample with a given r: a scaled basis function
  double v;
  const Vec2 q(1, 1);
  single.evaluate(std::span(&q, 1), std::span(&v, 1));
  EXPECT_NEAR(v, 2.0, 1e-14);
}

}  // namespace
}  // namespace radrecon
