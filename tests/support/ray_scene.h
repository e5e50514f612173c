#pragma once
// An independent ray caster over a scene's polygons (quads and triangles), for tests that check the solver against brute
// force: it shares no code with the solver's exact-clipping visibility.

#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

#include "scene/scene.h"

namespace radrecon::testing_support {

struct Hit {
  double t;
  size_t surface;
  bool front;  ///< the ray arrived on the front side
  Vec3 point;
};

/// Intersection of the ray o + t d (t in (t_min, t_max)) with a convex planar polygon (a quad or a
/// triangle: the corners of Surface::polygon()).
inline std::optional<double> intersect_quad(const Surface& s, const Vec3& o, const Vec3& d, double t_min,
                                            double t_max) {
  const Vec3 n = s.normal();
  const double denom = n.dot(d);
  if (std::abs(denom) < 1e-15) return std::nullopt;
  const double t = n.dot(s.corners[0] - o) / denom;
  if (!(t > t_min && t < t_max)) return std::nullopt;
  const Vec3 x = o + t * d;
  const auto p = s.polygon();
  for (size_t i = 0; i < p.size(); ++i) {
    const Vec3 e = p[(i + 1) % p.size()] - p[i];
    if (e.cross(x - p[i]).dot(n) < 0) return std::nullopt;
  }
  return t;
}

/// Nearest hit of the ray o + t d, t > t_min, skipping surface `skip` (the one the ray leaves).
inline std::optional<Hit> trace(const Scene& scene, const Vec3& o, const Vec3& d, size_t skip,
                                double t_min = 1e-9) {
  std::optional<Hit> best;
  double t_max = std::numeric_limits<double>::infinity();
  for (size_t k = 0; k < scene.surfaces.size(); ++k) {
    if (k == skip) continue;
    if (auto t = intersect_quad(scene.surfaces[k], o, d, t_min, t_max)) {
      t_max = *t;
      best = Hit{*t, k, scene.surfaces[k].normal().dot(d) < 0, o + *t * d};
    }
  }
  return best;
}

/// True if nothing but surfaces `a` and `b` blocks the open segment from p to q.
inline bool visible(const Scene& scene, const Vec3& p, const Vec3& q, size_t a, size_t b) {
  const Vec3 d = q - p;
  for (size_t k = 0; k < scene.surfaces.size(); ++k) {
    if (k == a || k == b) continue;
    if (intersect_quad(scene.surfaces[k], p, d, 1e-12, 1.0 - 1e-12)) return false;
  }
  return true;
}

/// F(dA -> visible part of the surface `shooter`) from the point p (unit normal n) on the
/// surface `receiver`, by the midpoint rule on an n_side x n_side grid of the shooter's
/// parameters, each point's visibility by the ray caster: an O(1/n_side) error where a shadow's
/// edge cuts the shooter.
inline double brute_force_form_factor(const Scene& scene, size_t shooter, const Vec3& p, const Vec3& n, size_t receiver,
                                      int n_side) {
  const Surface& s = scene.surfaces[shooter];
  const Vec3 ns = s.normal();
  const double dA = s.area_m2() / (static_cast<double>(n_side) * n_side);
  double f = 0;
  for (int i = 0; i < n_side; ++i)
    for (int j = 0; j < n_side; ++j) {
      const Vec3 y = s.point((i + 0.5) / n_side, (j + 0.5) / n_side);
      const Vec3 r = y - p;
      const double d2 = r.squaredNorm();
      const double cos_r = n.dot(r) / std::sqrt(d2), cos_s = -ns.dot(r) / std::sqrt(d2);
      if (cos_r <= 0 || cos_s <= 0) continue;
      if (!visible(scene, p, y, receiver, shooter)) continue;
      f += cos_r * cos_s / (std::numbers::pi * d2) * dA;
    }
  return f;
}

}  // namespace radrecon::testing_support
