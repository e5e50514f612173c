// Resource limits: a request at the limit passes, one beyond is refused naming the option that
// raises it, and a raised limit lets it through.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "core/error.h"
#include "core/limits.h"
#include "support/temp_dir.h"

namespace radrecon {
namespace limits_test {

/// Restores a limit's default when the test ends.
struct Restore {
  Limit which;
  ~Restore() { set_limit(which, limit_spec(which).default_value); }
};

std::string refusal(Limit which, long long amount) {
  return testing_support::user_error_message([&] { check_limit(which, amount, "--where", "the request"); });
}

TEST(Limits, BeyondTheLimitIsRefusedNamingItsOption) {
  for (const Limit which : kAllLimits) {
    const Restore restore{which};
    const long long limit = limit_spec(which).default_value;
    EXPECT_EQ(limit_value(which), limit);
    EXPECT_EQ(refusal(which, limit), "") << limit_spec(which).option;
    const std::string message = refusal(which, limit + 1);
    EXPECT_NE(message.find("--where"), std::string::npos) << message;
    EXPECT_NE(message.find(limit_spec(which).option), std::string::npos) << message;
    EXPECT_NE(message.find(std::to_string(limit + 1)), std::string::npos) << message;
    set_limit(which, limit + 1);  // raised: now it passes
    EXPECT_EQ(refusal(which, limit + 1), "");
  }
}

TEST(Limits, OptionsAreDistinct) {
  for (const Limit a : kAllLimits)
    for (const Limit b : kAllLimits) {
      if (a == b) continue;
      EXPECT_STRNE(limit_spec(a).option, limit_spec(b).option);
    }
}

TEST(Limits, InputFilesBeyondTheByteLimitAreRefusedByName) {
  const Restore restore{Limit::file_bytes};
  testing_support::TempDir files("limits");
  const std::string path = (files / "ten.csv").string();
  std::ofstream(path) << "0123456789";
  set_limit(Limit::file_bytes, 10);
  EXPECT_NO_THROW(check_input_file_size(path));
  set_limit(Limit::file_bytes, 9);
  const std::string message = testing_support::user_error_message([&] { check_input_file_size(path); });
  EXPECT_NE(message.find(path), std::string::npos) << message;
  EXPECT_NE(message.find("--max-file-bytes"), std::string::npos) << message;
  EXPECT_NO_THROW(check_input_file_size((files / "missing.csv").string()));  // left to the reader
}

}  // namespace limits_test
}  // namespace radrecon
