// The share done of a converging run (core/progress.h ConvergencePace), against the closed form
// of a residual that falls geometrically at a known pace.

#include <gtest/gtest.h>

#include <cmath>

#include "core/progress.h"

namespace radrecon {
namespace progress_test {

TEST(ConvergencePace, EarlyTheWayDoneThenTheTimeLeftAtTheLatePace) {
  // log10 of the residual falls by 0.2 a second for 10 s (to 1e-2), then by 0.05 a second: a
  // target of 1e-4 is 40 s away from then. One sample every 0.1 s.
  ConvergencePace pace(1e-4);
  const auto log10_residual = [](double t) { return t <= 10 ? -0.2 * t : -2 - 0.05 * (t - 10); };
  double share = 0;
  for (int k = 1; k <= 50; ++k) share = pace.share_done_at(std::pow(10.0, log10_residual(0.1 * k)), 0.1 * k);
  // Before 10 s: the way done in log(residual), 1 of 4 decades at 5 s.
  EXPECT_NEAR(share, 0.25, 1e-12);
  for (int k = 51; k <= 200; ++k) share = pace.share_done_at(std::pow(10.0, log10_residual(0.1 * k)), 0.1 * k);
  // At 20 s (log10 r = -2.5): the last half (10 s to 20 s) fell at 0.05 a second, so the 1.5
  // decades left take 30 s: 20 of 50 s done. The way done alone would say 2.5 / 4.
  EXPECT_NEAR(share, 20.0 / 50.0, 1e-9);
}

TEST(ConvergencePace, ARunThatStallsFallsBackToTheWayDone) {
  // The residual stays put over the last half: no pace to judge by.
  ConvergencePace pace(1e-4);
  double share = 0;
  for (int k = 1; k <= 300; ++k) share = pace.share_done_at(k <= 100 ? std::pow(10.0, -0.02 * k) : 1e-2, 0.1 * k);
  EXPECT_NEAR(share, 0.5, 1e-12);
}

}  // namespace progress_test
}  // namespace radrecon
