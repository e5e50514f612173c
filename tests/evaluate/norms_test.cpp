// Error norms against hand-computed values.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "evaluate/norms.h"

namespace radrecon {
namespace norms_test {

// Small integers summed and divided by 4: exact in binary except for the square root.
constexpr double kExact = 1e-15;

TEST(ErrorNorms, HandComputedCase) {
  // e = approx - reference = {0, 1, -2, 0}:
  //   L1 = (0 + 1 + 2 + 0) / 4 = 0.75, L2 = (0 + 1 + 4 + 0) / 4 = 1.25, RMSE = sqrt(1.25), Linf = 2.
  const std::vector<double> approx = {1, 2, 3, 4}, reference = {1, 1, 5, 4};
  const ErrorNorms n = error_norms(approx, reference);
  EXPECT_EQ(n.count, 4u);
  EXPECT_NEAR(n.l1, 0.75, kExact);
  EXPECT_NEAR(n.l2, 1.25, kExact);
  EXPECT_NEAR(n.rmse, std::sqrt(1.25), kExact);
  EXPECT_NEAR(n.linf, 2.0, kExact);
}

TEST(ErrorNorms, SignOfTheErrorDoesNotMatter) {
  // Swapping approx and reference negates e; every norm is of |e| or e^2.
  const std::vector<double> a = {1, 2, 3, 4}, b = {1, 1, 5, 4};
  const ErrorNorms n = error_norms(b, a);
  EXPECT_NEAR(n.l1, 0.75, kExact);
  EXPECT_NEAR(n.l2, 1.25, kExact);
  EXPECT_NEAR(n.linf, 2.0, kExact);
}

TEST(ErrorNorms, ZeroErrorGivesZeros) {
  const std::vector<double> v = {0.5, -3, 1e6, 42};
  const ErrorNorms n = error_norms(v, v);
  EXPECT_EQ(n.count, 4u);
  EXPECT_EQ(n.l1, 0.0);
  EXPECT_EQ(n.l2, 0.0);
  EXPECT_EQ(n.rmse, 0.0);
  EXPECT_EQ(n.linf, 0.0);
}

TEST(ErrorNorms, SingleValue) {
  // One value with error -3: L1 = 3, L2 = 9, RMSE = 3, Linf = 3.
  const std::vector<double> a = {2}, r = {5};
  const ErrorNorms n = error_norms(a, r);
  EXPECT_EQ(n.count, 1u);
  EXPECT_NEAR(n.l1, 3.0, kExact);
  EXPECT_NEAR(n.l2, 9.0, kExact);
  EXPECT_NEAR(n.rmse, 3.0, kExact);
  EXPECT_NEAR(n.linf, 3.0, kExact);
}

TEST(ErrorNorms, NanInApproxGivesNanNorms) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (size_t at = 0; at < 4; ++at) {
    std::vector<double> approx = {1, 2, 3, 4};
    const std::vector<double> reference = {1, 1, 5, 4};
    approx[at] = nan;  // first, middle and last positions alike (a max must not skip it)
    const ErrorNorms n = error_norms(approx, reference);
    EXPECT_TRUE(std::isnan(n.l1)) << "NaN at " << at;
    EXPECT_TRUE(std::isnan(n.l2)) << "NaN at " << at;
    EXPECT_TRUE(std::isnan(n.rmse)) << "NaN at " << at;
    EXPECT_TRUE(std::isnan(n.linf)) << "NaN at " << at;
  }
}

}  // namespace norms_test
}  // namespace radrecon
