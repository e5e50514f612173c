#include "solver/visibility.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "core/tolerances.h"
#include "solver/form_factor.h"

namespace radrecon {

std::vector<Occluder> make_occluders(const Scene& scene) {
  std::vector<Occluder> out;
  const std::vector<std::shared_ptr<const ConvexSolid>> solids = find_convex_solids(scene);
  for (size_t k = 0; k < scene.surfaces.size(); ++k) {
    const Surface& s = scene.surfaces[k];
    Occluder o;
    o.corners = s.corners;
    o.corner_count = s.corner_count;
    o.centroid = Vec3::Zero();
    for (const Vec3& c : s.polygon()) o.centroid += c / s.corner_count;
    Vec3 n = s.normal();
    o.plane = HalfSpace{n, n.dot(o.centroid)};
    o.bbox_min = o.bbox_max = s.corners[0];
    for (const Vec3& c : s.corners) {
      o.bbox_min = o.bbox_min.cwiseMin(c);
      o.bbox_max = o.bbox_max.cwiseMax(c);
    }
    o.scene_surface = k;
    o.solid = solids[k];
    out.push_back(o);
  }
  return out;
}

std::vector<const Occluder*> occluders_in_box(const std::vector<Occluder>& occluders,
                                              const Vec3& lo, const Vec3& hi,
                                              size_t skip_surface_a, size_t skip_surface_b) {
  std::vector<const Occluder*> out;
  const double slack = tol::kPlaneDistance_m;
  for (const Occluder& o : occluders) {
    if (o.scene_surface == skip_surface_a || o.scene_surface == skip_surface_b) continue;
    bool apart = (o.bbox_min.array() > hi.array() + slack).any() ||
                 (o.bbox_max.array() < lo.array() - slack).any();
    if (!apart) out.push_back(&o);
  }
  return out;
}

bool quads_face(const std::array<Vec3, 4>& receiver, const Vec3& receiver_normal,
                const std::array<Vec3, 4>& source, const Vec3& source_normal) {
  bool receiver_in_front = false, source_in_front = false;
  for (const Vec3& c : receiver)
    receiver_in_front = receiver_in_front || source_normal.dot(c - source[0]) > tol::kPlaneDistance_m;
  for (const Vec3& c : source)
    source_in_front = source_in_front || receiver_normal.dot(c - receiver[0]) > tol::kPlaneDistance_m;
  return receiver_in_front && source_in_front;
}

std::vector<const Occluder*> occluders_between(const std::vector<Occluder>& occluders,
                                               const std::array<Vec3, 4>& a, const std::array<Vec3, 4>& b,
                                               size_t surface_a, size_t surface_b) {
  Vec3 lo = a[0], hi = a[0];
  for (const auto* quad : {&a, &b})
    for (const Vec3& c : *quad) {
      lo = lo.cwiseMin(c);
      hi = hi.cwiseMax(c);
    }
  return occluders_in_box(occluders, lo, hi, surface_a, surface_b);
}

ShadowVolume shadow_volume(const Vec3& p, const Occluder& o) {
  ShadowVolume volume;
  volume.occluder = &o;
  const double side_p = o.plane.eval(p);
  if (std::abs(side_p) <= tol::kPlaneDistance_m) return volume;  // p in the occluder's plane
  // Beyond the occluder's plane, as seen from p.
  volume.planes[0] = (side_p > 0 ? o.plane.complement() : o.plane).with_tolerance();
  const int n = o.corner_count;
  for (int i = 0; i < n; ++i) {
    Vec3 m = (o.corners[i] - p).cross(o.corners[(i + 1) % n] - p);
    if (m.dot(o.centroid - p) < 0) m = -m;
    volume.planes[i + 1] = HalfSpace{m, m.dot(p)}.with_tolerance();
  }
  if (n == 3) volume.planes[4] = volume.planes[3];  // a triangle's cone has three sides: clip by one twice
  volume.sides = n;
  return volume;
}

void shadow_volumes(const Vec3& p, const Vec3& n, const std::vector<const Occluder*>& occluders,
                    std::vector<ShadowVolume>& out) {
  out.clear();
  for (const Occluder* o : occluders) {
    if (o->solid && o->solid->face_hides_nothing(o->plane, p, n)) continue;
    const ShadowVolume v = shadow_volume(p, *o);
    if (v.sides > 0) out.push_back(v);
  }
}

namespace {

/// Whether the shadow volume can hide any point of `polygon`: some vertex of it lies inside each
/// of the volume's half-spaces (else the polygon lies wholly outside one of them).
bool meets(const ShadowVolume& volume, const ConvexPolygon& polygon) {
  if (volume.sides == 0) return false;  // the point lies in the occluder's plane
  for (int h = 0; h <= volume.sides; ++h) {
    bool any_inside = false;
    for (int i = 0; i < polygon.n && !any_inside; ++i) any_inside = volume.planes[h].eval(polygon.v[i]) > 0;
    if (!any_inside) return false;
  }
  return true;
}

/// The polygon clipped by every half-space, in turn; `whole` set to whether each kept all of it.
ConvexPolygon clip_all(const ConvexPolygon& poly, const std::array<HalfSpace, 5>& volume, bool& whole) {
  std::array<ConvexPolygon, 2> cuts;  // each cut into the one the last did not fill
  const ConvexPolygon* now = &poly;
  std::array<double, ConvexPolygon::kCapacity> d;
  whole = true;
  for (size_t k = 0; k < volume.size(); ++k) {
    switch (distances(*now, volume[k], d)) {
      case Side::inside: continue;
      case Side::outside: whole = false; return {};
      case Side::across: {
        ConvexPolygon& next = now == &cuts[0] ? cuts[1] : cuts[0];
        cut(*now, d, 1.0, next);
        whole = false;
        if (next.empty()) return {};
        now = &next;
      }
    }
  }
  return *now;
}

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
  Vec3 p_, normal_, u_, w_;
  double height_p_;
};

/// The fewest shadows on a shooter for which visible_form_factor_past() rejects shadows by boxes.
constexpr size_t kBoxedShadows = 16;

/// Each of subtract()'s five clips adds at most one vertex: a polygon with more vertices than this
/// is cut in two first (subtract_large()).
constexpr int kMaxSubtractVertices = ConvexPolygon::kCapacity - 6;

/// Appends the convex pieces of q (at most kMaxSubtractVertices vertices) minus the
/// intersection of the half-spaces to `out`.
void subtract(const ConvexPolygon& q, const std::array<HalfSpace, 5>& volume,
              std::vector<ConvexPolygon>& out) {
  // A fragment wholly outside one of the half-spaces (to clip()'s tolerance) misses the shadow:
  // keep it whole rather than cut it along the planes before that one (fewer, larger fragments;
  // the same visible polygon).
  for (const HalfSpace& h : volume) {
    const double on_plane = h.on_plane >= 0 ? h.on_plane : tol::kPlaneDistance_m * h.normal.norm();
    bool outside = true;
    for (int i = 0; i < q.n && outside; ++i) outside = h.eval(q.v[i]) <= on_plane;
    if (outside) {
      out.push_back(q);
      return;
    }
  }
  // Peel off the part outside each half-space in turn; what is left inside all five is hidden.
  std::array<ConvexPolygon, 2> rest;
  ConvexPolygon outside;
  const ConvexPolygon* left = &q;
  for (size_t k = 0; k < volume.size(); ++k) {
    ConvexPolygon& inside = rest[k % 2];
    split(*left, volume[k], inside, outside);
    if (!outside.empty()) out.push_back(outside);
    if (inside.empty()) break;
    left = &inside;
  }
}

/// subtract() for a polygon of any size: one with too many vertices is cut into two convex halves
/// along a diagonal first (form factors add up over the pieces), so the fragments of any number of
/// overlapping shadows fit in a ConvexPolygon and the result stays exact. Rare: kept out of line.
[[gnu::noinline]] void subtract_large(const ConvexPolygon& q, const std::array<HalfSpace, 5>& volume,
                                      std::vector<ConvexPolygon>& out) {
  if (q.n <= kMaxSubtractVertices) {
    subtract(q, volume, out);
    return;
  }
  ConvexPolygon a, b;
  const int m = q.n / 2;
  for (int i = 0; i <= m; ++i) a.push(q.v[i]);
  for (int i = m; i < q.n; ++i) b.push(q.v[i]);
  b.push(q.v[0]);
  subtract_large(a, volume, out);
  subtract_large(b, volume, out);
}

}  // namespace

double visible_form_factor(const Vec3& p, const Vec3& n, const ConvexPolygon& shooter,
                           const Vec3& shooter_normal,
                           const std::vector<const Occluder*>& occluders, bool* partly_seen) {
  thread_local std::vector<ShadowVolume> volumes;
  shadow_volumes(p, n, occluders, volumes);
  return visible_form_factor_past(p, n, shooter, shooter_normal, volumes, partly_seen);
}

double visible_form_factor_past(const Vec3& p, const Vec3& n, const ConvexPolygon& shooter, const Vec3& shooter_normal,
                                std::span<const ShadowVolume> volumes, bool* partly_seen) {
  bool partly_unused = false;
  bool& partly = partly_seen != nullptr ? *partly_seen : partly_unused;
  partly = false;
  if (shooter.empty()) return 0.0;
  if (shooter_normal.dot(p - shooter.v[0]) <= tol::kPlaneDistance_m) return 0.0;
  ConvexPolygon front = clip_to_horizon(p, n, shooter);
  if (front.empty()) return 0.0;
  for (int i = 0; i < shooter.n && !partly; ++i) partly = n.dot(shooter.v[i] - p) < 0;

  // Common cases first: no occluder, or a single one, cast a shadow on the polygon.
  const ShadowVolume* first = nullptr;
  ConvexPolygon first_shadow;
  size_t k = 0;
  for (; k < volumes.size(); ++k) {
    if (!meets(volumes[k], front)) continue;
    bool whole = false;
    ConvexPolygon shadow = clip_all(front, volumes[k].planes, whole);
    if (shadow.empty()) continue;
    // Every clip left the polygon whole: the occluder hides all of it.
    if (whole) {
      partly = false;
      return 0.0;
    }
    if (first == nullptr) {
      first = &volumes[k];
      first_shadow = shadow;
    } else {
      break;  // a second shadow: fall back to the general difference below
    }
  }
  const double unoccluded = lambert_form_factor(p, n, front);
  if (first == nullptr) return unoccluded;
  partly = true;
  if (k == volumes.size())
    return std::max(0.0, unoccluded - lambert_form_factor(p, n, first_shadow));

  // General case: subtract every shadow volume that meets the polygon from the fragments of the
  // visible polygon. Nearest occluders first: their shadows are the largest seen from p, so the
  // fragments shrink (or vanish, ending the loop) early and later shadows cut fewer of them.
  struct Shadow {
    double distance_m2;
    const ShadowVolume* volume;
  };
  thread_local std::vector<Shadow> shadows;
  shadows.clear();
  for (const ShadowVolume& v : volumes)
    if (meets(v, front)) shadows.push_back({(v.occluder->centroid - p).squaredNorm(), &v});
  std::stable_sort(shadows.begin(), shadows.end(),
                   [](const Shadow& x, const Shadow& y) { return x.distance_m2 < y.distance_m2; });
  // With many shadows (a light seen past hundreds of a model's small triangles), each one's trace
  // on the shooter's plane lies within the occluder's projection from p (PlaneBasis): a fragment
  // whose projection's box misses that one's misses the shadow, and is kept whole without
  // subtract()'s plane tests. With a few there are
  // few fragments, and the boxes would cost more than they save.
  thread_local std::vector<Box2> traces, boxes;
  std::optional<PlaneBasis> plane;
  traces.clear();
  if (shadows.size() >= kBoxedShadows) {
    plane.emplace(p, shooter_normal, shooter_normal.dot(shooter.v[0]));
    for (const Shadow& shadow : shadows) traces.push_back(plane->trace(*shadow.volume->occluder));
  }
  thread_local std::vector<ConvexPolygon> fragments, pieces;
  // The fragments left after each shadow, with their boxes when `Boxed`. A fragment the shadow
  // misses stays where it is (no copy: there are hundreds of shadows); one it cuts is replaced
  // by its first piece, and its other pieces go to the end, past the fragments still to cut.
  const auto subtract_shadows = [&]<bool Boxed>() {
    fragments.assign(1, front);
    if constexpr (Boxed) boxes.assign(1, plane->box(front));
    for (size_t k_shadow = 0; k_shadow < shadows.size(); ++k_shadow) {
      const size_t count = fragments.size();
      size_t kept = 0;  // fragments [0, kept) survive; the rest of [0, f) are gone
      for (size_t f = 0; f < count; ++f) {
        const auto keep = [&](size_t from) {
          if (from != kept) {
            fragments[kept] = fragments[from];
            if constexpr (Boxed) boxes[kept] = boxes[from];
          }
          ++kept;
        };
        if constexpr (Boxed) {
          if (!boxes[f].meets(traces[k_shadow])) {
            keep(f);
            continue;
          }
        }
        pieces.clear();
        const ConvexPolygon& q = fragments[f];
        if (q.n <= kMaxSubtractVertices) subtract(q, shadows[k_shadow].volume->planes, pieces);
        else subtract_large(q, shadows[k_shadow].volume->planes, pieces);
        if (pieces.empty()) continue;
        fragments[kept] = pieces[0];
        if constexpr (Boxed) boxes[kept] = plane->box(pieces[0]);
        ++kept;
        for (size_t i = 1; i < pieces.size(); ++i) {
          fragments.push_back(pieces[i]);
          if constexpr (Boxed) boxes.push_back(plane->box(pieces[i]));
        }
      }
      // Close the gap between the survivors and the pieces appended after them.
      if (kept < count) {
        fragments.erase(fragments.begin() + static_cast<std::ptrdiff_t>(kept),
                        fragments.begin() + static_cast<std::ptrdiff_t>(count));
        if constexpr (Boxed)
          boxes.erase(boxes.begin() + static_cast<std::ptrdiff_t>(kept), boxes.begin() + static_cast<std::ptrdiff_t>(count));
      }
      if (fragments.empty()) return;
    }
  };
  if (plane) subtract_shadows.template operator()<true>();
  else subtract_shadows.template operator()<false>();
  if (fragments.empty()) {
    partly = false;
    return 0.0;
  }
  double visible = 0.0;
  for (const ConvexPolygon& q : fragments) visible += lambert_form_factor(p, n, q);
  return visible;
}

namespace {

/// Whether visible_form_factor_past() would find p seeing all of the polygon: p in front of its
/// plane, the polygon wholly in front of p's (to clip()'s tolerance, as clip_to_horizon() decides
/// it) and no shadow volume meeting it. Then the form factor is lambert_form_factor() of the
/// polygon itself.
bool sees_whole(const Vec3& p, const Vec3& n, const ConvexPolygon& shooter, const Vec3& shooter_normal,
                std::span<const ShadowVolume> volumes) {
  if (shooter.empty() || shooter_normal.dot(p - shooter.v[0]) <= tol::kPlaneDistance_m) return false;
  const double offset = n.dot(p), on_plane = tol::kPlaneDistance_m * n.norm();
  for (int i = 0; i < shooter.n; ++i)
    if (!(n.dot(shooter.v[i]) - offset >= -on_plane)) return false;  // (NaN: as clip(), which empties it)
  for (const ShadowVolume& v : volumes)
    if (meets(v, shooter)) return false;
  return true;
}

}  // namespace

void visible_form_factors_past(std::span<const Vec3> points, const Vec3& n, const ConvexPolygon& shooter,
                               const Vec3& shooter_normal, std::span<const std::span<const ShadowVolume>> volumes,
                               std::span<double> out) {
  RR_CHECK(points.size() <= 4 && volumes.size() == points.size() && out.size() == points.size(),
           "visible_form_factors_past: up to four points, each with its shadow volumes");
  std::array<Vec3, 4> batch;
  std::array<size_t, 4> slot{};
  size_t whole = 0;
  for (size_t k = 0; k < points.size(); ++k) {
    if (sees_whole(points[k], n, shooter, shooter_normal, volumes[k])) {
      batch[whole] = points[k];
      slot[whole++] = k;
    } else {
      out[k] = visible_form_factor_past(points[k], n, shooter, shooter_normal, volumes[k]);
    }
  }
  if (whole == 0) return;
  for (size_t k = whole; k < 4; ++k) batch[k] = batch[0];
  std::array<double, 4> f;
  lambert_form_factors4(batch, n, shooter, f);
  for (size_t k = 0; k < whole; ++k) out[slot[k]] = f[k];
}

void visible_form_factors(std::span<const Vec3> points, const Vec3& n, const ConvexPolygon& shooter,
                          const Vec3& shooter_normal, const std::vector<const Occluder*>& occluders,
                          std::span<double> out) {
  RR_CHECK(out.size() == points.size(), "visible_form_factors: one value per point");
  thread_local std::array<std::vector<ShadowVolume>, 4> volumes;
  std::array<std::span<const ShadowVolume>, 4> spans;
  for (size_t first = 0; first < points.size(); first += 4) {
    const size_t count = std::min<size_t>(4, points.size() - first);
    for (size_t k = 0; k < count; ++k) {
      shadow_volumes(points[first + k], n, occluders, volumes[k]);
      spans[k] = volumes[k];
    }
    visible_form_factors_past(points.subspan(first, count), n, shooter, shooter_normal, {spans.data(), count},
                              out.subspan(first, count));
  }
}

}  // namespace radrecon
