#include "core/parse.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace radrecon {
namespace {

NumberStatus status_of(std::string_view text, double& value) { return parse_double(text, value); }

TEST(ParseDouble, AMagnitudeTooSmallRoundsToZeroOrASubnormalWithItsSign) {
  double v = 1;
  ASSERT_EQ(status_of("1e-400", v), NumberStatus::ok);
  EXPECT_EQ(v, 0.0);
  EXPECT_FALSE(std::signbit(v));
  ASSERT_EQ(status_of("-1e-400", v), NumberStatus::ok);
  EXPECT_EQ(v, 0.0);
  EXPECT_TRUE(std::signbit(v));
  // The least subnormal is 2^-1074 = 4.94e-324; 5e-324 is nearest to it, 2e-324 rounds to 0.
  ASSERT_EQ(status_of("5e-324", v), NumberStatus::ok);
  EXPECT_EQ(v, std::numeric_limits<double>::denorm_min());
  ASSERT_EQ(status_of("+2e-324", v), NumberStatus::ok);
  EXPECT_EQ(v, 0.0);
  // A subnormal by hand: 2^-1060 = 2^14 times the least subnormal.
  ASSERT_EQ(status_of("8.095e-320", v), NumberStatus::ok);
  EXPECT_EQ(v, std::ldexp(1.0, -1060));
}

TEST(ParseDouble, AMagnitudeTooLargeIsOutOfRangeAndOtherTextIsNoNumber) {
  double v = 0;
  EXPECT_EQ(status_of("1e400", v), NumberStatus::out_of_range);
  EXPECT_EQ(status_of("-1e400", v), NumberStatus::out_of_range);
  EXPECT_EQ(status_of("1e-400x", v), NumberStatus::not_a_number);
  EXPECT_EQ(status_of("1e400 ", v), NumberStatus::not_a_number);
  EXPECT_EQ(status_of("+-1", v), NumberStatus::not_a_number);
  EXPECT_EQ(status_of("inf", v), NumberStatus::not_finite);
  ASSERT_EQ(status_of("1.7976931348623157e308", v), NumberStatus::ok);
  EXPECT_EQ(v, std::numeric_limits<double>::max());
}

}  // namespace
}  // namespace radrecon
