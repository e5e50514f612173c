// Progressive refinement against closed forms: direct light on an open floor, a closed box,
// energy balance, and independence from the number of threads.

#include <gtest/gtest.h>

#include <cstdio>

#include "mesh/grid_mesh.h"
#include "support/closed_forms.h"
#include "support/ray_scene.h"
#include "support/scenes.h"
#include "support/threads.h"
#include "solver/closed_room.h"
#include "solver/progressive.h"

namespace radrecon {
namespace progressive_test {

using testing_support::quad;

/// The bound for direct radiosity against the closed form.
constexpr double kDirectRelative = 1e-3;
/// Energy bookkeeping is exact up to round-off in sums of ~10^3..10^5 terms.
constexpr double kBalanceRelative = 1e-9;
/// The bound for a closed room: the power absorbed equals the power emitted to 1e-3.
constexpr double kClosedRoomRelative = 1e-3;
/// The midpoint rule's error on a closed room's mean radiosity from 0.25 m elements' centres.
constexpr double kMidpointRelative = 5e-3;


/// Closed-form F from a floor point to the light [x0,x1] x [y0,y1] at height h.
double floor_to_light(double x, double y, double x0, double y0, double x1, double y1, double h) {
  return testing_support::floor_to_rectangle(x, y, x0, y0, x1, y1, h);
}

Solution solve(const Scene& scene, int divisions, double residual = 1e-6, size_t max_shots = 0,
               double far_field_error = kDefaultFarFieldError) {
  ProgressiveOptions po;
  po.residual = residual;
  po.max_shots = max_shots;
  po.far_field_error = far_field_error;
  return solve_progressive(scene, make_grid_mesh(scene, {divisions}), po, "grid:" + std::to_string(divisions));
}

TEST(Progressive, OpenFloorUnderRectangularLightMatchesClosedForm) {
  Scene scene;
  scene.name = "floor";
  scene.surfaces.push_back(quad("floor", {0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}, 0.5));
  scene.surfaces.push_back(quad("light", {1, 1, 2.5}, {1, 2, 2.5}, {2, 2, 2.5}, {2, 1, 2.5}, 0.0, 40.0));
  const Solution sol = solve(scene, 40);
  const SurfaceSolution* floor = sol.find("floor");
  ASSERT_NE(floor, nullptr);
  for (const SolutionElement& e : floor->elements) {
    const double expected = 0.5 * 40.0 * floor_to_light(e.center.x(), e.center.y(), 1, 1, 2, 2, 2.5);
    ASSERT_NEAR(e.radiosity_w_m2[0], expected, kDirectRelative * expected) << "at " << e.center.transpose();
  }
  // Peak under the light's centre: the design brief's "about 1.93 W/m^2" irradiance.
  EXPECT_NEAR(40.0 * floor_to_light(1.5, 1.5, 1, 1, 2, 2, 2.5), 1.93, 0.01);
  for (const SolutionElement& e : sol.find("light")->elements) EXPECT_EQ(e.radiosity_w_m2[0], 40.0);
}

TEST(Progressive, PaperSceneDirectLightMatchesClosedFormAndUmbraIsDark) {
  // One shot: only the light has shot, so the ground holds direct radiosity alone.
  const Scene scene = paper_scene();
  const Solution sol = solve(scene, 400, 1e-4, 1);
  ASSERT_EQ(sol.stats.shots, 1u);
  const SurfaceSolution* ground = sol.find("ground");
  size_t checked = 0;
  for (const SolutionElement& e : ground->elements) {
    const Vec3& c = e.center;
    if (c.x() < 2.6 && c.y() < 2.6) {  // inside the L: no wall can hide the light
      const double expected = 0.5 * 40.0 * floor_to_light(c.x(), c.y(), 1, 1, 2, 2, 2.5);
      ASSERT_NEAR(e.radiosity_w_m2[0], expected, kDirectRelative * expected) << "at " << c.transpose();
      ++checked;
    }
    // Behind wall1 at x in [2.9, 3.0] and y in [1.4, 1.6] every ray to the light crosses the wall.
    if (c.x() > 2.9 && c.x() < 3.0 && c.y() > 1.4 && c.y() < 1.6) {
      EXPECT_EQ(e.radiosity_w_m2[0], 0.0);
    }
  }
  EXPECT_EQ(checked, 260u * 260u);
}

TEST(Progressive, PaperScenePenumbraeMatchBruteForcePointByPoint) {
  // Behind the walls, where part of the light is hidden: after the light's one shot each ground
  // element's radiosity is rho E F(centre -> visible light), checked against the ray caster's
  // midpoint rule (tests/support/ray_scene.h: no code shared with the exact clipping). The
  // rule's error is at most the weight of the cells a shadow's edge cuts: an edge crosses at most
  // 2 n of the n x n cells, each at most 1.5 F / n^2 (the kernel varies by less than 1.5 over
  // the light from here), so 3 F / n of the unoccluded F.
  constexpr int kSide = 512;
  constexpr double kBruteForceShare = 3.0 / kSide;
  const Scene scene = paper_scene();
  const Solution sol = solve(scene, 100, 1e-4, 1);
  ASSERT_EQ(sol.stats.shots, 1u);
  const SurfaceSolution* ground = sol.find("ground");
  size_t behind = 0, checked = 0, partly = 0;
  for (const SolutionElement& e : ground->elements) {
    const Vec3& c = e.center;
    if (c.x() < 2.6 && c.y() < 2.6) continue;  // inside the L: the closed form's test above
    if (behind++ % 97 != 0) continue;         // some 60 points spread over the region behind
    const double unoccluded = 0.5 * 40.0 * floor_to_light(c.x(), c.y(), 1, 1, 2, 2, 2.5);
    const double expected =
        0.5 * 40.0 * testing_support::brute_force_form_factor(scene, 1, c, Vec3(0, 0, 1), 0, kSide);
    EXPECT_NEAR(e.radiosity_w_m2[0], expected, kDirectRelative * expected + kBruteForceShare * unoccluded)
        << "at " << c.transpose() << " (unoccluded " << unoccluded << ")";
    ++checked;
    if (expected > 0.05 * unoccluded && expected < 0.95 * unoccluded) ++partly;
  }
  EXPECT_GE(checked, 50u);
  EXPECT_GE(partly, 15u);  // the points are in penumbrae, not only in full light or umbra
}

TEST(Progressive, EnergyBalanceHolds) {
  const Solution sol = solve(paper_scene(), 16, 1e-4);
  const SolveStats& s = sol.stats;
  for (int c = 0; c < 3; ++c) {
    const double sum = s.absorbed_w[c] + s.unshot_w[c] + s.escaped_w[c];
    EXPECT_NEAR(sum, s.emitted_w[c], kBalanceRelative * s.emitted_w[c]);
  }
  EXPECT_DOUBLE_EQ(s.emitted_w[0], 40.0);  // 1 m^2 at 40 W/m^2
  EXPECT_LT(s.residual, 1e-4);
  // Absorbed power seen from the solution alone: (1 - rho) / rho * (B - E) * A on reflecting sides.
  double absorbed_by_reflectors = 0;
  for (const SurfaceSolution& surf : sol.surfaces)
    if (surf.scene_surface != "light")
      for (const SolutionElement& e : surf.elements) absorbed_by_reflectors += e.area_m2 * e.radiosity_w_m2[0];
  // rho = 0.5 everywhere but the light: absorbed = B * A. The light (black) absorbs the rest.
  EXPECT_LT(absorbed_by_reflectors, s.absorbed_w[0]);
  EXPECT_GT(absorbed_by_reflectors, 0.9 * s.absorbed_w[0]);
}

TEST(Progressive, ClosedBoxRadiosityPowerIsEmittedOverOneMinusReflectance) {
  // Every face of a closed unit box has reflectance rho; the top emits. Light can only be
  // absorbed, so sum(A B) = Phi / (1 - rho), and nothing escapes if the form factors close.
  const double rho = 0.6, E = 10.0;
  const Scene box = testing_support::closed_box(rho, E);
  for (const Surface& s : box.surfaces) ASSERT_GT(s.normal().dot(Vec3(0.5, 0.5, 0.5) - s.corners[0]), 0) << s.name;
  const Solution sol = solve(box, 12, 1e-7);
  double power = 0;
  for (const SurfaceSolution& s : sol.surfaces)
    for (const SolutionElement& e : s.elements) power += e.area_m2 * e.radiosity_w_m2[0];
  const double phi = E * 1.0;
  // The 1e-3 for a closed room (measured: 1.1e-5 of the power, escaped -1.8e-5 of Phi):
  // a gain of 0.2% of each shot's power, as before the Gauss rule near the shooter, fails it.
  EXPECT_NEAR(power, phi / (1 - rho), kClosedRoomRelative * phi / (1 - rho));
  EXPECT_LT(std::abs(sol.stats.escaped_w[0]), kClosedRoomRelative * phi);
  EXPECT_NEAR(sol.stats.absorbed_w[0], phi, kClosedRoomRelative * phi);
  EXPECT_TRUE(sol.stats.converged);
  EXPECT_LT(sol.stats.residual, 1e-7);
}

// Issue 11 item 5: before the Gauss rule near the shooter and the corrected far field
// (solver/progressive.cpp gather()), progressive refinement gained 0.2% of the shot power per
// bounce here (absorbed 20.04 W of 20 at rho 0.5).
TEST(Progressive, SlowClosedRoomKeepsItsEnergyAndMatchesTheClosedFormMeanIrradiance) {
  // In a closed room of uniform reflectance every watt emitted is absorbed: (1 - rho) sum A H =
  // Phi, so the mean irradiance is E = Phi / ((1 - rho) A) = Phi / A + rho Phi / ((1 - rho) A),
  // and the mean radiosity is B = Phi / ((1 - rho) A) (B = E_emitted + rho H, summed over A).
  const double E = 40, phi = E * testing_support::kClosedRoomLight_m2, area = testing_support::kClosedRoomArea_m2;
  for (const double rho : {0.5, 0.95}) {
    const Scene room = testing_support::closed_room(rho, E);
    for (const Surface& s : room.surfaces) ASSERT_GT(s.normal().dot(Vec3(1.5, 1.25, 1) - s.corners[0]), 0) << s.name;
    const Solution sol = solve(room, 12, 1e-5);
    ASSERT_TRUE(sol.stats.converged);
    const SolveStats& st = sol.stats;
    EXPECT_EQ(st.emitted_w[0], phi);
    // The bound: absorbed = emitted to 1e-3 (the unshot 1e-5 still to be absorbed).
    EXPECT_NEAR(st.absorbed_w[0], phi, kClosedRoomRelative * phi) << "rho = " << rho;
    EXPECT_LT(std::abs(st.escaped_w[0]), kClosedRoomRelative * phi) << "rho = " << rho;
    // The solver's mean irradiance, sum A H / A with H each element's mean irradiance, is
    // absorbed / ((1 - rho) A) (uniform rho): the closed form, to the 1e-3.
    const double mean_irradiance = phi / ((1 - rho) * area);
    EXPECT_NEAR(mean_irradiance, phi / area + rho * phi / ((1 - rho) * area), 1e-12 * mean_irradiance);
    const double solver_irradiance = st.absorbed_w[0] / ((1 - rho) * area);
    EXPECT_NEAR(solver_irradiance, mean_irradiance, kClosedRoomRelative * mean_irradiance) << "rho = " << rho;
    // The radiosities are the values at the elements' centres: their area-weighted sum is the
    // midpoint rule's estimate of the mean radiosity B = Phi / ((1 - rho) A), within its
    // O(size^2) error (measured +1.6e-3 at rho 0.5 on these 0.25 m elements).
    double radiosity_power = 0, total_area = 0;
    for (const SurfaceSolution& s : sol.surfaces)
      for (const SolutionElement& e : s.elements) {
        radiosity_power += e.area_m2 * e.radiosity_w_m2[0];
        total_area += e.area_m2;
      }
    EXPECT_NEAR(total_area, area, 1e-12 * area);
    const double mean_radiosity = phi / ((1 - rho) * area);
    EXPECT_NEAR(radiosity_power / area, mean_radiosity, kMidpointRelative * mean_radiosity) << "rho = " << rho;
    std::printf("closed room, rho %.2f: absorbed / emitted - 1 = %.2e, mean irradiance / closed form - 1 = %.2e, "
                "centre radiosities' mean / closed form - 1 = %.2e\n",
                rho, st.absorbed_w[0] / phi - 1, solver_irradiance / mean_irradiance - 1,
                radiosity_power / area / mean_radiosity - 1);
  }
}

TEST(Progressive, ALightLyingOnTheCeilingKeepsTheRoomsEnergy) {
  // The closed room with a lamp lying on its ceiling: the ceiling's part under it neither absorbs
  // nor reflects (docs/method.md, "Covered parts"); else both it and the lamp receive the light
  // the floor sends up, and the room gains power (+1.7% at reflectance 0.5, +35% at 0.95).
  // Absorbed = emitted to the 1e-3, as the tiled room's closed form demands.
  const double E = 40, phi = E * testing_support::kClosedRoomLight_m2;
  for (const double rho : {0.5, 0.95}) {
    const Solution sol = solve(testing_support::closed_room_with_lamp(rho, E), 12, 1e-5);
    ASSERT_TRUE(sol.stats.converged);
    EXPECT_NEAR(sol.stats.absorbed_w[0], phi, kClosedRoomRelative * phi) << "rho = " << rho;
    EXPECT_LT(std::abs(sol.stats.escaped_w[0]), kClosedRoomRelative * phi) << "rho = " << rho;
    std::printf("light lying on the ceiling, rho %.2f: absorbed / emitted - 1 = %.2e\n", rho,
                sol.stats.absorbed_w[0] / phi - 1);
  }
}

TEST(Progressive, ShotLimitIsReportedNotConverged) {
  const Scene box = testing_support::closed_box(0.6, 10.0);
  const Mesh mesh = make_grid_mesh(box, GridMeshOptions{8, 2});
  ProgressiveOptions options;
  options.residual = 1e-9;
  options.max_shots = 5;
  const Solution sol = solve_progressive(box, mesh, options, "grid:8");
  EXPECT_EQ(sol.stats.shots, 5u);
  EXPECT_FALSE(sol.stats.converged);
  EXPECT_GT(sol.stats.residual, options.residual);
}

TEST(Progressive, BlockViewsKeptFromShotToShotGiveTheSameValues) {
  // A floor under a ceiling, a lattice of 100 small squares between them: the ceiling's elements
  // see dozens of shadows on each of the floor's patches, which shoot again and again (the light
  // on the ceiling, the two reflecting). What they saw of a patch's blocks at its last shot
  // (solver/gather.h BlockView) must give what finding the shadows again gives: the same bits,
  // but for a block first seen in a later shot, whose form factors come without the patch's
  // fragments (the same to round-off).
  Scene scene;
  scene.name = "lattice";
  scene.surfaces.push_back(quad("floor", {0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}, 0.6));
  scene.surfaces.push_back(quad("ceiling", {0, 0, 2}, {0, 4, 2}, {4, 4, 2}, {4, 0, 2}, 0.6));
  scene.surfaces.push_back(quad("light", {1.5, 1.5, 1.9}, {1.5, 2.5, 1.9}, {2.5, 2.5, 1.9}, {2.5, 1.5, 1.9}, 0.0, 40.0));
  for (int j = 0; j < 10; ++j)
    for (int i = 0; i < 10; ++i) {
      const double x = 0.25 + 0.35 * i, y = 0.25 + 0.35 * j;
      scene.surfaces.push_back(quad("slat" + std::to_string(10 * j + i), {x, y, 1}, {x + 0.2, y, 1}, {x + 0.2, y + 0.2, 1},
                                    {x, y + 0.2, 1}, 0.3));
    }
  ProgressiveOptions kept, found;
  kept.residual = found.residual = 1e-3;
  found.keep_block_views = false;
  const Mesh mesh = make_grid_mesh(scene, {16, 2});
  const Solution a = solve_progressive(scene, mesh, kept, "grid:16"), b = solve_progressive(scene, mesh, found, "grid:16");
  ASSERT_GT(a.stats.shots, 10u);
  EXPECT_EQ(a.stats.shots, b.stats.shots);
  for (size_t s = 0; s < a.surfaces.size(); ++s)
    for (size_t e = 0; e < a.surfaces[s].elements.size(); ++e)
      ASSERT_NEAR(a.surfaces[s].elements[e].radiosity_w_m2[0], b.surfaces[s].elements[e].radiosity_w_m2[0],
                  1e-12 * b.surfaces[s].elements[e].radiosity_w_m2[0])
          << a.surfaces[s].name << " element " << e;
  EXPECT_NEAR(a.stats.escaped_w[0], b.stats.escaped_w[0], 1e-12 * b.stats.escaped_w[0]);
  // And with the views kept, the same bits on one thread as on several.
  const auto [one, many] =
      testing_support::solved_on_one_and_many_threads([&] { return solve_progressive(scene, mesh, kept, "grid:16"); });
  testing_support::expect_same_bits(one, many);
}

TEST(Progressive, ResultDoesNotDependOnThreadCount) {
  const Scene scene = paper_scene();
  for (const double far_field_error : {0.0, 1e-2}) {
    const auto [one, many] = testing_support::solved_on_one_and_many_threads(
        [&] { return solve(scene, 32, 1e-4, 0, far_field_error); });
    testing_support::expect_same_bits(one, many);
  }
}

/// Issue 13's targets for the far field with an error bound: the walls' radiosity within 0.5% of
/// a fine solve's everywhere (their back sides included), the umbra on the ground within 2%.
constexpr double kWallRelative = 5e-3, kUmbraRelative = 2e-2;

TEST(Progressive, SlowFarFieldErrorBoundKeepsWallsAndUmbraNearAFineSolve) {
  // The paper scene at grid:64, against the same solve with a bound 200 times finer. The distance
  // rule (far_field_error 0) is shown to miss the walls' target: the test tells the two apart.
  // Converged to 1e-6: at 1e-4 the umbra is still some 6% from its converged value, by an amount
  // that depends on the order in which the two mirror-image walls happen to shoot.
  const Scene scene = paper_scene();
  const Solution fine = solve(scene, 64, 1e-6, 0, 1e-4);
  const Solution bounded = solve(scene, 64, 1e-6, 0, kDefaultFarFieldError);
  const Solution distance_rule = solve(scene, 64, 1e-6, 0, 0.0);
  const auto worst = [&](const Solution& sol, bool walls) {
    double out = 0;
    for (size_t s = 0; s < fine.surfaces.size(); ++s) {
      const SurfaceSolution& ref = fine.surfaces[s];
      if (ref.name == "light" || (ref.name == "ground") == walls) continue;
      double peak = 0;
      for (const SolutionElement& e : ref.elements) peak = std::max(peak, e.radiosity_w_m2[0]);
      for (size_t e = 0; e < ref.elements.size(); ++e) {
        const double b_ref = ref.elements[e].radiosity_w_m2[0];
        // Walls: every element that gets light; ground: the umbra (below 15% of the peak).
        if (walls ? b_ref <= 1e-3 * peak : b_ref >= 0.15 * peak || b_ref <= 0) continue;
        out = std::max(out, std::abs(sol.surfaces[s].elements[e].radiosity_w_m2[0] - b_ref) / b_ref);
      }
    }
    return out;
  };
  std::printf("largest relative difference from the fine solve: walls %.2e (distance rule %.2e), umbra %.2e "
              "(distance rule %.2e)\n",
              worst(bounded, true), worst(distance_rule, true), worst(bounded, false), worst(distance_rule, false));
  EXPECT_LT(worst(bounded, true), kWallRelative);
  EXPECT_LT(worst(bounded, false), kUmbraRelative);
  EXPECT_GT(worst(distance_rule, true), kWallRelative);
}

}  // namespace progressive_test
}  // namespace radrecon
