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

}  // namespace math_test
}  // namespace radrecon
