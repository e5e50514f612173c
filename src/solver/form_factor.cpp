#include "solver/form_factor.h"

#include <cmath>
#include <numbers>

#include "core/math.h"

namespace radrecon {

double lambert_form_factor(const Vec3& p, const Vec3& n, const ConvexPolygon& polygon) {
  if (polygon.empty()) return 0.0;
  double sum = 0.0;
  Vec3 r0 = polygon.v[polygon.n - 1] - p;
  for (int i = 0; i < polygon.n; ++i) {
    Vec3 r1 = polygon.v[i] - p;
    Vec3 c = r0.cross(r1);
    double c_norm = c.norm();
    // c_norm == 0: p on the line of this edge; the edge subtends no angle and adds nothing.
    if (c_norm > 0) sum += atan2_nonneg(c_norm, r0.dot(r1)) * n.dot(c) / c_norm;
    r0 = r1;
  }
  return std::abs(sum) / (2.0 * std::numbers::pi);
}

ConvexPolygon clip_to_horizon(const Vec3& p, const Vec3& n, const ConvexPolygon& polygon) {
  return clip(polygon, HalfSpace{n, n.dot(p)});
}

}  // namespace radrecon
