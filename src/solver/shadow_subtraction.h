#pragma once
// The part of a convex polygon (a shooting patch, or a block of it) that a point sees past
// occluders: the polygon minus the union of the occluders' shadows (visibility.h ShadowVolume),
// kept as convex fragments. visible_form_factor_past() sums their form factors for one polygon;
// VisibleFragments keeps them for the parts of a patch.

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <span>
#include <vector>

#include "core/tolerances.h"
#include "solver/polygon.h"
#include "solver/visibility.h"

namespace radrecon {

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

/// Whether the shadow volume can hide any point of `polygon`: some vertex of it lies inside each
/// of the volume's half-spaces (else the polygon lies wholly outside one of them).
bool meets(const ShadowVolume& volume, const ConvexPolygon& polygon);

/// A shadow volume that meets the polygon, with its occluder's squared distance from the point.
struct Shadow {
  double distance_m2;
  const ShadowVolume* volume;
};

/// The convex fragments of `front` (a polygon in front of the point) that the point sees past
/// `shadows` (the volumes that meet it; sorted here) into `fragments`. Nearest occluders first:
/// their shadows are the largest seen from the point, so the fragments shrink (or vanish, ending
/// the loop) early and later shadows cut fewer of them. With `plane` (the polygon's plane seen from
/// the point: for many shadows, a light seen past hundreds of a model's small triangles) each
/// shadow's trace on the plane lies within its occluder's projection, so a fragment whose
/// projection's box misses that one's misses the shadow, and is kept whole without subtract()'s
/// plane tests; the fragments' boxes are then left in `boxes`. With a few shadows there are few
/// fragments, and the boxes would cost more than they save.
void subtract_shadows(std::vector<Shadow>& shadows, const ConvexPolygon& front, const PlaneBasis* plane,
                      std::vector<ConvexPolygon>& fragments, std::vector<Box2>& boxes);

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

}  // namespace radrecon
