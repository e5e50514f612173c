#pragma once
// An independent global-illumination estimate for tests: Monte Carlo path tracing with the test
// ray caster of ray_scene.h (no form factors, no clipping, no mesh), per colour channel, over
// quads and triangles, lit by every emitting surface.
//
// The scene is read as the solver reads it: a surface lying flat on another (the Cornell box's
// light on its ceiling) covers it there (solver/covered.h), so a path meeting both at once
// continues from the one on top, facing it (nearest()); a shadow ray ending on an emitter is not
// blocked by a surface in its plane.

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "support/ray_scene.h"

namespace radrecon::testing_support {

/// Whether a quad is a parallelogram (its bilinear map then has a constant Jacobian).
inline bool is_parallelogram(const Surface& s) {
  return !s.is_triangle() &&
         (s.corners[0] + s.corners[2] - s.corners[1] - s.corners[3]).norm() <= 1e-12 * (s.corners[2] - s.corners[0]).norm();
}

/// The point of surface s for (a, b) in the unit square, uniform over its area when (a, b) is
/// uniform: the bilinear map of a parallelogram; otherwise the polygon cut into the triangles
/// (c0, c1, c2) and (c0, c2, c3), chosen by area with a, each sampled by the square-root warp.
inline Vec3 uniform_point(const Surface& s, double a, double b) {
  if (is_parallelogram(s)) return s.point(a, b);
  const auto tri = [](const Vec3& p0, const Vec3& p1, const Vec3& p2, double x, double y) {
    const double r = std::sqrt(x);
    return Vec3((1 - r) * p0 + r * (1 - y) * p1 + r * y * p2);
  };
  const Vec3 &c0 = s.corners[0], &c1 = s.corners[1], &c2 = s.corners[2], &c3 = s.corners[3];
  if (s.is_triangle()) return tri(c0, c1, c2, a, b);
  const double a1 = (c1 - c0).cross(c2 - c0).norm(), a2 = (c2 - c0).cross(c3 - c0).norm();
  const double f = a1 / (a1 + a2);
  return a < f ? tri(c0, c1, c2, a / f, b) : tri(c0, c2, c3, (a - f) / (1 - f), b);
}

class PathTracer {
 public:
  explicit PathTracer(const Scene& scene) : scene_(scene), coplanar_(scene.surfaces.size()) {
    for (size_t k = 0; k < scene.surfaces.size(); ++k)
      if ((scene.surfaces[k].emission_w_m2 > 0).any()) emitters_.push_back(k);
    // The surfaces in each one's plane (either orientation), to break ties between them.
    for (size_t a = 0; a < scene.surfaces.size(); ++a)
      for (size_t b = 0; b < scene.surfaces.size(); ++b) {
        const Surface &sa = scene.surfaces[a], &sb = scene.surfaces[b];
        const Vec3 n = sa.normal();
        if (a == b || std::abs(std::abs(n.dot(sb.normal())) - 1) > kTie) continue;
        const double size = std::sqrt(std::max(sa.area_m2(), sb.area_m2()));
        bool in_plane = true;
        for (const Vec3& c : sb.polygon()) in_plane = in_plane && std::abs(n.dot(c - sa.corners[0])) <= kTie * size;
        if (in_plane) coplanar_[a].push_back(b);
      }
  }

  /// The nearest surface along the ray o + t d (t > 0), `skip` excepted. Where surfaces coincide
  /// there, the smallest of those the ray meets on a side they show (the front, or either side of
  /// a two-sided one) wins: it lies on the others and covers them (the light on the Cornell box's
  /// ceiling, seen from below; the ceiling, seen from above a one-sided light). Taking the ceiling
  /// under the light reflected light from under the black emitter and put the box's floor 0.8%
  /// too bright (docs/cornell.md).
  std::optional<Hit> nearest(const Vec3& o, const Vec3& d, size_t skip) const {
    auto hit = trace(scene_, o, d, skip);
    if (!hit || coplanar_[hit->surface].empty()) return hit;
    const auto shows = [&](size_t k) { return scene_.surfaces[k].two_sided || scene_.surfaces[k].normal().dot(d) < 0; };
    std::optional<Hit> best;
    if (shows(hit->surface)) best = hit;
    for (size_t k : coplanar_[hit->surface]) {
      if (k == skip || !shows(k)) continue;
      if (best && scene_.surfaces[k].area_m2() >= scene_.surfaces[best->surface].area_m2()) continue;
      if (auto t = intersect_quad(scene_.surfaces[k], o, d, hit->t * (1 - kTie), hit->t * (1 + kTie)))
        best = Hit{*t, k, scene_.surfaces[k].normal().dot(d) < 0, o + *t * d};
    }
    return best ? best : hit;
  }

  /// Irradiance (W/m^2 per channel) at p (unit normal n, on surface `surface`) straight from the
  /// emitters, by stratified sampling of each emitter's area (strata x strata) with shadow rays.
  Rgb direct(const Vec3& p, const Vec3& n, size_t surface, int strata, std::mt19937_64& rng) const {
    std::uniform_real_distribution<double> U(0, 1);
    Rgb total = Rgb::Zero();
    for (size_t light : emitters_) {
      if (light == surface) continue;
      const Surface& L = scene_.surfaces[light];
      const Vec3 nl = L.normal();
      double sum = 0;
      for (int i = 0; i < strata; ++i)
        for (int j = 0; j < strata; ++j) {
          const double a = (i + U(rng)) / strata, b = (j + U(rng)) / strata;
          const Vec3 y = uniform_point(L, a, b);
          const Vec3 r = y - p;
          const double d2 = r.squaredNorm(), d = std::sqrt(d2);
          const double cos_p = n.dot(r) / d, cos_l = -nl.dot(r) / d;
          if (cos_p <= 0 || cos_l <= 0) continue;
          if (!unblocked(p, y, surface, light)) continue;
          sum += cos_p * cos_l / (std::numbers::pi * d2);
        }
      total += L.emission_w_m2 * (L.area_m2() * sum / (strata * strata));
    }
    return total;
  }

  /// Irradiance (W/m^2 per channel) from reflecting surfaces, one cosine-weighted path: its
  /// expectation is the indirect irradiance at p. Russian roulette continues a path with
  /// probability q = the hit's largest reflectance and weighs it by reflectance / q per channel,
  /// so the estimate is unbiased.
  Rgb indirect(const Vec3& p, const Vec3& n, size_t surface, std::mt19937_64& rng, int depth = 0) const {
    if (depth > kMaxDepth) return Rgb::Zero();
    std::uniform_real_distribution<double> U(0, 1);
    const double r = std::sqrt(U(rng)), phi = 2 * std::numbers::pi * U(rng);
    const Vec3 t = (std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(n).normalized();
    const Vec3 b = n.cross(t);
    const Vec3 d = r * std::cos(phi) * t + r * std::sin(phi) * b + std::sqrt(std::max(0.0, 1 - r * r)) * n;
    auto hit = nearest(p, d, surface);
    if (!hit) return Rgb::Zero();
    const Surface& s = scene_.surfaces[hit->surface];
    if (!hit->front && !s.two_sided) return Rgb::Zero();
    const Vec3 nh = hit->front ? s.normal() : Vec3(-s.normal());
    const double q = s.reflectance.maxCoeff();
    if (q <= 0) return Rgb::Zero();
    if (U(rng) >= q) return Rgb::Zero();
    return (s.reflectance / q) *
           (direct(hit->point, nh, hit->surface, 2, rng) + indirect(hit->point, nh, hit->surface, rng, depth + 1));
  }

  /// One estimate of the radiosity (W/m^2 per channel) at p: rho (direct + mean of `paths`
  /// indirect paths), the surface's own emission excluded.
  Rgb radiosity(const Vec3& p, const Vec3& n, size_t surface, int strata, int paths, std::mt19937_64& rng) const {
    const Rgb& rho = scene_.surfaces[surface].reflectance;
    if (rho.maxCoeff() <= 0) return Rgb::Zero();
    Rgb e = direct(p, n, surface, strata, rng);
    Rgb ind = Rgb::Zero();
    for (int i = 0; i < paths; ++i) ind += indirect(p, n, surface, rng);
    return rho * (e + ind / paths);
  }

 private:
  static constexpr int kMaxDepth = 12;
  /// Relative distance within which two hits are one (coplanar surfaces).
  static constexpr double kTie = 1e-9;

  /// True if nothing blocks the segment from p (on surface a) to y (on emitter b); a surface
  /// through y itself (in the emitter's plane) does not.
  bool unblocked(const Vec3& p, const Vec3& y, size_t a, size_t b) const {
    const Vec3 d = y - p;
    for (size_t k = 0; k < scene_.surfaces.size(); ++k) {
      if (k == a || k == b) continue;
      if (intersect_quad(scene_.surfaces[k], p, d, 1e-12, 1.0 - kTie)) return false;
    }
    return true;
  }

  const Scene& scene_;
  std::vector<size_t> emitters_;
  std::vector<std::vector<size_t>> coplanar_;  ///< by surface: the others in its plane
};

}  // namespace radrecon::testing_support
