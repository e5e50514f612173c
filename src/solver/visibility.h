#pragma once
// Exact visibility between a receiver point and a convex polygon in a scene of convex quads:
// the shadow each occluder casts on the polygon, seen from the point, is the polygon clipped by
// five half-spaces (beyond the occluder's plane, and inside the four planes through the point
// and the occluder's edges). The visible part is the polygon minus the union of the shadows,
// kept as a list of convex fragments, and its form factor is exact up to round-off. Near the
// shooter, where a point stands poorly for a receiving element, the same form factor averaged
// over the element (area_visible_form_factor()).

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <span>
#include <vector>

#include "core/tolerances.h"
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

/// A box in a plane's 2-D coordinates (PlaneBasis), m; empty when lo > hi, everything when
/// infinite. A NaN bound meets everything: a box decides nothing it cannot.
struct Box2 {
  double lo_u = std::numeric_limits<double>::infinity(), lo_w = lo_u;
  double hi_u = -lo_u, hi_w = -lo_u;
  void add(double u, double w) {
    lo_u = std::min(lo_u, u), hi_u = std::max(hi_u, u);
    lo_w = std::min(lo_w, w), hi_w = std::max(hi_w, w);
  }
  bool meets(const Box2& o) const { return !(o.hi_u < lo_u || hi_u < o.lo_u || o.hi_w < lo_w || hi_w < o.lo_w); }
  static Box2 everything() {
    constexpr double inf = std::numeric_limits<double>::infinity();
    return Box2{-inf, -inf, inf, inf};
  }
};

/// Central projection from a point p in front of a plane {x : normal . x = offset} (normal of
/// unit length) onto it, in the plane's 2-D coordinates. Points of the shooter and of its
/// fragments are projected too, not taken as lying in the plane: a quad may be off its plane
/// within tol::kPlanarityRelative, and projected from p both boxes see what the shadow volumes'
/// planes through p see.
class PlaneBasis {
 public:
  PlaneBasis() = default;
  PlaneBasis(const Vec3& p, const Vec3& normal, double offset)
      : p_(p), normal_(normal), height_p_(normal.dot(p) - offset) {
    u_ = (std::abs(normal.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(normal).normalized();
    w_ = normal.cross(u_);
  }
  /// The box of the projections of a fragment's vertices, widened (tol::kShadowTraceRelative).
  Box2 box(const ConvexPolygon& polygon) const { return projected(polygon.v.data(), polygon.n); }
  /// The box of the occluder's projection, widened (tol::kShadowTraceRelative): it holds the trace
  /// of the occluder's shadow on the plane (the projection of the part of the occluder between p
  /// and the plane) when every corner lies on the plane's side of the plane through p parallel to
  /// it; else everything.
  Box2 trace(const Occluder& o) const { return projected(o.corners.data(), o.corner_count); }

 private:
  Box2 projected(const Vec3* points, int count) const {
    Box2 b;
    for (int i = 0; i < count; ++i) {
      const Vec3 ray = points[i] - p_;
      const double down = -normal_.dot(ray);  // how far the point is from p toward the plane
      if (!(down > 0)) return Box2::everything();
      const Vec3 x = p_ + (height_p_ / down) * ray;
      b.add(u_.dot(x), w_.dot(x));
    }
    return widened(b);
  }
  /// Rounding in the projections, and clip()'s own tolerance, kept out of the boxes' verdict.
  static Box2 widened(Box2 b) {
    const double margin = tol::kShadowTraceRelative * (1 + std::max(b.hi_u - b.lo_u, b.hi_w - b.lo_w) +
                                          std::max({std::abs(b.lo_u), std::abs(b.hi_u), std::abs(b.lo_w), std::abs(b.hi_w)}));
    b.lo_u -= margin, b.lo_w -= margin, b.hi_u += margin, b.hi_w += margin;
    if (!(std::isfinite(b.lo_u) && std::isfinite(b.lo_w) && std::isfinite(b.hi_u) && std::isfinite(b.hi_w)))
      return Box2::everything();
    return b;
  }
  Vec3 p_ = Vec3::Zero(), normal_ = Vec3::UnitZ(), u_ = Vec3::UnitX(), w_ = Vec3::UnitY();
  double height_p_ = 0;
};


/// What a point sees of a convex polygon past many occluders, kept to answer for the polygon's
/// parts (the blocks of a shooting patch, gather()): the visible part of the polygon as the
/// convex fragments visible_form_factor_past() finds, made once, and each part's visible form
/// factor then the sum of the Lambert form factors of those fragments clipped to the part's cone
/// from the point. A form factor depends only on the directions seen, so the fragments, in the
/// whole polygon's plane, stand in for the part wherever the part lies off that plane (within
/// tol::kPlanarityRelative). The same values as visible_form_factor_past() on each part, to
/// round-off: behind hundreds of a model's small triangles, a part then costs a clip of each
/// fragment that its box meets, not the subtraction of every shadow again.
class VisibleFragments {
 public:
  /// Finds the fragments of `polygon` (unit normal `polygon_normal`) that p (unit normal n) sees
  /// past `volumes`. Returns false, keeping nothing usable, when fewer than
  /// tol::kKeptFragmentsShadows shadows meet the polygon's part in front of p: then
  /// visible_form_factor_past() on each part costs less.
  bool find(const Vec3& p, const Vec3& n, const ConvexPolygon& polygon, const Vec3& polygon_normal,
            std::span<const ShadowVolume> volumes);
  /// visible_form_factor_past(p, n, part, polygon_normal, volumes, partly_seen) for a convex
  /// polygon `part` within the polygon given to find() (which must have returned true), to
  /// round-off. `partly_seen`: some of the part lies behind p's plane, or the fragments cover
  /// less of its front than all of it but the slack of tol::kHiddenAreaRelative, and not all of
  /// it is hidden (visible_form_factor_past() asks whether a shadow volume cuts it: the two differ
  /// only for shadows over less than that slack, whose form factor is within it).
  double form_factor(const ConvexPolygon& part, bool* partly_seen = nullptr) const;

 private:
  Vec3 p_ = Vec3::Zero(), n_ = Vec3::UnitZ(), polygon_normal_ = Vec3::UnitZ();
  bool behind_ = false;        ///< p is not in front of the polygon's plane: every part gives 0
  ConvexPolygon front_;        ///< the polygon in front of p's plane
  PlaneBasis plane_;
  std::vector<ConvexPolygon> fragments_;  ///< of front_, visible from p
  std::vector<Box2> boxes_;               ///< the fragments' boxes on the plane
};

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
