#pragma once
// The area-weighted mean radiosity of one side of a solution, shared by the solver tests.

#include <gtest/gtest.h>

#include <string>

#include "solver/solution.h"

namespace radrecon::testing_support {

/// Area-weighted mean radiosity (W/m^2 per channel) over a side's elements.
inline Rgb side_mean(const Solution& solution, const std::string& side) {
  const SurfaceSolution* s = solution.find(side);
  EXPECT_NE(s, nullptr) << side;
  if (s == nullptr) return Rgb::Zero();
  Rgb sum = Rgb::Zero();
  double area = 0;
  for (const SolutionElement& e : s->elements) sum += e.area_m2 * e.radiosity_w_m2, area += e.area_m2;
  return sum / area;
}

}  // namespace radrecon::testing_support
