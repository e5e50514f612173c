#include "scene/shadow_lines.h"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "core/tolerances.h"

namespace radrecon {

namespace {

/// The side's plane: unit normal n (the side's front) and a point on it.
struct Plane {
  Vec3 n, o;
  double height(const Vec3& p) const { return n.dot(p - o); }
};

/// The (u, v) parameters of a point of the side's plane, by the affine frame of corners 0, 1 and 3
/// (exact for parallelograms and triangles, whose corner 3 repeats corner 2, and for any planar
/// quad the contact lines use the same frame within tol::kQuadEdgeParameter when the point is on
/// the quad).
Vec2 plane_uv(const Surface& s, const Vec3& p) {
  const Vec3 e1 = s.corners[1] - s.corners[0], e2 = s.corners[3] - s.corners[0];
  const double a = e1.dot(e1), b = e1.dot(e2), c = e2.dot(e2);
  const Vec3 d = p - s.corners[0];
  const double r1 = e1.dot(d), r2 = e2.dot(d), det = a * c - b * b;
  const double u = (c * r1 - b * r2) / det, v = (a * r2 - b * r1) / det;
  return {u, v};
}

/// Clips the (u,v) segment [a, b] to the parameter domain (Liang-Barsky): the unit box, or for a
/// triangle u, v >= 0 and u + v <= 1; false if nothing is left.
bool clip_to_domain(Vec2& a, Vec2& b, bool triangle) {
  double t0 = 0, t1 = 1;
  const Vec2 d = b - a;
  const double p[4] = {-d.x(), -d.y(), d.x(), d.y()};
  const double q[4] = {a.x(), a.y(), 1 - a.x(), 1 - a.y()};
  const double p_triangle[3] = {-d.x(), -d.y(), d.sum()}, q_triangle[3] = {a.x(), a.y(), 1 - a.sum()};
  for (int i = 0; i < (triangle ? 3 : 4); ++i) {
    const double pi = triangle ? p_triangle[i] : p[i], qi = triangle ? q_triangle[i] : q[i];
    if (pi == 0) {
      if (qi < 0) return false;
      continue;
    }
    const double t = qi / pi;
    if (pi < 0) t0 = std::max(t0, t);
    else t1 = std::min(t1, t);
  }
  if (!(t0 < t1)) return false;
  const Vec2 a0 = a;
  a = a0 + t0 * d;
  b = a0 + t1 * d;
  return true;
}

/// The point where the ray from `from` through `through` meets the plane, if `through` lies
/// strictly between `from` and the plane (heights 0 <= h_through < h_from).
std::optional<Vec3> project(const Plane& plane, const Vec3& from, const Vec3& through, double touch_m) {
  const double hf = plane.height(from), ht = plane.height(through);
  if (!(hf > touch_m) || ht < -touch_m || !(ht < hf - touch_m)) return std::nullopt;
  return from + (through - from) * (hf / (hf - ht));
}

}  // namespace

std::vector<Segment2> shadow_lines(const Scene& scene, SideRef side) {
  const Surface& s = scene.surfaces[side.surface];
  const Plane plane{side_normal(s, side.back_side), s.corners[0]};
  const SurfaceFrame frame = s.frame();
  const double lu = frame.length_u_m, lv = frame.length_v_m;
  const double touch_m = tol::kContactRelative * std::max(lu, lv);
  std::vector<Segment2> out;
  const auto add = [&](const Vec3& a3, const Vec3& b3) {
    Vec2 a = plane_uv(s, a3), b = plane_uv(s, b3);
    if (!clip_to_domain(a, b, s.is_triangle())) return;
    // The clip's round-off may leave an end 1 ulp outside.
    a = frame.st(a.cwiseMax(Vec2::Zero()).cwiseMin(Vec2::Ones()));
    b = frame.st(b.cwiseMax(Vec2::Zero()).cwiseMin(Vec2::Ones()));
    if ((b - a).norm() <= touch_m) return;
    if (std::tie(b.x(), b.y()) < std::tie(a.x(), a.y())) std::swap(a, b);
    for (const Segment2& o : out)
      if ((o.a - a).norm() <= touch_m && (o.b - b).norm() <= touch_m) return;  // a duplicate
    out.push_back({a, b});
  };
  for (size_t li = 0; li < scene.surfaces.size(); ++li) {
    const Surface& light = scene.surfaces[li];
    if (li == side.surface || !(light.emission_w_m2 > 0).any()) continue;
    const Vec3 light_normal = light.normal();  // emitters shine from their front
    for (size_t oi = 0; oi < scene.surfaces.size(); ++oi) {
      const Surface& occ = scene.surfaces[oi];
      if (oi == side.surface || oi == li || (occ.emission_w_m2 > 0).any()) continue;
      for (int e = 0; e < 4; ++e) {
        const Vec3& p = occ.corners[static_cast<size_t>(e)];
        const Vec3& q = occ.corners[static_cast<size_t>((e + 1) % 4)];
        if (std::abs(plane.height(p)) <= touch_m && std::abs(plane.height(q)) <= touch_m) continue;  // on the side
        for (int v = 0; v < 4; ++v) {
          const Vec3& l = light.corners[static_cast<size_t>(v)];
          // VE: the occluder edge [p, q] seen from the light vertex l.
          const auto lit = [&](const Vec3& from, const Vec3& x) { return light_normal.dot(x - from) > 0; };
          const auto pa = project(plane, l, p, touch_m), pb = project(plane, l, q, touch_m);
          if (pa && pb && lit(l, p) && lit(l, q)) add(*pa, *pb);
          // EV: the light edge [l, l'] seen through the occluder corner p.
          const Vec3& l2 = light.corners[static_cast<size_t>((v + 1) % 4)];
          const auto ea = project(plane, l, p, touch_m), eb = project(plane, l2, p, touch_m);
          if (ea && eb && lit(l, p) && lit(l2, p)) add(*ea, *eb);
        }
      }
    }
  }
  return out;
}

}  // namespace radrecon
