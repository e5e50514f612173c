// Hierarchical radiosity: the quadtree's structure, exact leaf counts, a closed box, determinism.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/thread_pool.h"
#include "core/error.h"
#include "solver/hierarchical.h"
#include "solver/solve.h"
#include "support/closed_forms.h"
#include "support/scenes.h"
#include "support/side_mean.h"
#include "solver/closed_room.h"

namespace radrecon {
namespace hierarchical_test {

using testing_support::quad;
using testing_support::side_mean;

Solution paper_leaves(int leaves) {
  return solve_hierarchical_leaves(paper_scene(), "ground", leaves, HierarchicalOptions{}, "test");
}

TEST(Hierarchical, LeavesTileTheGroundWithDyadicSquares) {
  const Solution sol = paper_leaves(286);
  const SurfaceSolution* ground = sol.find("ground");
  ASSERT_NE(ground, nullptr);
  ASSERT_EQ(ground->elements.size(), 286u);
  ASSERT_EQ(ground->grid_nu, 0);
  double area = 0;
  for (const SolutionElement& e : ground->elements) {
    area += e.area_m2;
    const double size = e.u1 - e.u0;
    EXPECT_EQ(size, e.v1 - e.v0) << "a quadtree leaf is a square in (u,v)";
    const double level = -std::log2(size);
    EXPECT_EQ(level, std::round(level)) << "leaf size " << size << " is not a power of 1/2";
    EXPECT_EQ(e.u0 / size, std::round(e.u0 / size)) << "leaf not aligned to its level";
    EXPECT_EQ(e.v0 / size, std::round(e.v0 / size));
  }
  EXPECT_NEAR(area, 16.0, 1e-12);
  // No overlap and no gap: every point of a fine grid lies in exactly one leaf.
  for (int j = 0; j < 256; ++j)
    for (int i = 0; i < 256; ++i) {
      const double u = (i + 0.5) / 256, v = (j + 0.5) / 256;
      int inside = 0;
      for (const SolutionElement& e : ground->elements) inside += u >= e.u0 && u < e.u1 && v >= e.v0 && v < e.v1;
      ASSERT_EQ(inside, 1) << "at u=" << u << " v=" << v;
    }
}

TEST(Hierarchical, QuadtreeLeavesGivesExactlyThatManyLeaves) {
  for (int leaves : {100, 286, 1000}) EXPECT_EQ(leaf_count(paper_leaves(leaves), "ground"), static_cast<size_t>(leaves));
}

TEST(Hierarchical, RefusesImpossibleLeafCounts) {
  EXPECT_THROW(paper_leaves(287), UserError);   // not 1 + 3k
  EXPECT_THROW(paper_leaves(0), UserError);
  EXPECT_THROW(paper_leaves(1000000), UserError);  // beyond the minimum element size
  // All of the ground's 256 x 256 at the minimum element size, or nearly: reached only as epsilon
  // goes to 0 (a search crept for minutes), so refused at once, with the count within reach.
  for (const int leaves : {65536, 64882}) {
    try {
      paper_leaves(leaves);
      ADD_FAILURE() << leaves << " leaves accepted";
    } catch (const UserError& e) {
      EXPECT_NE(std::string(e.what()).find("allows at most 65536"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("ask for at most 64879"), std::string::npos) << e.what();
    }
  }
}

TEST(Hierarchical, ASmallTrianglesLeafCountsAreReachedAndABlackSideIsRefusedAtOnce) {
  // A tilted triangle in a closed box with a black lamp: its leaf count rests at 16 over a
  // decade of epsilon before it grows on; every 1 + 3k count is still reached (19 to 28 had
  // been refused as "refinement stops at 16"). The black lamp is never split: refused at once.
  Scene box = testing_support::closed_box(0.5, 0.0);
  box.surfaces.push_back(testing_support::quad("lamp", {0.4, 0.4, 0.999}, {0.4, 0.6, 0.999}, {0.6, 0.6, 0.999},
                                               {0.6, 0.4, 0.999}, 0.0, 40.0));
  Surface tri = box.surfaces[0];
  tri.name = "tri";
  tri.set_triangle({0.7, 0.1, 0.3}, {0.9, 0.1, 0.3}, {0.8, 0.3, 0.6});
  box.surfaces.push_back(tri);
  for (const int leaves : {16, 19, 22, 28, 31})
    EXPECT_EQ(leaf_count(solve_hierarchical_leaves(box, "tri", leaves, HierarchicalOptions{}, "test"), "tri"),
              static_cast<size_t>(leaves));
  try {
    solve_hierarchical_leaves(box, "lamp", 4, HierarchicalOptions{}, "test");
    ADD_FAILURE() << "4 leaves on the black lamp accepted";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("a black side (reflectance 0) is never split"), std::string::npos) << e.what();
  }
}

TEST(Hierarchical, ClosedBoxRadiosityPowerIsEmittedOverOneMinusReflectance) {
  const double rho = 0.6, E = 10.0;
  const Scene box = testing_support::closed_box(rho, E);
  HierarchicalOptions options;
  options.epsilon_w = 1e-3;
  const Solution sol = solve_hierarchical(box, options, "quadtree-eps:1e-3");
  const double power = testing_support::radiosity_power_w(sol);
  const double expected = E * 1.0 / (1 - rho);
  EXPECT_NEAR(power, expected, 0.01 * expected);
  EXPECT_GT(sol.stats.elements, 6u) << "the box should have been refined";
  EXPECT_TRUE(sol.stats.converged);
}

/// Issue 11 item 5 for hierarchical radiosity: the room that `make` builds (reflectance rho,
/// light exitance E) keeps its energy to 1e-3 (links are area-to-area already): absorbed =
/// emitted, and sum A B = Phi / (1 - rho), the closed form of the mean radiosity.
void expect_closed_room_keeps_its_energy(Scene (*make)(double rho, double E), const char* what) {
  const double E = 40, phi = E * testing_support::kClosedRoomLight_m2, area = testing_support::kClosedRoomArea_m2;
  for (const double rho : {0.5, 0.95}) {
    HierarchicalOptions options;
    options.epsilon_w = 1e-3;
    const Solution sol = solve_hierarchical(make(rho, E), options, "quadtree-eps:1e-3");
    const double radiosity_power = testing_support::radiosity_power_w(sol);
    EXPECT_TRUE(sol.stats.converged);
    EXPECT_NEAR(sol.stats.absorbed_w[0], phi, 1e-3 * phi) << what << ", rho = " << rho;
    const double mean_radiosity = phi / ((1 - rho) * area);
    EXPECT_NEAR(radiosity_power / area, mean_radiosity, 1e-3 * mean_radiosity) << what << ", rho = " << rho;
    std::printf("hierarchical, %s, rho %.2f: absorbed / emitted - 1 = %.2e, sum A B / closed form - 1 = %.2e\n", what,
                rho, sol.stats.absorbed_w[0] / phi - 1, radiosity_power / area / mean_radiosity - 1);
  }
}

TEST(Hierarchical, ClosedRoomKeepsItsEnergy) {
  // Measured: absorbed / emitted - 1 = 1.3e-4 (rho 0.5) and 1.0e-4 (0.95); sum A B against the
  // closed form: 6.5e-5 and 9.8e-5.
  expect_closed_room_keeps_its_energy(testing_support::closed_room, "closed room");
}

TEST(Hierarchical, ALightLyingOnTheCeilingKeepsTheRoomsEnergy) {
  // The lamp lying on the one-quad ceiling (solver/covered.h): a leaf's radiosity is its mean over
  // its area, the covered part dark, so the tiled room's closed forms hold. Measured 1.4e-4 and
  // 2.9e-4 (1.6e-2 and 0.35 while the covered part received light as the lamp did).
  expect_closed_room_keeps_its_energy(testing_support::closed_room_with_lamp, "lamp on the ceiling");
}

/// A block standing on the floor of the closed room, open at its foot (solver/enclosed.h): the
/// floor under it neither receives nor sends light. A floor node across the block's foot sends
/// what its exposed part reflects, and every receiver sees only that part (the block hides the
/// rest): it must be seen at the radiosity of that part, its power over its exposed area, not at
/// its mean over its whole area. Seen at its mean, the room lost 1.25e-2 of its power at
/// epsilon 1e-2 W and 6.6e-3 at 1e-3 W (0.12 and 0.090 at reflectance 0.95). What is left is the
/// loss of links that see a source in part at the mean of all of it (docs/method.md, hierarchical
/// radiosity's known limits), which the block's shadow and what it hides make one-signed: the
/// same block lifted 1 cm, with a bottom, loses 3.1e-3 and 9.4e-4 here (1.6e-2 and 2.8e-2 at
/// reflectance 0.95, which this test leaves out for that reason).
TEST(Hierarchical, AClosedRoomWithABlockStandingOnItsFloorKeepsItsEnergy) {
  constexpr double kOccludedRoomRelative = 2e-3;  // the loss left by links seeing sources in part
  const double rho = 0.5, E = 40, phi = E * testing_support::kClosedRoomLight_m2;
  for (const double epsilon_w : {1e-2, 1e-3}) {
    HierarchicalOptions options;
    options.epsilon_w = epsilon_w;
    const Solution sol =
        solve_hierarchical(testing_support::closed_room_with_standing_block(rho, E), options, "quadtree-eps");
    EXPECT_TRUE(sol.stats.converged);
    EXPECT_NEAR(sol.stats.emitted_w[0], phi, 1e-12 * phi);
    EXPECT_NEAR(sol.stats.absorbed_w[0], phi, kOccludedRoomRelative * phi) << "epsilon " << epsilon_w;
    std::printf("hierarchical, a block standing in the closed room, epsilon %g W: absorbed / emitted - 1 = %.2e\n",
                epsilon_w, sol.stats.absorbed_w[0] / phi - 1);
  }
}

TEST(Hierarchical, GatheringStoppedByItsIterationLimitIsReportedNotConverged) {
  // In a closed box of reflectance 0.6 each Jacobi step removes about a factor 0.6 of the
  // change: 3 steps cannot reach 1e-6, 200 can (0.6^200 ~ 1e-44).
  const Scene box = testing_support::closed_box(0.6, 10.0);
  HierarchicalOptions options;
  options.epsilon_w = 1e-2;
  options.max_gather_iterations = 3;
  const Solution stopped = solve_hierarchical(box, options, "quadtree-eps:1e-2");
  EXPECT_FALSE(stopped.stats.converged);
  EXPECT_GT(stopped.stats.residual, options.tolerance);
  options.max_gather_iterations = 200;
  const Solution settled = solve_hierarchical(box, options, "quadtree-eps:1e-2");
  EXPECT_TRUE(settled.stats.converged);
  EXPECT_LE(settled.stats.residual, options.tolerance);
}

TEST(Hierarchical, OpenFloorLeavesHoldTheClosedFormAverageOfDirectLight) {
  // A floor under a black rectangular light: a leaf's radiosity is rho E times the mean over the
  // leaf of the closed-form point-to-rectangle form factor (computed here by a fine midpoint rule).
  Scene scene;
  scene.name = "floor";
  scene.surfaces.push_back(quad("floor", {0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}, 0.5));
  scene.surfaces.push_back(quad("light", {1, 1, 2.5}, {1, 2, 2.5}, {2, 2, 2.5}, {2, 1, 2.5}, 0.0, 40.0));
  const Solution sol = solve_hierarchical_leaves(scene, "floor", 100, HierarchicalOptions{}, "test");
  const SurfaceSolution& floor = *sol.find("floor");
  ASSERT_EQ(floor.elements.size(), 100u);
  constexpr int kFine = 64;
  for (const SolutionElement& e : floor.elements) {
    double mean = 0;
    for (int j = 0; j < kFine; ++j)
      for (int i = 0; i < kFine; ++i) {
        const double x = 4 * (e.u0 + (i + 0.5) / kFine * (e.u1 - e.u0)), y = 4 * (e.v0 + (j + 0.5) / kFine * (e.v1 - e.v0));
        mean += testing_support::floor_to_rectangle(x, y, 1, 1, 2, 2, 2.5);
      }
    mean /= kFine * kFine;
    const double expected = 0.5 * 40.0 * mean;
    // The solver's 4 x 4 rule against the 64 x 64 one: second-order error in the leaf size.
    EXPECT_NEAR(e.radiosity_w_m2[0], expected, 2e-3 * expected) << "leaf at " << e.center.transpose();
  }
}

TEST(Hierarchical, RefinementIsDeterministic) {
  HierarchicalOptions options;
  options.epsilon_w = 0.005;
  const Solution a = solve_hierarchical(paper_scene(), options, "a");
  const Solution b = solve_hierarchical(paper_scene(), options, "b");
  ASSERT_EQ(a.surfaces.size(), b.surfaces.size());
  EXPECT_EQ(a.stats.links, b.stats.links);
  for (size_t s = 0; s < a.surfaces.size(); ++s) {
    ASSERT_EQ(a.surfaces[s].elements.size(), b.surfaces[s].elements.size());
    for (size_t e = 0; e < a.surfaces[s].elements.size(); ++e) {
      EXPECT_EQ(a.surfaces[s].elements[e].u0, b.surfaces[s].elements[e].u0);
      EXPECT_EQ(a.surfaces[s].elements[e].radiosity_w_m2[0], b.surfaces[s].elements[e].radiosity_w_m2[0]);
    }
  }
}

// Links are measured in parallel and may come from a cache filled by another solve of the same
// scene (quadtree:LEAVES's search): neither may change a bit of the result.
TEST(Hierarchical, SameForAnyThreadCountAndWithACacheOfAnotherSolve) {
  HierarchicalOptions options;
  options.epsilon_w = 0.005;
  const int threads = worker_thread_count();
  set_worker_thread_count(1);
  const Solution alone = solve_hierarchical(paper_scene(), options, "alone");
  set_worker_thread_count(std::max(2, threads));
  LinkFormFactorCache cache;
  HierarchicalOptions finer = options;
  finer.epsilon_w = 0.002;
  solve_hierarchical(paper_scene(), finer, "finer", &cache);
  const size_t cached = cache.size();
  const Solution shared = solve_hierarchical(paper_scene(), options, "shared", &cache);
  set_worker_thread_count(threads);
  EXPECT_GT(cached, shared.stats.links) << "the cache was filled by the finer solve";
  ASSERT_EQ(alone.surfaces.size(), shared.surfaces.size());
  EXPECT_EQ(alone.stats.links, shared.stats.links);
  for (size_t s = 0; s < alone.surfaces.size(); ++s) {
    ASSERT_EQ(alone.surfaces[s].elements.size(), shared.surfaces[s].elements.size());
    for (size_t e = 0; e < alone.surfaces[s].elements.size(); ++e)
      for (int c = 0; c < 3; ++c)
        ASSERT_EQ(alone.surfaces[s].elements[e].radiosity_w_m2[c], shared.surfaces[s].elements[e].radiosity_w_m2[c]);
  }
}

TEST(Hierarchical, SmallerEpsilonRefinesMore) {
  HierarchicalOptions coarse, fine;
  coarse.epsilon_w = 0.02;
  fine.epsilon_w = 0.002;
  EXPECT_LT(leaf_count(solve_hierarchical(paper_scene(), coarse, "c"), "ground"),
            leaf_count(solve_hierarchical(paper_scene(), fine, "f"), "ground"));
}

TEST(Hierarchical, GroundLeavesApproachAFineProgressiveSolveAsEpsilonShrinks) {
  // The paper scene with its interreflections: each ground leaf's radiosity (its mean) against
  // the mean over the leaf of a progressive solve on a 128 x 128 grid (another solver: shooting,
  // a far-field bound, point collocation), over the leaves no smaller than the grid's elements
  // (dyadic squares: each holds whole elements). The error, weighted by area and relative to the
  // mean radiosity, falls as epsilon falls: measured 1.31%, 1.10% and 0.69% at 0.02, 0.002 and
  // 0.0005 W (the largest errors at 0.002 W are 1% under the light, in leaves of 0.0625 m^2
  // whose power, 0.064 W, errs by a third of epsilon).
  constexpr int kGrid = 128;
  const Solution reference = solve_scene(paper_scene(), "grid:128", SolveSettings{}, "test");
  const SurfaceSolution& fine = *reference.find("ground");
  ASSERT_EQ(fine.grid_nu, kGrid);
  ASSERT_EQ(fine.grid_nv, kGrid);
  std::vector<double> errors;
  for (const double epsilon_w : {0.02, 0.002, 0.0005}) {
    HierarchicalOptions options;
    options.epsilon_w = epsilon_w;
    const Solution sol = solve_hierarchical(paper_scene(), options, "test");
    double error = 0, total = 0, covered = 0;
    for (const SolutionElement& leaf : sol.find("ground")->elements) {
      if (leaf.u1 - leaf.u0 < 1.0 / kGrid - 1e-12) continue;
      double mean = 0;
      int count = 0;
      for (const SolutionElement& e : fine.elements)
        if (e.center.x() > 4 * leaf.u0 && e.center.x() < 4 * leaf.u1 && e.center.y() > 4 * leaf.v0 &&
            e.center.y() < 4 * leaf.v1)
          mean += e.radiosity_w_m2[0], ++count;
      const double side = (leaf.u1 - leaf.u0) * kGrid;
      ASSERT_EQ(count, static_cast<int>(std::lround(side * side))) << "a leaf holds whole elements";
      mean /= count;
      error += leaf.area_m2 * std::abs(leaf.radiosity_w_m2[0] - mean);
      total += leaf.area_m2 * mean;
      covered += leaf.area_m2;
    }
    EXPECT_GT(covered, 0.9 * 16) << "the leaves compared cover most of the ground";
    errors.push_back(error / total);
    std::printf("epsilon %g W: %zu ground leaves, relative L1 error %.3e over %.1f m^2\n", epsilon_w,
                sol.find("ground")->elements.size(), error / total, covered);
  }
  EXPECT_LT(errors[1], errors[0]);
  EXPECT_LT(errors[2], errors[1]);
  EXPECT_LT(errors[2], 0.01);
}

TEST(Hierarchical, AWallSeesOnlyTheGroundOnItsOwnSideOfItsFoot) {
  // The paper scene: wall1 stands on the ground along x = 2.6 m, a line no node boundary of the
  // 4 m ground's quadtree meets (0.65 of its width has no finite binary expansion). A ground node
  // across the foot is lit in front of the wall and shadowed behind it, and each face of the wall
  // sees only the part on its own side. Against a progressive solve on grid:128 (another solver:
  // shooting, point collocation), the wall's mean radiosity at epsilon 1e-4 W was measured off by
  // -3.3% on its front and +24% on its back (the rest: leaves across the foot, whose radiosity
  // is one mean). Seen at the nodes' whole means they were off by -5.7% and +93%.
  const Solution reference = solve_scene(paper_scene(), "grid:128", SolveSettings{}, "test");
  HierarchicalOptions options;
  options.epsilon_w = 1e-4;
  const Solution sol = solve_hierarchical(paper_scene(), options, "test");
  const double front = side_mean(sol, "wall1/front").mean(), front_ref = side_mean(reference, "wall1/front").mean();
  const double back = side_mean(sol, "wall1/back").mean(), back_ref = side_mean(reference, "wall1/back").mean();
  std::printf("wall1 front %.4f (grid:128 %.4f), back %.4f (%.4f) W/m^2\n", front, front_ref, back, back_ref);
  EXPECT_NEAR(front / front_ref, 1, 0.04);
  EXPECT_NEAR(back / back_ref, 1, 0.3);
}

}  // namespace hierarchical_test
}  // namespace radrecon
