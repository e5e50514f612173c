// The 400 x 400 reference of the paper scene against an independent global-illumination
// estimate: Monte Carlo path tracing (tests/support/path_tracer.h: its own ray caster, no form
// factors, no clipping), at the centres of randomly chosen reference elements.

#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "mesh/grid_mesh.h"
#include "solver/hierarchical.h"
#include "solver/progressive.h"
#include "support/path_tracer.h"

namespace radrecon {
namespace paper_accuracy_test {

using testing_support::PathTracer;

/// The target: mean relative difference over points with B > 0.05 W/m^2.
constexpr double kMeanRelative = 3e-3;
constexpr int kPoints = 160;
constexpr int kDirectStrata = 128;    ///< light samples per axis at the points checked
constexpr int kIndirectPaths = 30000; ///< cosine-weighted paths per point checked

/// The 400 x 400 reference, solved once for the tests of this file.
const Solution& reference_solution() {
  static const Solution reference = [] {
    const Scene scene = paper_scene();
    return solve_progressive(scene, make_grid_mesh(scene, {400}), ProgressiveOptions{}, "grid:400");
  }();
  return reference;
}

/// A reflectance-0.5 side's radiosity (red) at p by path tracing: the direct light by
/// `kDirectStrata`^2 light samples, the indirect by `paths` cosine-weighted paths, seeded with
/// `seed`; and the standard error of the indirect part's mean (W/m^2).
struct PointEstimate {
  double radiosity_w_m2, standard_error_w_m2;
};
PointEstimate path_traced(const PathTracer& tracer, const Vec3& p, const Vec3& n, size_t surface, int paths,
                          std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  const double direct = tracer.direct(p, n, surface, kDirectStrata, rng)[0];
  double sum = 0, sum_sq = 0;
  for (int i = 0; i < paths; ++i) {
    const double x = tracer.indirect(p, n, surface, rng)[0];
    sum += x, sum_sq += x * x;
  }
  const double mean = sum / paths;
  return {0.5 * (direct + mean), 0.5 * std::sqrt(std::max(0.0, sum_sq / paths - mean * mean) / (paths - 1))};
}

TEST(PaperReference, AgreesWithIndependentPathTracing) {
  const Scene scene = paper_scene();
  const Solution& reference = reference_solution();
  const SurfaceSolution* ground = reference.find("ground");
  ASSERT_NE(ground, nullptr);
  const size_t ground_index = *scene.find_surface("ground");

  PathTracer tracer(scene);
  std::mt19937_64 pick(1234);
  std::uniform_int_distribution<size_t> element(0, ground->elements.size() - 1);
  double sum_rel = 0, max_rel = 0;
  int counted = 0;
  for (int k = 0; k < kPoints; ++k) {
    const SolutionElement& e = ground->elements[element(pick)];
    const double b_mc = path_traced(tracer, e.center, Vec3::UnitZ(), ground_index, kIndirectPaths, 1000 + k).radiosity_w_m2;
    const double b_ref = e.radiosity_w_m2[0];
    if (b_mc <= 0.05) continue;
    const double rel = std::abs(b_ref - b_mc) / b_mc;
    sum_rel += rel;
    max_rel = std::max(max_rel, rel);
    ++counted;
  }
  ASSERT_GT(counted, kPoints / 2);
  const double mean_rel = sum_rel / counted;
  std::printf("reference vs path tracing: mean relative difference %.2e, max %.2e over %d points\n", mean_rel,
              max_rel, counted);
  EXPECT_LT(mean_rel, kMeanRelative);
}

TEST(PaperReference, WallsBothSidesAgreeWithIndependentPathTracing) {
  // The walls' fronts (lit by the lamp) and wall1's back (lit only by the ground beyond it, all
  // indirect) at random element centres. Each point's path-traced estimate has its own standard
  // error (from its paths' spread): the reference must lie within 4 of them plus 0.3% of the
  // value (the mesh), and the mean signed relative difference over a side within 3 standard
  // errors of that mean plus 0.3% (a bias would show there).
  constexpr int kSidePoints = 40, kSidePaths = 20000;
  constexpr double kMeshRelative = 3e-3;
  const Scene scene = paper_scene();
  const Solution& reference = reference_solution();
  PathTracer tracer(scene);
  for (const char* side : {"wall1/front", "wall1/back", "wall2/front"}) {
    const SurfaceSolution* s = reference.find(side);
    ASSERT_NE(s, nullptr) << side;
    const size_t index = *scene.find_surface(s->scene_surface);
    const Vec3 n = s->back_side ? Vec3(-scene.surfaces[index].normal()) : scene.surfaces[index].normal();
    std::mt19937_64 pick(4321);
    std::uniform_int_distribution<size_t> element(0, s->elements.size() - 1);
    double sum_rel = 0, sum_rel_sq = 0;
    int counted = 0;
    for (int k = 0; k < kSidePoints; ++k) {
      const SolutionElement& e = s->elements[element(pick)];
      const auto [b_mc, standard_error] = path_traced(tracer, e.center, n, index, kSidePaths, 5000 + k);
      const double b_ref = e.radiosity_w_m2[0];
      if (b_mc <= 1e-3) continue;
      EXPECT_NEAR(b_ref, b_mc, 4 * standard_error + kMeshRelative * b_mc) << side << " at " << e.center.transpose();
      const double rel = b_ref / b_mc - 1;
      sum_rel += rel, sum_rel_sq += rel * rel;
      ++counted;
    }
    ASSERT_GT(counted, kSidePoints / 2) << side;
    const double mean_rel = sum_rel / counted;
    const double mean_se = std::sqrt(std::max(0.0, sum_rel_sq / counted - mean_rel * mean_rel) / (counted - 1));
    std::printf("%s: reference vs path tracing, mean relative difference %+.2e (standard error %.1e) over %d points\n",
                side, mean_rel, mean_se, counted);
    EXPECT_NEAR(mean_rel, 0.0, 3 * mean_se + kMeshRelative) << side;
  }
}

/// The bound: RMS over the leaves of (leaf radiosity - reference averaged over the leaf).
constexpr double kLeafRms_w_m2 = 0.02;

TEST(PaperQuadtree, LeavesAgreeWithTheReferenceAveragedOverEachLeaf) {
  const SurfaceSolution& ref = *reference_solution().find("ground");
  const int N = ref.grid_nu;
  ASSERT_EQ(N, 400);
  const Solution quadtree = solve_hierarchical_leaves(paper_scene(), "ground", 286, HierarchicalOptions{}, "test");
  const SurfaceSolution& ground = *quadtree.find("ground");
  ASSERT_EQ(ground.elements.size(), 286u);
  double sum_sq = 0, worst = 0;
  for (const SolutionElement& leaf : ground.elements) {
    // Area-weighted mean of the reference cells over the leaf (cells cut by its edges count
    // with the part inside).
    double sum = 0, weight = 0;
    for (int j = static_cast<int>(leaf.v0 * N); j < static_cast<int>(std::ceil(leaf.v1 * N)); ++j)
      for (int i = static_cast<int>(leaf.u0 * N); i < static_cast<int>(std::ceil(leaf.u1 * N)); ++i) {
        const double ox = std::min(leaf.u1, (i + 1.0) / N) - std::max(leaf.u0, double(i) / N);
        const double oy = std::min(leaf.v1, (j + 1.0) / N) - std::max(leaf.v0, double(j) / N);
        if (ox <= 0 || oy <= 0) continue;
        sum += ox * oy * ref.elements[static_cast<size_t>(j) * N + i].radiosity_w_m2[0];
        weight += ox * oy;
      }
    const double d = leaf.radiosity_w_m2[0] - sum / weight;
    sum_sq += d * d;
    worst = std::max(worst, std::abs(d));
  }
  const double rms = std::sqrt(sum_sq / ground.elements.size());
  std::printf("quadtree (286 leaves) vs reference leaf averages: RMS %.4f W/m^2, max %.4f W/m^2\n", rms, worst);
  EXPECT_LT(rms, kLeafRms_w_m2);
}

}  // namespace paper_accuracy_test
}  // namespace radrecon
