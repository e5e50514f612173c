#pragma once
// The scene model: planar convex triangles and quads with diffuse reflectance and emission, and
// cameras.
// All lengths in metres; emission is exitance in W/m^2.

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/vec.h"
#include "scene/param_cell.h"

namespace radrecon {

/// The map from a surface's parameters (u, v) to its metric coordinates (s, t), metres:
/// s = u length_u_m + v shear_m, t = v length_v_m. For a triangle it is an isometry (corner 0 at
/// the origin, edge 0->1 along s); for a quad (u length_u, v length_v), exact for a rectangle.
/// Reconstructions, barriers and excluded regions of a side live in (s, t).
struct SurfaceFrame {
  double length_u_m = 1, length_v_m = 1, shear_m = 0;
  Vec2 st(const Vec2& uv) const { return {uv.x() * length_u_m + uv.y() * shear_m, uv.y() * length_v_m}; }
  Vec2 uv(const Vec2& st) const {
    const double v = st.y() / length_v_m;
    return {(st.x() - v * shear_m) / length_u_m, v};
  }
};

/// A surface's extent as meshing and texel densities take it, metres, from its frame: a quad's
/// longer mean edge; a triangle's longest edge. Not a triangle's base or height, which depend on
/// which corner is listed first (a floor listed from another corner made every element of the
/// scene 1.4 times smaller).
inline double mesh_extent_m(const SurfaceFrame& f, bool triangle) {
  if (!triangle) return std::max(f.length_u_m, f.length_v_m);
  // Corners (0, 0), (length_u, 0), (shear, length_v) in (s, t).
  return std::max({f.length_u_m, std::hypot(f.shear_m, f.length_v_m), std::hypot(f.length_u_m - f.shear_m, f.length_v_m)});
}

/// A planar convex polygon of 3 or 4 corners, counter-clockwise seen from the front.
///
/// Its surface parameters (u, v) cover a quad's unit square, u from corner 0 to corner 1 and v
/// from corner 0 to corner 3, a point being the bilinear blend of the corners (iso-parametric
/// lines of a planar quad are straight, so a (u,v) rectangle maps to a planar quad); and a
/// triangle's unit right triangle {u, v >= 0, u + v <= 1}, a point being the affine blend
/// c0 + u (c1 - c0) + v (c2 - c0). A triangle keeps corners[3] == corners[2], so that code
/// reading four corners (bounding boxes, the diagonal-based area and normal) stays right.
struct Surface {
  std::string name;
  std::array<Vec3, 4> corners;
  int corner_count = 4;             ///< 3 (triangle) or 4 (quad)
  Rgb reflectance = Rgb::Zero();    ///< diffuse reflectance per channel, in [0,1)
  Rgb emission_w_m2 = Rgb::Zero();  ///< emitted exitance per channel, W/m^2, >= 0
  bool two_sided = false;           ///< reflects (never emits) on its back too
  /// Mesh setting: at most this many elements along the longer parametric edge (the shorter
  /// edge gets proportionally fewer). Unset: the global mesh density applies.
  std::optional<int> max_divisions;

  bool is_triangle() const { return corner_count == 3; }
  /// The corners in use, in order.
  std::span<const Vec3> polygon() const { return {corners.data(), static_cast<size_t>(corner_count)}; }
  /// Sets a triangle's corners (and corners[3] = c2, corner_count = 3).
  void set_triangle(const Vec3& c0, const Vec3& c1, const Vec3& c2);

  /// The point at parameters (u, v): the bilinear (quad) or affine (triangle) blend of the corners.
  Vec3 point(double u, double v) const;
  /// The parameters (u, v) of a point on the surface's plane (the inverse of point()); nullopt if
  /// the point lies outside the surface (points on its border, up to tol::kQuadEdgeParameter, are
  /// inside and clamped into the parameter domain).
  std::optional<Vec2> parameters(const Vec3& p) const;
  /// The same with the surface's normal() given (computed once for many points).
  std::optional<Vec2> parameters(const Vec3& p, const Vec3& unit_normal) const;
  /// Whether (u, v) lies in the parameter domain (up to tol::kQuadEdgeParameter).
  bool in_domain(double u, double v) const;
  /// Unit normal of the front side.
  Vec3 normal() const;
  double area_m2() const;
  /// Quad: mean length of the two u edges (corner 0->1 and 3->2); triangle: edge 0->1. Metres.
  double length_u_m() const;
  /// Quad: mean length of the two v edges (corner 0->3 and 1->2); triangle: its height over
  /// edge 0->1. Metres.
  double length_v_m() const;
  /// The length grid:N divides (mesh_extent_m()), metres.
  double extent_m() const { return mesh_extent_m({length_u_m(), length_v_m(), shear_m()}, is_triangle()); }
  /// Triangle: the component of edge 0->2 along edge 0->1, metres; quad: 0. With the two lengths
  /// it maps (u,v) to the metric coordinates (s, t) (SurfaceSolution::st()).
  double shear_m() const;
  SurfaceFrame frame() const { return {length_u_m(), length_v_m(), shear_m()}; }
  /// A bound of how far, metres in (s, t), the image of a straight line of the surface may bend
  /// away from the straight line between its ends' images: 0 on a triangle or a parallelogram,
  /// whose (s, t) are affine; on another quad (s, t) follow its bilinear parameters, and the bound
  /// is half its twist |c0 - c1 + c2 - c3| times the most the map from the plane to (s, t)
  /// stretches a length at a corner (1 on a rectangle; 1 / sin of the angle on a sheared quad).
  /// The Cornell box's floor: 1.6 mm, its blocks' feet bent by 0.4 mm at most; random convex
  /// quads bent by at most 0.18 of it (a brute-force inverse of the bilinear map).
  double frame_bend_m() const;
  /// The parameter domain: the unit box of a quad, the lower half of it for a triangle.
  ParamCell domain() const { return parameter_domain(corner_count); }
};

/// A pinhole camera; fov_deg is the vertical field of view in degrees, in (0, 180).
struct Camera {
  std::string name;
  Vec3 eye, target, up;
  double fov_deg = 45.0;
};

struct Scene {
  std::string name;
  std::vector<Surface> surfaces;
  std::vector<Camera> cameras;

  /// Index of the surface with this name, if any.
  std::optional<size_t> find_surface(const std::string& name) const;
};

/// Checks the geometric and radiometric invariants (planar, convex, non-degenerate polygons;
/// reflectance in [0,1); finite non-negative emission; unique names; sane cameras; a scene at
/// least tol::kMinSceneExtent_m across). Throws UserError naming `source` and the offending field.
void validate_scene(const Scene& scene, const std::string& source);

/// Why `reflectance` cannot be a surface's (each channel in [0, 1)), e.g. "must be in [0,1), got
/// 1.5"; empty if it can.
std::string reflectance_problem(const Rgb& reflectance);

/// Why `emission_w_m2` cannot be a surface's (each channel in [0, tol::kMaxEmission_w_m2]); empty
/// if it can.
std::string emission_problem(const Rgb& emission_w_m2);

/// The built-in scene of the paper experiment (design brief): a 4 m x 4 m ground, a 1 m x 1 m
/// light of 40 W/m^2 at 2.5 m, and two perpendicular two-sided walls meeting at (2.6, 2.6).
Scene paper_scene();

/// The built-in Cornell box (docs/cornell.md): the published geometry of "Cornell Box Data"
/// (Cornell University Program of Computer Graphics) in metres, its short and tall blocks, the
/// ceiling light in the ceiling's plane, the commonly used RGB reflectances and light of
/// Bitterli's scene, and the published camera ("published") with two more ("blocks", "corner").
/// The red wall, warped as published, is split into "red_wall.a" and "red_wall.b" by
/// regularise_surfaces(), silently.
Scene cornell_scene();

/// Makes a modeller's polygons fit the surface model, in place, and returns a warning per change:
/// a quad with a repeated corner becomes the triangle of the other three; a quad off its plane by
/// more than tol::kPlanarityRelative of its longest edge, or planar but not convex, is split into
/// two triangles "NAME.a" and "NAME.b": along the diagonal through the reflex corner if it has
/// one, else along its shorter diagonal (corners 0-2 on a tie). Polygons it cannot fix (corners out of order, zero area) are left for
/// validate_scene() to refuse. `source` names the scene in the warnings.
std::vector<std::string> regularise_surfaces(Scene& scene, const std::string& source);

}  // namespace radrecon
