// sibson-c1's two gradient fits (Sibson's weights; distance alone where those are
// ill-conditioned) meet without a step: a value moves continuously as a sample nears a long
// hull edge and its fit's conditioning falls through tol::kGradientFitConditionRelative.

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "reconstruct/natural_neighbour.h"
#include "support/scattered.h"

namespace radrecon {
namespace {

TEST(SibsonC1, AValueMovesWithoutAStepAsASampleNearsAHullEdge) {
  // A sample 2 m to 0.2 mm above the middle of a 40 m hull edge, in 2000 geometric steps: as it
  // nears the edge, the edge's ends take nearly all its Sibson coordinates and its fit's
  // conditioning falls through the threshold. The value at a query 1.3 m away, which weighs the
  // sample's gradient, should move by steps like its neighbours'. When the fits switched at the
  // threshold, one step jumped by 0.114 (at 1.3 cm above the edge); blended, the largest step is
  // 0.018 (far from the edge, where the sample moves most), on data of range about 10. A second
  // channel, a linear function, is reproduced at every step: both fits and so their blend are
  // planes through the sample's neighbours.
  auto f = [](const Vec2& p) { return std::sin(p.x() / 3) * std::cos(p.y() / 4) + 0.02 * p.x() * p.x(); };
  auto linear = [](const Vec2& p) { return 1 - 0.3 * p.x() + 0.7 * p.y(); };
  const Vec2 query(1.5, 0.8);
  double previous = NAN, largest_step = 0, step_at_m = 0;
  for (int step = 0; step <= 2000; ++step) {
    const double height_m = 2.0 * std::pow(1e-4, step / 2000.0);
    ScatteredSamples s;
    s.channels = 2;
    s.points = {Vec2(-20, 0), Vec2(20, 0), Vec2(-20, 12), Vec2(20, 12), Vec2(-6, 5), Vec2(7, 6), Vec2(0, 9),
                Vec2(0.4, height_m)};
    for (const Vec2& p : s.points) s.values.insert(s.values.end(), {f(p), linear(p)});
    std::vector<double> out(2);
    NaturalNeighbour(s, OutsideHull::none, {}, NeighbourRule::sibson_c1).evaluate(std::vector<Vec2>{query}, out);
    ASSERT_NEAR(out[1], linear(query), 1e-12) << "sample " << height_m << " m above the edge";
    if (step > 0 && std::abs(out[0] - previous) > largest_step) largest_step = std::abs(out[0] - previous), step_at_m = height_m;
    previous = out[0];
  }
  EXPECT_LT(largest_step, 0.03) << "a step of " << largest_step << " with the sample " << step_at_m << " m above the edge";
}

}  // namespace
}  // namespace radrecon
