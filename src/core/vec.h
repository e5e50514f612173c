#pragma once
// Small fixed-size vector types shared by every module (Eigen underneath).

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

}  // namespace radrecon
