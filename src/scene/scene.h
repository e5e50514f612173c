#pragma once
// The scene model: planar convex quads with diffuse reflectance and emission, and cameras.
// All lengths in metres; emission is exitance in W/m^2.

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "core/vec.h"

namespace radrecon {

/// A planar convex quad. Corners are counter-clockwise seen from the front. The surface
/// parameters are u in [0,1] from corner 0 to corner 1 and v in [0,1] from corner 0 to corner 3;
/// a point is the bilinear blend of the corners (iso-parametric lines of a planar quad are
/// straight, so a (u,v) rectangle maps to a planar quad).
struct Surface {
  std::string name;
  std::array<Vec3, 4> corners;
  Rgb reflectance = Rgb::Zero();    ///< diffuse reflectance per channel, in [0,1)
  Rgb emission_w_m2 = Rgb::Zero();  ///< emitted exitance per channel, W/m^2, >= 0
  bool two_sided = false;           ///< reflects (never emits) on its back too
  /// Mesh setting: at most this many elements along the longer parametric edge (the shorter
  /// edge gets proportionally fewer). Unset: the global mesh density applies.
  std::optional<int> max_divisions;

  /// The point at parameters (u, v): the bilinear blend of the corners.
  Vec3 point(double u, double v) const;
  /// The parameters (u, v) of a point on the quad's plane (the inverse of point()); nullopt if
  /// the point lies outside the quad (points on its border, up to tol::kQuadEdgeParameter, are
  /// inside and clamped to [0,1]).
  std::optional<Vec2> parameters(const Vec3& p) const;
  /// Unit normal of the front side.
  Vec3 normal() const;
  double area_m2() const;
  /// Mean length of the two u edges (corner 0->1 and 3->2), metres.
  double length_u_m() const;
  /// Mean length of the two v edges (corner 0->3 and 1->2), metres.
  double length_v_m() const;
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

/// Checks the geometric and radiometric invariants (planar, convex, non-degenerate quads;
/// reflectance in [0,1); finite non-negative emission; unique names; sane cameras).
/// Throws UserError naming `source` and the offending field.
void validate_scene(const Scene& scene, const std::string& source);

/// The built-in scene of the paper experiment (design brief): a 4 m x 4 m ground, a 1 m x 1 m
/// light of 40 W/m^2 at 2.5 m, and two perpendicular two-sided walls meeting at (2.6, 2.6).
Scene paper_scene();

}  // namespace radrecon
