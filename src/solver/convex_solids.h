#pragma once
// Convex solids bounded by a scene's surfaces, such as the Cornell box's blocks, and the faces of
// one that cannot hide anything from a point.
//
// Let a solid be convex, its faces' normals point out of it, and every edge of a face be shared
// with exactly one other face, except edges that all lie in one plane: the solid's opening (a
// block standing on the floor has no bottom). Take a point p strictly outside the solid and not
// strictly beyond its opening's plane. A segment from p that crosses a face F from its back
// (p strictly behind F's plane) is inside the solid just before F; it got there by entering
// through a face G that it crosses from the front, and p lies in front of G's plane (a line
// meets a plane once). It did not enter through the opening: that would need p beyond the
// opening's plane. So G hides every such segment that F does, and F can be left out of p's
// shadows: exact visibility stays exact with half of a box's faces (solver/visibility.h,
// shadow_volumes()).
//
// Points on the solid's surface or inside it keep every face: the floor beneath a block sees
// the light through none of it, as before. But a receiver on one of its faces, facing out,
// looks at the solid from behind its horizon: a segment from it into its front half-space stays
// in front of that face's plane, outside the solid, and no face of it hides anything.

#include <memory>
#include <optional>
#include <vector>

#include "core/tolerances.h"
#include "scene/scene.h"
#include "solver/polygon.h"

namespace radrecon {

/// A convex solid bounded by scene surfaces (the opening aside): the planes of its faces, and of
/// its opening if it has one, with unit normals pointing out of it (HalfSpace::eval() > 0
/// outside, <= 0 on its side).
struct ConvexSolid {
  std::vector<HalfSpace> faces;
  std::optional<HalfSpace> opening;

  /// Whether p lies strictly outside the solid (in front of some face's plane, beyond
  /// tol::kPlaneDistance_m) and not strictly beyond the opening's plane: then a face whose plane
  /// has p strictly behind it hides nothing from p that the faces in front of p do not.
  bool sees_from_outside(const Vec3& p) const;
  /// Whether the solid lies behind the horizon of a receiver at p with unit normal n: n is the
  /// outward normal of one of its faces or of its opening (bit for bit, as a receiver on that
  /// face has it) and p lies on or in front of that plane (to tol::kPlaneDistance_m). Then
  /// none of its faces hides anything from p in front of p's plane.
  bool behind_horizon(const Vec3& p, const Vec3& n) const;
  /// Whether the face whose plane is `face` (one of `faces`) can hide nothing from a receiver at
  /// p with unit normal n that the solid's other faces do not: the solid is behind p's horizon,
  /// or p sees the face from its back (beyond tol::kPlaneDistance_m) from outside the solid.
  bool face_hides_nothing(const HalfSpace& face, const Vec3& p, const Vec3& n) const {
    return behind_horizon(p, n) || (face.eval(p) < -tol::kPlaneDistance_m && sees_from_outside(p));
  }
};

/// The most faces a solid is looked for with: each point that a solid's face could shade tests
/// the solid's planes (ConvexSolid::sees_from_outside() and behind_horizon()), which pays for
/// boxes, prisms and furniture, not for a finely tessellated sphere.
inline constexpr size_t kMaxSolidFaces = 64;

/// The convex solids found among the scene's surfaces: for each surface, the solid it bounds,
/// or null. A surface bounds at most one. Corners are matched exactly (bit for bit), as a model
/// with shared vertices or a scene built from the same numbers gives them; a solid whose
/// corners differ by round-off, or with more than kMaxSolidFaces faces, is not found, which costs
/// time, never accuracy.
std::vector<std::shared_ptr<const ConvexSolid>> find_convex_solids(const Scene& scene);

}  // namespace radrecon
