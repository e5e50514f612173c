// Scattered samples as the nodes of a regular grid (reconstruct/sample_set.h as_regular_grid()):
// rounding within the tolerance, a centimetre grid at UTM coordinates, and the grids that are
// not, with the refusal's words.

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "reconstruct/methods.h"
#include "reconstruct/sample_set.h"

namespace radrecon {
namespace regular_grid_test {

TEST(RegularGrid, GridDetectionToleratesRoundingWithinTolerance) {
  ScatteredSamples s;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 4; ++i) {
      s.points.emplace_back(i / 3.0 * (1 + (j ? 1e-13 : 0)), j * 0.1);
      s.values.push_back(i + 4 * j);
    }
  const std::optional<GridNodes> g = as_regular_grid(s);
  ASSERT_TRUE(g.has_value());
  EXPECT_EQ(g->nx, 4);
  EXPECT_EQ(g->ny, 2);
}

TEST(RegularGrid, AGridOfCentimetresAtAUtmNorthingIsAGridAndAStrayOfAMicronIsNot) {
  // 11 x 11 nodes 1 cm apart at x = 500000 m, y = 5000000 m, as the decimals 5000000.03 etc.
  // read: 1 ulp (9.3e-10 m, 9.3e-9 of the 0.1 m extent) off the lines, which the extent's
  // 1e-9 alone refused (an outside-in trial). Bilinear then reproduces a linear function; a
  // node 1 micron off (1e-5 of the extent, 1000 ulps) is still no grid, and the message gives
  // the tolerance used.
  const auto utm_grid = [](double stray_m) {
    ScatteredSamples s;
    for (int j = 0; j <= 10; ++j)
      for (int i = 0; i <= 10; ++i) {
        char text[64];
        std::snprintf(text, sizeof text, "%.2f %.2f", 500000 + i / 100.0, 5000000 + j / 100.0);
        char* end = nullptr;
        const double x = std::strtod(text, &end), y = std::strtod(end, nullptr) + (i == 3 && j == 7 ? stray_m : 0);
        s.points.emplace_back(x, y);
        s.values.push_back(2 * (x - 500000) - 3 * (y - 5000000));
      }
    return s;
  };
  const ScatteredSamples s = utm_grid(0);
  const std::optional<GridNodes> g = as_regular_grid(s);
  ASSERT_TRUE(g.has_value());
  EXPECT_EQ(g->nx, 11);
  EXPECT_EQ(g->ny, 11);
  const InterpolantResult bilinear = make_point_interpolant(Method::bilinear, s, {});
  ASSERT_TRUE(bilinear) << bilinear.reason();
  const Vec2 q(500000.0437, 5000000.0612);
  double v = 0;
  bilinear.value()->evaluate(std::span(&q, 1), std::span(&v, 1));
  EXPECT_NEAR(v, 2 * 0.0437 - 3 * 0.0612, 1e-8);  // the query's own rounding at 5e6: 1e-9 m
  const InterpolantResult stray = make_point_interpolant(Method::bilinear, utm_grid(1e-6), {});
  ASSERT_FALSE(stray);
  // 64 ulps at 5e6 m: 7.1e-8 m, 7.1e-7 of the extent.
  EXPECT_NE(stray.reason().find("11 distinct x, 12 distinct y; the y values are unevenly spaced"), std::string::npos)
      << stray.reason();
  EXPECT_NE(stray.reason().find("beyond the tolerance of 7.1e-07"), std::string::npos)
      << stray.reason();
}

TEST(RegularGrid, RejectsIncompleteOrUnevenGrids) {
  const auto grid = [](const std::vector<double>& xs, const std::vector<double>& ys) {
    ScatteredSamples s;
    for (double y : ys)
      for (double x : xs) {
        s.points.emplace_back(x, y);
        s.values.push_back(x + y);
      }
    return s;
  };
  ScatteredSamples full = grid({0, 1, 2, 3}, {0, 1, 2});
  ASSERT_TRUE(as_regular_grid(full).has_value());

  ScatteredSamples missing = full;  // one point missing
  missing.points.erase(missing.points.begin() + 5);
  missing.values.erase(missing.values.begin() + 5);
  EXPECT_FALSE(as_regular_grid(missing).has_value());

  ScatteredSamples replaced = full;  // right count, one point moved off the grid
  replaced.points[5] = Vec2(1.5, 1);
  EXPECT_FALSE(as_regular_grid(replaced).has_value());

  EXPECT_FALSE(as_regular_grid(grid({0, 1, 2.5, 3}, {0, 1, 2})).has_value());  // uneven x
  EXPECT_FALSE(as_regular_grid(grid({0, 1, 2, 3}, {0, 1, 3})).has_value());    // uneven y
  EXPECT_FALSE(as_regular_grid(grid({0, 1, 2, 3}, {0.5})).has_value());        // one row
  EXPECT_FALSE(as_regular_grid(grid({0, 1, 2, 3}, {0, 1, 2 + 1e-6})).has_value());

  const DistinctCoordinates d = count_distinct_coordinates(missing);
  EXPECT_EQ(d.x, 4u);
  EXPECT_EQ(d.y, 3u);
  // How uneven: y = 0, 1, 3 has 1 (the middle one's place is 1.5) of its extent 3 off, a half.
  const DistinctCoordinates uneven = count_distinct_coordinates(grid({0, 1, 2, 3}, {0, 1, 3}));
  EXPECT_EQ(uneven.x_uneven, 0.0);
  EXPECT_NEAR(uneven.y_uneven, 0.5 / 3, 1e-15);
  // The message says so: 32-bit coordinates 0, 0.1, 0.2, 0.3 (0.2f lies 1.66e-8 of the extent
  // 0.3f from its place, two thirds of it) looked like a whole grid of the wrong kind.
  const InterpolantResult r =
      make_point_interpolant(Method::bilinear, grid({0, 1, 2}, {0, double(0.1f), double(0.2f), double(0.3f)}), {});
  ASSERT_FALSE(r);
  EXPECT_NE(r.reason().find("12 samples, 3 distinct x, 4 distinct y; the y values are unevenly spaced: one lies 1.7e-08 of "
                            "their extent from its equally spaced place, beyond the tolerance of 1e-09"),
            std::string::npos)
      << r.reason();
}

}  // namespace regular_grid_test
}  // namespace radrecon
