#pragma once
// Exact visibility between a receiver point and a convex polygon in a scene of convex quads:
// the shadow each occluder casts on the polygon, seen from the point, is the polygon clipped by
// five half-spaces (beyond the occluder's plane, and inside the four planes through the point
// and the occluder's edges). The visible part is the polygon minus the union of the shadows,
// kept as a list of convex fragments, and its form factor is exact up to round-off. Near the
// shooter, where a point stands poorly for a receiving element, the same form factor averaged
// over the element (area_visible_form_factor()).

#include <array>
#include <span>
#include <vector>

#include "scene/scene.h"
#include "solver/convex_solids.h"
#include "solver/polygon.h"

namespace radrecon {

/// A scene surface seen as a potential blocker of light.
struct Occluder {
  std::array<Vec3, 4> corners;  ///< as Surface::corners (a triangle repeats corner 2)
  int corner_count = 4;
  Vec3 centroid;
  HalfSpace plane;  ///< the surface's plane, normal of unit length
  Vec3 bbox_min, bbox_max;
  size_t scene_surface;
  /// The convex solid the surface bounds, with its plane's normal pointing out of it
  /// (solver/convex_solids.h); null if none.
  std::shared_ptr<const ConvexSolid> solid;
};

/// All surfaces of a scene as occluders.
std::vector<Occluder> make_occluders(const Scene& scene);

/// Whether light leaving the front of the quad `source` (unit normal `source_normal`) can reach
/// the front of the quad `receiver`: some corner of each lies strictly in front of the other's
/// plane.
bool quads_face(const std::array<Vec3, 4>& receiver, const Vec3& receiver_normal,
                const std::array<Vec3, 4>& source, const Vec3& source_normal);

/// Occluders that may stand between two quads (their bounding boxes meet the quads' common
/// box), other than the quads' own surfaces.
std::vector<const Occluder*> occluders_between(const std::vector<Occluder>& occluders,
                                               const std::array<Vec3, 4>& a, const std::array<Vec3, 4>& b,
                                               size_t surface_a, size_t surface_b);

/// Occluders whose bounding box meets the box [lo, hi] (a conservative pre-selection for every
/// receiver point and shooter polygon inside that box).
std::vector<const Occluder*> occluders_in_box(const std::vector<Occluder>& occluders,
                                              const Vec3& lo, const Vec3& hi,
                                              size_t skip_surface_a, size_t skip_surface_b);

/// The shadow volume of an occluder seen from a point: the half-spaces beyond the occluder's
/// plane (planes[0]) and inside the planes through the point and its edges (planes[1..sides]; a
/// triangle's third repeated as the fourth). It depends on the point and the occluder alone, so
/// a point that looks at many polygons (the blocks of a shooting patch) makes it once.
/// An occluder hides nothing from p (sides = 0) when p lies in its plane.
struct ShadowVolume {
  std::array<HalfSpace, 5> planes;
  int sides = 0;  ///< 0: the point lies in the occluder's plane, and it hides nothing from it
  const Occluder* occluder = nullptr;
};
ShadowVolume shadow_volume(const Vec3& p, const Occluder& o);
/// The shadow volumes of those of `occluders` that can hide anything from p (unit normal n) in
/// front of p, in their order, into `out` (cleared first): not the faces of a convex solid that
/// its other faces stand in for (ConvexSolid::face_hides_nothing()), nor those whose volume has
/// no sides.
void shadow_volumes(const Vec3& p, const Vec3& n, const std::vector<const Occluder*>& occluders,
                    std::vector<ShadowVolume>& out);

/// The form factor from a differential receiver area at `p` with unit normal `n` to the part of
/// the convex polygon `shooter` that is in front of the receiver and not hidden by any of the
/// `occluders` (which must not include the surfaces of `p` and of `shooter`). Returns 0 when `p`
/// is not in front of the shooter's plane, whose unit normal is `shooter_normal`.
///
/// `partly_seen`, when given, is set to whether p may see only part of the polygon: some of it
/// lies behind p's plane (the horizon) or some occluder's shadow falls on it, and not all of it
/// is hidden. A shooter block of varying radiosity seen in part is not represented by its
/// far field (solver/gather.h gather()).
double visible_form_factor(const Vec3& p, const Vec3& n, const ConvexPolygon& shooter,
                           const Vec3& shooter_normal,
                           const std::vector<const Occluder*>& occluders, bool* partly_seen = nullptr);
/// The same with the occluders' shadow volumes from p already made (shadow_volumes()); the same
/// value, bit for bit.
double visible_form_factor_past(const Vec3& p, const Vec3& n, const ConvexPolygon& shooter, const Vec3& shooter_normal,
                                std::span<const ShadowVolume> volumes, bool* partly_seen = nullptr);

/// visible_form_factor_past() at up to four points of one receiver (unit normal n), each with
/// its own shadow volumes: out[k] for points[k]. The points that see all of the polygon (wholly
/// in front of them, no shadow volume meeting it) share one vectorised contour integral
/// (lambert_form_factors4()); the others go one by one. The same values to round-off.
void visible_form_factors_past(std::span<const Vec3> points, const Vec3& n, const ConvexPolygon& shooter,
                               const Vec3& shooter_normal, std::span<const std::span<const ShadowVolume>> volumes,
                               std::span<double> out);

/// visible_form_factor() at any number of points with the same normal: out[k] for points[k], four
/// at a time through visible_form_factors_past(). The same values to round-off.
void visible_form_factors(std::span<const Vec3> points, const Vec3& n, const ConvexPolygon& shooter,
                          const Vec3& shooter_normal, const std::vector<const Occluder*>& occluders,
                          std::span<double> out);

/// F(R -> S) = (1 / A_R) * integral over R of F(x -> S) dA_x: the form factor from the planar
/// quad R (corners in order around it; its points are the bilinear patch through them, so any
/// element of a grid or quadtree; unit normal `receiver_normal`) to the part of the convex
/// polygon `shooter` it sees past the `occluders` (as visible_form_factor(): not R's surface nor
/// S's). Dimensionless, in [0, 1].
///
/// Adaptive cubature: 2 x 2 Gauss-Legendre points on a square of R's (s, t) parameters, weighted
/// by the patch's Jacobian; a square is split into its quarters while the quarters' sum differs
/// from the square's own estimate by more than `tolerance` (an absolute error of the returned
/// form factor, per square), down to kMaxAreaFormFactorDepth levels. Exact for a receiver far
/// from the shooter up to the cubature's 4th-order error; near a shared edge (a wall standing on
/// the floor) or corner, where F(x -> S) is continuous but not smooth, the splitting follows the
/// corners. Deterministic: the same points in the same order for the same arguments.
double area_visible_form_factor(const std::array<Vec3, 4>& receiver, const Vec3& receiver_normal,
                                const ConvexPolygon& shooter, const Vec3& shooter_normal,
                                const std::vector<const Occluder*>& occluders, double tolerance);

/// Deepest level of area_visible_form_factor()'s splitting (a square of 4^-10 of the receiver):
/// a guard; the tolerance ends the splitting first.
inline constexpr int kMaxAreaFormFactorDepth = 10;

}  // namespace radrecon
