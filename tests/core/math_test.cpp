#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/math.h"

namespace radrecon {
namespace math_test {

/// Double-precision round-off of the reduction steps, a few ulps of pi.
constexpr double kAbsolute = 1e-15;

TEST(Atan2NonNeg, AgreesWithLibmOverTheUpperHalfPlane) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> angle(0, std::numbers::pi), log_r(-20, 20);
  for (int k = 0; k < 200000; ++k) {
    const double a = angle(rng), r = std::exp(log_r(rng));
    const double y = std::max(0.0, r * std::sin(a)), x = r * std::cos(a);
    ASSERT_NEAR(atan2_nonneg(y, x), std::atan2(y, x), kAbsolute) << "y=" << y << " x=" << x;
  }
}

TEST(Atan2NonNeg, SpecialAngles) {
  EXPECT_EQ(atan2_nonneg(0, 1), 0.0);
  EXPECT_EQ(atan2_nonneg(0, 0), 0.0);
  EXPECT_NEAR(atan2_nonneg(1, 0), std::numbers::pi / 2, kAbsolute);
  EXPECT_NEAR(atan2_nonneg(0, -1), std::numbers::pi, kAbsolute);
  EXPECT_NEAR(atan2_nonneg(1, 1), std::numbers::pi / 4, kAbsolute);
  EXPECT_NEAR(atan2_nonneg(1, -1), 3 * std::numbers::pi / 4, kAbsolute);
  EXPECT_NEAR(atan2_nonneg(1e-300, 1), 1e-300, 1e-310);
}

#if defined(__AVX2__) && defined(__FMA__)
TEST(Atan2NonNeg4, AgreesWithLibmInEveryLane) {
  std::mt19937_64 rng(6);
  std::uniform_real_distribution<double> angle(0, std::numbers::pi), log_r(-20, 20);
  for (int k = 0; k < 50000; ++k) {
    alignas(32) double y[4], x[4], a[4];
    for (int l = 0; l < 4; ++l) {
      const double t = angle(rng), r = std::exp(log_r(rng));
      y[l] = std::max(0.0, r * std::sin(t)), x[l] = r * std::cos(t);
    }
    _mm256_store_pd(a, atan2_nonneg4(_mm256_load_pd(y), _mm256_load_pd(x)));
    for (int l = 0; l < 4; ++l) ASSERT_NEAR(a[l], std::atan2(y[l], x[l]), kAbsolute) << "y=" << y[l] << " x=" << x[l];
  }
}

TEST(Atan2NonNeg4, SpecialAngles) {
  const double q = std::numbers::pi / 4;
  alignas(32) double a[4];
  _mm256_store_pd(a, atan2_nonneg4(_mm256_setr_pd(0, 0, 1, 0), _mm256_setr_pd(1, 0, 0, -1)));
  EXPECT_EQ(a[0], 0.0);
  EXPECT_EQ(a[1], 0.0);  // y == x == 0
  EXPECT_NEAR(a[2], 2 * q, kAbsolute);
  EXPECT_NEAR(a[3], 4 * q, kAbsolute);
  _mm256_store_pd(a, atan2_nonneg4(_mm256_setr_pd(1, 1, 1e-300, std::tan(q / 2)), _mm256_setr_pd(1, -1, 1, 1)));
  EXPECT_NEAR(a[0], q, kAbsolute);
  EXPECT_NEAR(a[1], 3 * q, kAbsolute);
  EXPECT_NEAR(a[2], 1e-300, 1e-310);
  EXPECT_NEAR(a[3], q / 2, kAbsolute);  // the reduction's threshold
}
#endif

}  // namespace math_test
}  // namespace radrecon
