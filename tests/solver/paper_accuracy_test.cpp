// The 400 x 400 reference of the paper scene against an independent global-illumination
// estimate: Monte Carlo path tracing with the test's own ray caster (no form factors, no
// clipping), at the centres of randomly chosen reference elements.

#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "mesh/grid_mesh.h"
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

TEST(PaperReference, AgreesWithIndependentPathTracing) {
  const Scene scene = paper_scene();
  ProgressiveOptions po;
  const Solution reference = solve_progressive(scene, make_grid_mesh(scene, {400, 2}), po, "grid:400");
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

}  // namespace
}  // namespace radrecon
