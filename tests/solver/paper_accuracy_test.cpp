// The 400 x 400 reference of the paper scene against an independent global-illumination
// estimate: Monte Carlo path tracing with the test's own ray caster (no form factors, no
// clipping), at the centres of randomly chosen reference elements.

#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "mesh/grid_mesh.h"
#include "solver/hierarchical.h"
#include "solver/progressive.h"
#include "support/ray_scene.h"

namespace radrecon {
namespace {

using testing_support::trace;
using testing_support::visible;

/// The target: mean relative difference over points with B > 0.05 W/m^2.
constexpr double kMeanRelative = 3e-3;
constexpr int kPoints = 160;
constexpr int kDirectStrata = 128;    ///< light samples per axis at the points checked
constexpr int kIndirectPaths = 30000; ///< cosine-weighted paths per point checked

class PathTracer {
 public:
  explicit PathTracer(const Scene& scene) : scene_(scene), light_(*scene.find_surface("light")) {}

  /// Irradiance (W/m^2) at p (unit normal n, on surface `surface`) straight from the light, by
  /// stratified sampling of the light's area with shadow rays.
  double direct(const Vec3& p, const Vec3& n, size_t surface, int strata, std::mt19937_64& rng) const {
    const Surface& L = scene_.surfaces[light_];
    const Vec3 nl = L.normal();
    std::uniform_real_distribution<double> U(0, 1);
    double sum = 0;
    for (int i = 0; i < strata; ++i)
      for (int j = 0; j < strata; ++j) {
        const Vec3 y = L.point((i + U(rng)) / strata, (j + U(rng)) / strata);
        const Vec3 r = y - p;
        const double d2 = r.squaredNorm(), d = std::sqrt(d2);
        const double cos_p = n.dot(r) / d, cos_l = -nl.dot(r) / d;
        if (cos_p <= 0 || cos_l <= 0) continue;
        if (!visible(scene_, p, y, surface, light_)) continue;
        sum += cos_p * cos_l / (std::numbers::pi * d2);
      }
    return L.emission_w_m2[0] * L.area_m2() * sum / (strata * strata);
  }

  /// Radiosity estimate (W/m^2) at p: rho (direct + indirect), one indirect path per call;
  /// the path continues with probability rho (Russian roulette), so the estimate is unbiased.
  double radiosity(const Vec3& p, const Vec3& n, size_t surface, int strata, std::mt19937_64& rng, int depth) const {
    const double rho = scene_.surfaces[surface].reflectance[0];
    if (rho == 0) return 0;
    return rho * (direct(p, n, surface, strata, rng) + indirect(p, n, surface, rng, depth));
  }

  /// Irradiance from every surface but the light, one cosine-weighted sample: E[B(hit)].
  double indirect(const Vec3& p, const Vec3& n, size_t surface, std::mt19937_64& rng, int depth) const {
    if (depth > 12) return 0;
    std::uniform_real_distribution<double> U(0, 1);
    const double r = std::sqrt(U(rng)), phi = 2 * std::numbers::pi * U(rng);
    const Vec3 t = (std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(n).normalized();
    const Vec3 b = n.cross(t);
    const Vec3 d = r * std::cos(phi) * t + r * std::sin(phi) * b + std::sqrt(std::max(0.0, 1 - r * r)) * n;
    auto hit = trace(scene_, p, d, surface);
    if (!hit) return 0;
    const Surface& s = scene_.surfaces[hit->surface];
    if (!hit->front && !s.two_sided) return 0;
    const Vec3 nh = hit->front ? s.normal() : Vec3(-s.normal());
    // Russian roulette on the hit's radiosity: B = rho (direct + indirect), continue w.p. rho.
    const double rho = s.reflectance[0];
    if (rho == 0) return 0;
    if (U(rng) >= rho) return 0;
    return direct(hit->point, nh, hit->surface, 2, rng) + indirect(hit->point, nh, hit->surface, rng, depth + 1);
  }

 private:
  const Scene& scene_;
  size_t light_;
};

/// The 400 x 400 reference, solved once for the tests of this file.
const Solution& reference_solution() {
  static const Solution reference = [] {
    const Scene scene = paper_scene();
    return solve_progressive(scene, make_grid_mesh(scene, {400, 2}), ProgressiveOptions{}, "grid:400");
  }();
  return reference;
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
    std::mt19937_64 rng(1000 + k);
    const double direct = tracer.direct(e.center, Vec3::UnitZ(), ground_index, kDirectStrata, rng);
    double indirect = 0;
    for (int i = 0; i < kIndirectPaths; ++i) indirect += tracer.indirect(e.center, Vec3::UnitZ(), ground_index, rng, 0);
    const double b_mc = 0.5 * (direct + indirect / kIndirectPaths);
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

}  // namespace
}  // namespace radrecon
