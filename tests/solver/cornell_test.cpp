// The Cornell box solved by progressive refinement against an independent computation: the
// mean radiosity of its floor by Monte Carlo path tracing (tests/support/path_tracer.h), which
// shares no code with the solver (no mesh, no form factors, no clipping).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "mesh/grid_mesh.h"
#include "solver/progressive.h"
#include "support/path_tracer.h"
#include "support/side_mean.h"

namespace radrecon {
namespace cornell_test {

using testing_support::PathTracer;
using testing_support::side_mean;

/// Mesh: elements along the box's longest edge (0.56 m), so some 17 mm elements.
constexpr int kDivisions = 32;
/// Floor points for the path tracer, each one path (fixed seed): some 0.18% standard error (the
/// estimates of six other seeds spread by 0.26%; 40,000 paths at this seed landed 0.7% high).
constexpr int kPaths = 400000;
/// Light samples per axis at each floor point.
constexpr int kStrata = 2;

Solution solve_grid(const Scene& scene, int divisions) {
  return solve_progressive(scene, make_grid_mesh(scene, {divisions}), ProgressiveOptions{}, "grid");
}

/// Area-weighted mean radiosity (W/m^2 per channel) over the floor's elements, solved on grid:N.
Rgb solver_floor_mean(const Scene& scene, int divisions) { return side_mean(solve_grid(scene, divisions), "floor"); }

struct Estimate {
  Rgb mean, standard_error;
};

/// A side's mean radiosity by path tracing from `paths` uniformly random points of it (the front
/// side of a surface named `surface`).
Estimate path_traced_mean(const Scene& scene, const std::string& surface, int paths = kPaths) {
  const size_t index = *scene.find_surface(surface);
  const Surface& s = scene.surfaces[index];
  const PathTracer tracer(scene);
  std::mt19937_64 rng(20261123);
  std::uniform_real_distribution<double> U(0, 1);
  Rgb sum = Rgb::Zero(), sum_sq = Rgb::Zero();
  for (int k = 0; k < paths; ++k) {
    const double a = U(rng), b = U(rng);
    const Vec3 p = testing_support::uniform_point(s, a, b);
    const Rgb x = tracer.radiosity(p, s.normal(), index, kStrata, 1, rng);
    sum += x;
    sum_sq += x * x;
  }
  const Rgb mean = sum / paths;
  const Rgb variance = (sum_sq / paths - mean * mean) * (paths / (paths - 1.0));
  return {mean, (variance / paths).sqrt()};
}

/// Solves on grid:N and grid:N/2 and checks the grid:N floor mean against path tracing, within
/// 3 standard errors of the path tracer plus the mesh's discretisation error, bounded by the
/// change from grid:N/2 to grid:N (the error of grid:N is a fraction of that change for any
/// convergence order >= 1: for order p it is |change| / (2^p - 1)). The box's floor does not
/// converge that steadily: grid:32 sits 0.6% below both grid:16 and grid:64 (docs/cornell.md),
/// and its whole error, 0.6%, is within that change (0.7%).
void expect_floor_agrees(const Scene& scene) {
  const Rgb fine = solver_floor_mean(scene, kDivisions);
  const Rgb coarse = solver_floor_mean(scene, kDivisions / 2);
  const Estimate mc = path_traced_mean(scene, "floor");
  for (int c = 0; c < 3; ++c) {
    const double tolerance = 3 * mc.standard_error[c] + std::abs(fine[c] - coarse[c]);
    std::printf("%s channel %d: solver grid:%d %.4f (grid:%d %.4f), path tracing %.4f +- %.4f (%.2f%%), "
                "difference %.4f, tolerance %.4f W/m^2\n",
                scene.name.c_str(), c, kDivisions, fine[c], kDivisions / 2, coarse[c], mc.mean[c], mc.standard_error[c],
                100 * mc.standard_error[c] / mc.mean[c], fine[c] - mc.mean[c], tolerance);
    EXPECT_NEAR(fine[c], mc.mean[c], tolerance) << "channel " << c;
  }
}

/// The published box but with the red wall made planar (its corner (549.6, 0, 559.2) mm moved to
/// x = 552.8 mm, 3.2 mm: a parallelogram), so that every surface is a quad.
Scene planarised_cornell() {
  Scene scene = cornell_scene();
  scene.name = "cornell-planarised";
  std::vector<Surface> surfaces;
  for (const Surface& s : scene.surfaces) {
    if (s.name == "red_wall.b") continue;
    if (s.name != "red_wall.a") {
      surfaces.push_back(s);
      continue;
    }
    Surface red = s;
    red.name = "red_wall";
    red.corner_count = 4;
    red.corners = {Vec3(0.5528, 0, 0), Vec3(0.5528, 0, 0.5592), Vec3(0.556, 0.5488, 0.5592), Vec3(0.556, 0.5488, 0)};
    surfaces.push_back(red);
  }
  scene.surfaces = surfaces;
  validate_scene(scene, "cornell-planarised");
  return scene;
}

TEST(CornellBox, PlanarisedFloorMeanAgreesWithPathTracing) {
  const Scene scene = planarised_cornell();
  for (const Surface& s : scene.surfaces) ASSERT_FALSE(s.is_triangle()) << s.name;
  expect_floor_agrees(scene);
}

// The published box, its red wall two triangles. Written to be enabled when triangles mesh; they
// already do on main 89278cb, where it passes (the lead's rewrite of triangle meshing is what it
// checks: disable it with DISABLED_ only if that work is still in flight).
TEST(CornellBox, PublishedFloorMeanAgreesWithPathTracing) {
  const Scene scene = cornell_scene();
  ASSERT_TRUE(scene.surfaces[*scene.find_surface("red_wall.a")].is_triangle());
  expect_floor_agrees(scene);
}

/// Beyond the floor: the walls and the blocks' faces, each side's mean against path tracing from
/// its own points, within 3 standard errors plus the change from grid:16 to grid:32 (as the
/// floor's). The ceiling is left out: the solver's ceiling under the lamp is covered (dark),
/// which the path tracer's points on it do not know.
TEST(CornellBox, WallsAndBlocksAgreeWithPathTracing) {
  constexpr int kSidePaths = 150000;
  const Scene scene = cornell_scene();
  const Solution fine = solve_grid(scene, kDivisions), coarse = solve_grid(scene, kDivisions / 2);
  for (const char* side : {"back_wall", "green_wall", "short_top", "short_side_b", "tall_side_d"}) {
    const Rgb f = side_mean(fine, side), c = side_mean(coarse, side);
    const Estimate mc = path_traced_mean(scene, side, kSidePaths);
    for (int ch = 0; ch < 3; ++ch) {
      const double tolerance = 3 * mc.standard_error[ch] + std::abs(f[ch] - c[ch]);
      std::printf("%s channel %d: solver %.4f (grid:%d %.4f), path tracing %.4f +- %.4f, difference %+.2f%%, "
                  "tolerance %.2f%%\n", side, ch, f[ch], kDivisions / 2, c[ch], mc.mean[ch], mc.standard_error[ch],
                  100 * (f[ch] / mc.mean[ch] - 1), 100 * tolerance / mc.mean[ch]);
      EXPECT_NEAR(f[ch], mc.mean[ch], tolerance) << side << " channel " << ch;
    }
  }
}

/// The far field's bound (ProgressiveOptions::far_field_error) against a bound 20 times finer,
/// both converged to 1e-6, on every side of the published box but the light: each side's mean
/// relative difference over its elements (those above 1e-3 of its peak), and the largest.
/// Blocks that the strict bound lets shoot whole though an occluder hides part of them darken
/// the box by one sign (docs/method.md, the far field's bound): its ceiling by 0.14% on average
/// at the default bound (largest 0.28%), by 0.48% (largest 0.79%) without the quarter share
/// behind occluders (tol::kPartlyHiddenStrictShare), which this test tells apart.
TEST(CornellBox, SlowFarFieldBoundKeepsEverySideNearAFineSolve) {
  constexpr double kMeanRelative = 3e-3, kLargestRelative = 6e-3;
  const Scene scene = cornell_scene();
  const Mesh mesh = make_grid_mesh(scene, {kDivisions});
  const auto solve = [&](double far_field_error) {
    ProgressiveOptions options;
    options.residual = 1e-6;
    options.far_field_error = far_field_error;
    return solve_progressive(scene, mesh, options, "grid");
  };
  const Solution bounded = solve(kDefaultFarFieldError), fine = solve(1e-3);
  double worst_mean = 0, worst = 0;
  for (size_t s = 0; s < fine.surfaces.size(); ++s) {
    const SurfaceSolution& ref = fine.surfaces[s];
    if (ref.name == "light") continue;
    double peak = 0;
    for (const SolutionElement& e : ref.elements) peak = std::max(peak, e.radiosity_w_m2.sum());
    double sum = 0, largest = 0;
    int count = 0;
    for (size_t e = 0; e < ref.elements.size(); ++e) {
      const double b_ref = ref.elements[e].radiosity_w_m2.sum();
      if (b_ref <= 1e-3 * peak) continue;
      const double relative = (bounded.surfaces[s].elements[e].radiosity_w_m2.sum() - b_ref) / b_ref;
      sum += relative, largest = std::max(largest, std::abs(relative)), ++count;
    }
    ASSERT_GT(count, 0) << ref.name;
    const double mean = sum / count;
    EXPECT_LT(std::abs(mean), kMeanRelative) << ref.name;
    EXPECT_LT(largest, kLargestRelative) << ref.name;
    if (std::abs(mean) > std::abs(worst_mean)) worst_mean = mean;
    worst = std::max(worst, largest);
  }
  std::printf("the default bound against a 20 times finer one: worst side mean %+.2e, largest %.2e\n", worst_mean, worst);
}

/// The box closed by a front wall, its blocks standing on the floor: the power absorbed equals the
/// power emitted to the 1e-3 for a closed room. The floor under each block is enclosed by
/// its faces; an element across a block's foot gathered at its centre (nothing, under the block)
/// and reflected from its whole area, the part under the block into the block's inside: 0.73% of
/// the power was lost at grid:16, 0.47% at grid:32 (an outside-in trial); with the blocks lifted
/// 1 cm, bottoms added, 3e-5 (solver/enclosed.h).
TEST(CornellBox, ClosedWithItsBlocksStandingKeepsItsEnergy) {
  constexpr double kClosedRoomRelative = 1e-3;
  Scene scene = cornell_scene();
  Surface front;
  front.name = "front_wall";
  front.corners = {Vec3(0, 0, 0), Vec3(0.5528, 0, 0), Vec3(0.556, 0.5488, 0), Vec3(0, 0.5488, 0)};  // facing +z, in
  front.reflectance = Rgb::Constant(0.5);
  scene.surfaces.push_back(front);
  validate_scene(scene, "closed cornell");
  for (const int divisions : {16, 32}) {
    const SolveStats st = solve_grid(scene, divisions).stats;
    for (int c = 0; c < 3; ++c) {
      std::printf("grid:%d channel %d: escaped %+.2e of the emitted power\n", divisions, c, st.escaped_w[c] / st.emitted_w[c]);
      EXPECT_LT(std::abs(st.escaped_w[c]), kClosedRoomRelative * st.emitted_w[c]) << "grid:" << divisions << " channel " << c;
    }
  }
}

}  // namespace cornell_test
}  // namespace radrecon
