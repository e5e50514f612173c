// A surface's (u, v) <-> point mapping, both ways.

#include <gtest/gtest.h>

#include <random>

#include "scene/scene.h"

#include "support/scenes.h"

namespace radrecon {
namespace {

/// A black quad (reflectance and emission 0).
Surface quad(const std::string& name, const Vec3& c0, const Vec3& c1, const Vec3& c2, const Vec3& c3) {
  return testing_support::quad(name, c0, c1, c2, c3, 0.0);
}

TEST(QuadParameters, InvertsTheBilinearMapOfAGeneralConvexQuad) {
  // A planar, convex, non-parallelogram quad in a tilted plane.
  const Vec3 o(0.3, -0.2, 1.0), a(1, 0.2, 0.5), b(-0.1, 1, 0.3);
  const Surface s = quad("q", o, o + 2.0 * a, o + 1.6 * a + 1.3 * b, o + 0.2 * a + 1.0 * b);
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> U(0, 1);
  for (int k = 0; k < 1000; ++k) {
    const double u = U(rng), v = U(rng);
    const auto uv = s.parameters(s.point(u, v));
    ASSERT_TRUE(uv.has_value());
    EXPECT_NEAR(uv->x(), u, 1e-10);
    EXPECT_NEAR(uv->y(), v, 1e-10);
  }
  EXPECT_FALSE(s.parameters(s.point(1.2, 0.5)).has_value());
  EXPECT_FALSE(s.parameters(s.point(0.5, -0.1)).has_value());
}

}  // namespace
}  // namespace radrecon
