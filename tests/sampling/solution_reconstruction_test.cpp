// A side's reconstruction with the scene's structure: a box standing on a floor gives the floor
// four barriers and one excluded square; the square is neither sample nor query.

#include <gtest/gtest.h>

#include <cmath>

#include "sampling/solution_reconstruction.h"
#include "sampling/surface_samples.h"
#include "solver/solve.h"
#include "support/scenes.h"

namespace radrecon {
namespace {

using testing_support::quad;

/// A 4 m floor under a light, with a unit box standing on it over [1, 2] x [1, 2] (walls facing
/// out, and a top).
Scene box_on_floor() {
  Scene s;
  s.name = "box on floor";
  s.surfaces.push_back(quad("floor", {0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}, 0.5));
  s.surfaces.push_back(quad("light", {1, 1, 3}, {1, 3, 3}, {3, 3, 3}, {3, 1, 3}, 0, 10));
  s.surfaces.push_back(quad("x0", {1, 1, 0}, {1, 1, 1}, {1, 2, 1}, {1, 2, 0}, 0.5));
  s.surfaces.push_back(quad("x1", {2, 1, 0}, {2, 2, 0}, {2, 2, 1}, {2, 1, 1}, 0.5));
  s.surfaces.push_back(quad("y0", {1, 1, 0}, {2, 1, 0}, {2, 1, 1}, {1, 1, 1}, 0.5));
  s.surfaces.push_back(quad("y1", {1, 2, 0}, {1, 2, 1}, {2, 2, 1}, {2, 2, 0}, 0.5));
  s.surfaces.push_back(quad("top", {1, 1, 1}, {2, 1, 1}, {2, 2, 1}, {1, 2, 1}, 0.5));
  for (Surface& f : s.surfaces) f.max_divisions = 8;
  s.surfaces[0].max_divisions = 16;
  return s;
}

double at(const Interpolant& f, const Vec2& q) {
  std::vector<double> v(static_cast<size_t>(f.channels()));
  f.evaluate(std::span(&q, 1), v);
  return v[0];
}

TEST(SideReconstruction, TheFloorUnderABoxIsNeitherSampleNorQuery) {
  const Scene scene = box_on_floor();
  SolveSettings settings;
  const Solution solution = solve_scene(scene, "grid:16", settings, "test");
  const SurfaceSolution& floor = require_surface(solution, "floor", "test");
  ASSERT_EQ(floor.barriers.size(), 4u);
  ASSERT_EQ(floor.excluded.size(), 1u);
  // The same solution with the cells under the box made very bright: nothing outside may change.
  SurfaceSolution bright = floor;
  for (SolutionElement& e : bright.elements) {
    const Vec2 c((e.u0 + e.u1) * 2, (e.v0 + e.v1) * 2);  // centre, metres (4 m floor)
    if (c.x() > 1 && c.x() < 2 && c.y() > 1 && c.y() < 2) e.radiosity_w_m2 = Rgb::Constant(1e3);
  }
  const std::vector<Vec2> outside = {{0.9, 1.5}, {2.05, 1.2}, {1.5, 0.8}, {1.5, 2.3}, {0.5, 0.5}, {3, 3}};
  for (const bool barriers : {true, false})  // render --no-barriers too: the region still holds
  for (Method m : all_methods()) {
    SCOPED_TRACE(method_name(m) + (barriers ? " with barriers" : " without barriers"));
    const SideSampling sampling{.barriers = barriers};
    const auto plain = reconstruct_side(floor, m, {}, sampling);
    const auto lit = reconstruct_side(bright, m, {}, sampling);
    ASSERT_TRUE(plain.ok()) << plain.reason();
    EXPECT_TRUE(std::isnan(at(*plain.value(), {1.5, 1.5})));  // under the box: no value
    if (m == Method::bicubic) continue;  // its global spline couples distant nodes (barrier_grid.h)
    for (const Vec2& q : outside) EXPECT_EQ(at(*plain.value(), q), at(*lit.value(), q)) << q.transpose();
  }
}

}  // namespace
}  // namespace radrecon
