#include "scene/contacts.h"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "core/tolerances.h"

namespace radrecon {

namespace {

/// The segment where the convex polygon `corners` meets the plane {x : dot(n, x) = d}, given the
/// signed distances of its corners (snapped to 0 within `touch_m`); false if it does not.
bool plane_section(const std::array<Vec3, 4>& corners, const std::array<double, 4>& dist, Vec3& a, Vec3& b) {
  std::vector<Vec3> points;
  for (int i = 0; i < 4; ++i) {
    const int j = (i + 1) % 4;
    if (dist[i] == 0) points.push_back(corners[i]);
    if ((dist[i] < 0 && dist[j] > 0) || (dist[i] > 0 && dist[j] < 0)) {
      const double t = dist[i] / (dist[i] - dist[j]);
      points.push_back(corners[i] + t * (corners[j] - corners[i]));
    }
  }
  if (points.size() < 2) return false;
  // A convex polygon meets a plane in a segment: its two most distant points.
  double best = -1;
  for (size_t i = 0; i < points.size(); ++i)
    for (size_t j = i + 1; j < points.size(); ++j)
      if ((points[i] - points[j]).squaredNorm() > best) {
        best = (points[i] - points[j]).squaredNorm();
        a = points[i];
        b = points[j];
      }
  return best > 0;
}

/// Clips the segment [a, b] (in the quad's plane) to the convex quad; false if nothing is left.
bool clip_to_quad(const Surface& quad, Vec3& a, Vec3& b) {
  const Vec3 n = quad.normal();
  double t0 = 0, t1 = 1;
  const Vec3 d = b - a;
  for (int i = 0; i < 4; ++i) {
    const Vec3& c = quad.corners[static_cast<size_t>(i)];
    const Vec3 inward = n.cross(quad.corners[static_cast<size_t>((i + 1) % 4)] - c);  // corners are CCW
    const double fa = inward.dot(a - c), fd = inward.dot(d);
    if (fd == 0) {
      if (fa < 0) return false;
      continue;
    }
    const double t = -fa / fd;
    if (fd > 0) t0 = std::max(t0, t);
    else t1 = std::min(t1, t);
  }
  if (!(t0 < t1)) return false;
  const Vec3 a0 = a;
  a = a0 + t0 * d;
  b = a0 + t1 * d;
  return true;
}

}  // namespace

std::vector<Segment2> contact_lines(const Scene& scene, SideRef side) {
  const Surface& s = scene.surfaces[side.surface];
  const Vec3 n = side_normal(s, side.back_side);
  const double offset = n.dot(s.corners[0]);
  const double lu = s.length_u_m(), lv = s.length_v_m();
  const double border = tol::kOnBorderParameter;
  std::vector<Segment2> out;
  for (size_t k = 0; k < scene.surfaces.size(); ++k) {
    if (k == side.surface) continue;
    const Surface& t = scene.surfaces[k];
    const double touch_m = tol::kContactRelative * std::max(t.length_u_m(), t.length_v_m());
    std::array<double, 4> dist;
    bool in_front = false, all_on = true;
    for (int i = 0; i < 4; ++i) {
      double d = n.dot(t.corners[static_cast<size_t>(i)]) - offset;
      if (std::abs(d) <= touch_m) d = 0;
      dist[static_cast<size_t>(i)] = d;
      in_front = in_front || d > 0;
      all_on = all_on && d == 0;
    }
    if (all_on || !in_front) continue;  // lying flat on the side, or only behind it
    Vec3 a, b;
    if (!plane_section(t.corners, dist, a, b) || !clip_to_quad(s, a, b)) continue;
    const std::optional<Vec2> ua = s.parameters(a), ub = s.parameters(b);
    if (!ua || !ub) continue;
    const auto on_border = [&](double x, double y) {
      return (std::abs(x) <= border && std::abs(y) <= border) || (std::abs(x - 1) <= border && std::abs(y - 1) <= border);
    };
    if (on_border(ua->x(), ub->x()) || on_border(ua->y(), ub->y())) continue;  // along an edge of the quad
    Vec2 pa(ua->x() * lu, ua->y() * lv), pb(ub->x() * lu, ub->y() * lv);
    if (pa == pb) continue;
    if (std::tie(pb.x(), pb.y()) < std::tie(pa.x(), pa.y())) std::swap(pa, pb);
    out.push_back({pa, pb});
  }
  return out;
}

}  // namespace radrecon
