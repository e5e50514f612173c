#pragma once
// The mesh import tests' checks: a surface found by name, vectors and colours within the
// precision a model file keeps, and the area of a list of surfaces.

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace radrecon::testing_support {

// The files hold decimal numbers of a few digits; single-precision storage (assimp keeps
// positions and colours as float) rounds them to some 6e-8 relative.
inline constexpr double kFloat = 1e-6;

inline const Surface& named(const std::vector<Surface>& surfaces, const std::string& name) {
  const auto it = std::find_if(surfaces.begin(), surfaces.end(), [&](const Surface& s) { return s.name == name; });
  if (it == surfaces.end()) {
    std::string names;
    for (const Surface& s : surfaces) names += " " + s.name;
    ADD_FAILURE() << "no surface '" << name << "' among" << names;
    static const Surface none;
    return none;
  }
  return *it;
}

inline void expect_near(const Vec3& got, const Vec3& want) {
  EXPECT_LT((got - want).norm(), kFloat) << got.transpose() << " vs " << want.transpose();
}
inline void expect_near(const Rgb& got, const Rgb& want) {
  EXPECT_LT((got - want).abs().maxCoeff(), kFloat) << got.transpose() << " vs " << want.transpose();
}

inline double total_area(const std::vector<Surface>& surfaces) {
  return std::accumulate(surfaces.begin(), surfaces.end(), 0.0, [](double a, const Surface& s) { return a + s.area_m2(); });
}

}  // namespace radrecon::testing_support
