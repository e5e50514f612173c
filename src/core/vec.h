#pragma once
// Small fixed-size vector types shared by every module (Eigen underneath).

#include <algorithm>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

namespace radrecon {

/// A point or direction in a plane, e.g. surface coordinates (s, t) in metres.
using Vec2 = Eigen::Vector2d;
/// A point or direction in world space, in metres.
using Vec3 = Eigen::Vector3d;
/// Linear RGB triple: radiosity or exitance in W/m^2 per channel, or a reflectance in [0,1).
using Rgb = Eigen::Array3d;
/// A polyline in a plane: consecutive points joined by segments, metres.
using Polyline = std::vector<Vec2>;

/// The plane's cross product a x b = ax by - ay bx: twice the signed area of the triangle
/// (0, a, b), positive when b lies counter-clockwise of a.
inline double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

/// Twice the signed area of the closed polygon `p` (its last point joined back to its first),
/// positive when it runs counter-clockwise.
inline double twice_signed_area(const Polyline& p) {
  double a = 0;
  for (size_t i = 0, j = p.size() - 1; i < p.size(); j = i++) a += cross(p[j], p[i]);
  return p.empty() ? 0.0 : a;
}

/// The parameter t in [0, 1] of the point a + t (b - a) of the segment [a, b] nearest to q (q's
/// projection onto the segment's line, clamped to its ends); 0 when a = b.
inline double nearest_on_segment_t(const Vec2& q, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double length_sq = ab.squaredNorm();
  return length_sq > 0 ? std::clamp((q - a).dot(ab) / length_sq, 0.0, 1.0) : 0.0;
}

}  // namespace radrecon
