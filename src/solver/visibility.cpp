#include "solver/visibility.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
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

/// The fewest shadows on a shooter for which visible_form_factor_past() rejects shadows by boxes.
constexpr size_t kBoxedShadows = 16;

/// Each of subtract()'s five clips adds at most one vertex: a polygon with more vertices than this
/// is cut in two first (subtract_large()).
constexpr int kMaxSubtractVertices = ConvexPolygon::kCapacity - 6;

/// Whether q lies wholly outside one of the half-spaces (to clip()'s tolerance): then it misses
/// their intersection.
bool misses(const ConvexPolygon& q, const std::array<HalfSpace, 5>& volume) {
  for (const HalfSpace& h : volume) {
    const double on_plane = h.on_plane >= 0 ? h.on_plane : tol::kPlaneDistance_m * h.normal.norm();
    bool outside = true;
    for (int i = 0; i < q.n && outside; ++i) outside = h.eval(q.v[i]) <= on_plane;
    if (outside) return true;
  }
  return false;
}

/// Appends the convex pieces of q (at most kMaxSubtractVertices vertices) minus the
/// intersection of the half-spaces to `out`.
void subtract(const ConvexPolygon& q, const std::array<HalfSpace, 5>& volume,
              std::vector<ConvexPolygon>& out) {
  // A fragment wholly outside one of the half-spaces (to clip()'s tolerance) misses the shadow:
  // keep it whole rather than cut it along the planes before that one (fewer, larger fragments;
  // the same visible polygon).
  if (misses(q, volume)) {
    out.push_back(q);
    return;
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
/// A convex polygon cut in two convex halves along a diagonal (form factors and areas add up
/// over the halves).
void halve(const ConvexPolygon& q, ConvexPolygon& a, ConvexPolygon& b) {
  const int m = q.n / 2;
  for (int i = 0; i <= m; ++i) a.push(q.v[i]);
  for (int i = m; i < q.n; ++i) b.push(q.v[i]);
  b.push(q.v[0]);
}

[[gnu::noinline]] void subtract_large(const ConvexPolygon& q, const std::array<HalfSpace, 5>& volume,
                                      std::vector<ConvexPolygon>& out) {
  if (q.n <= kMaxSubtractVertices) {
    subtract(q, volume, out);
    return;
  }
  ConvexPolygon a, b;
  halve(q, a, b);
  subtract_large(a, volume, out);
  subtract_large(b, volume, out);
}

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
                      std::vector<ConvexPolygon>& fragments, std::vector<Box2>& boxes) {
  std::stable_sort(shadows.begin(), shadows.end(),
                   [](const Shadow& x, const Shadow& y) { return x.distance_m2 < y.distance_m2; });
  thread_local std::vector<ConvexPolygon> pieces;
  const auto subtract_one = [&](const ConvexPolygon& q, const Shadow& shadow) {
    pieces.clear();
    if (q.n <= kMaxSubtractVertices) subtract(q, shadow.volume->planes, pieces);
    else subtract_large(q, shadow.volume->planes, pieces);
  };
  fragments.clear();
  boxes.clear();
  if (plane == nullptr) {
    // Shadow by shadow over the fragments left. A fragment the shadow misses stays where it is;
    // one it cuts is replaced by its first piece, and its other pieces go to the end, past the
    // fragments still to cut.
    fragments.push_back(front);
    for (const Shadow& shadow : shadows) {
      const size_t count = fragments.size();
      size_t kept = 0;  // fragments [0, kept) survive; the rest of [0, f) are gone
      for (size_t f = 0; f < count; ++f) {
        subtract_one(fragments[f], shadow);
        if (pieces.empty()) continue;
        fragments[kept++] = pieces[0];
        for (size_t i = 1; i < pieces.size(); ++i) fragments.push_back(pieces[i]);
      }
      // Close the gap between the survivors and the pieces appended after them.
      fragments.erase(fragments.begin() + static_cast<std::ptrdiff_t>(kept),
                      fragments.begin() + static_cast<std::ptrdiff_t>(count));
      if (fragments.empty()) return;
    }
    return;
  }
  // With boxes: fragment by fragment, depth first, each with the shadows after the one that made
  // it whose traces its box meets (listed again for each new piece: a piece is smaller than the
  // fragment it came from, and meets fewer traces). Each fragment meets the shadows in the same
  // order as above: the same visible polygon, in fragments listed in another order (and a
  // fragment of many vertices that a shadow misses is kept whole rather than halved).
  thread_local std::vector<Box2> traces;
  traces.clear();
  for (const Shadow& shadow : shadows) traces.push_back(plane->trace(*shadow.volume->occluder));
  struct Work {
    ConvexPolygon fragment;
    Box2 box;
    size_t first, last;  ///< its shadows: candidates[first, last), indices into `shadows`
  };
  thread_local std::vector<std::uint32_t> candidates;
  thread_local std::vector<Work> stack;
  candidates.clear();
  stack.clear();
  const auto push = [&](const ConvexPolygon& fragment, const Box2& box, size_t from, size_t to) {
    const size_t first = candidates.size();
    for (size_t i = from; i < to; ++i)
      if (box.meets(traces[candidates[i]])) candidates.push_back(candidates[i]);
    stack.push_back({fragment, box, first, candidates.size()});
  };
  for (size_t k = 0; k < shadows.size(); ++k) candidates.push_back(static_cast<std::uint32_t>(k));
  push(front, plane->box(front), 0, shadows.size());
  while (!stack.empty()) {
    const Work work = stack.back();
    stack.pop_back();
    // What later-pushed (so already finished) work listed after this one's candidates is spent.
    candidates.resize(work.last);
    size_t i = work.first;
    while (i < work.last && misses(work.fragment, shadows[candidates[i]].volume->planes)) ++i;
    if (i == work.last) {  // past every shadow
      fragments.push_back(work.fragment);
      boxes.push_back(work.box);
      continue;
    }
    subtract_one(work.fragment, shadows[candidates[i]]);
    for (const ConvexPolygon& piece : pieces) push(piece, plane->box(piece), i + 1, work.last);
  }
}

/// The area of a convex polygon, m^2.
double area_m2(const ConvexPolygon& q) {
  Vec3 twice = Vec3::Zero();
  for (int i = 1; i + 1 < q.n; ++i) twice += (q.v[i] - q.v[0]).cross(q.v[i + 1] - q.v[0]);
  return 0.5 * twice.norm();
}

/// Sums over the pieces of polygons inside a cone: their Lambert form factors and areas.
struct InCone {
  double form_factor = 0, area_m2 = 0;
  bool any = false;  ///< some piece was not empty
};

/// Adds q's part inside every half-space of `cone` to `sums`, its form factor as seen from p
/// (unit normal n). A part that would outgrow a ConvexPolygon (each clip adds at most one vertex)
/// is cut in two along a diagonal first: form factors and areas add up over the pieces.
void add_in_cone(ConvexPolygon q, std::span<const HalfSpace> cone, const Vec3& p, const Vec3& n, InCone& sums) {
  for (size_t i = 0; i < cone.size(); ++i) {
    if (q.n >= ConvexPolygon::kCapacity) {
      ConvexPolygon a, b;
      halve(q, a, b);
      add_in_cone(a, cone.subspan(i), p, n, sums);
      add_in_cone(b, cone.subspan(i), p, n, sums);
      return;
    }
    q = clip(q, cone[i]);
    if (q.empty()) return;
  }
  sums.any = true;
  sums.form_factor += lambert_form_factor(p, n, q);
  sums.area_m2 += area_m2(q);
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
  // visible polygon.
  thread_local std::vector<Shadow> shadows;
  shadows.clear();
  for (const ShadowVolume& v : volumes)
    if (meets(v, front)) shadows.push_back({(v.occluder->centroid - p).squaredNorm(), &v});
  std::optional<PlaneBasis> plane;
  if (shadows.size() >= kBoxedShadows) plane.emplace(p, shooter_normal, shooter_normal.dot(shooter.v[0]));
  thread_local std::vector<ConvexPolygon> fragments;
  thread_local std::vector<Box2> boxes;
  subtract_shadows(shadows, front, plane ? &*plane : nullptr, fragments, boxes);
  if (fragments.empty()) {
    partly = false;
    return 0.0;
  }
  double visible = 0.0;
  for (const ConvexPolygon& q : fragments) visible += lambert_form_factor(p, n, q);
  return visible;
}

bool VisibleFragments::find(const Vec3& p, const Vec3& n, const ConvexPolygon& polygon, const Vec3& polygon_normal,
                            std::span<const ShadowVolume> volumes) {
  p_ = p, n_ = n, polygon_normal_ = polygon_normal;
  fragments_.clear();
  boxes_.clear();
  behind_ = polygon.empty() || polygon_normal.dot(p - polygon.v[0]) <= tol::kPlaneDistance_m;
  if (!behind_) front_ = clip_to_horizon(p, n, polygon);
  behind_ = behind_ || front_.empty();
  if (behind_) return true;  // every part gives 0
  thread_local std::vector<Shadow> shadows;
  shadows.clear();
  for (const ShadowVolume& v : volumes)
    if (meets(v, front_)) shadows.push_back({(v.occluder->centroid - p).squaredNorm(), &v});
  if (shadows.size() < tol::kKeptFragmentsShadows) return false;
  plane_ = PlaneBasis(p, polygon_normal, polygon_normal.dot(polygon.v[0]));
  subtract_shadows(shadows, front_, &plane_, fragments_, boxes_);
  return true;
}

double VisibleFragments::form_factor(const ConvexPolygon& part, bool* partly_seen) const {
  bool partly_unused = false;
  bool& partly = partly_seen != nullptr ? *partly_seen : partly_unused;
  partly = false;
  if (behind_ || part.empty() || polygon_normal_.dot(p_ - part.v[0]) <= tol::kPlaneDistance_m) return 0.0;
  const ConvexPolygon front = clip_to_horizon(p_, n_, part);
  if (front.empty()) return 0.0;
  // The part's cone from p: the half-spaces through p and each edge of the part (not of its
  // front: the fragments lie in front of p already, and a short edge that the horizon cut off a
  // corner would tilt its plane), the part's middle inside.
  Vec3 middle = Vec3::Zero();
  for (int i = 0; i < part.n; ++i) middle += part.v[i] / part.n;
  std::array<HalfSpace, ConvexPolygon::kCapacity> cone;
  for (int i = 0; i < part.n; ++i) {
    Vec3 m = (part.v[i] - p_).cross(part.v[(i + 1) % part.n] - p_);
    if (m.dot(middle - p_) < 0) m = -m;
    cone[static_cast<size_t>(i)] = HalfSpace{m, m.dot(p_)}.with_tolerance();
  }
  const std::span<const HalfSpace> sides(cone.data(), static_cast<size_t>(part.n));
  const Box2 box = plane_.box(front);
  InCone seen;
  for (size_t f = 0; f < fragments_.size(); ++f)
    if (boxes_[f].meets(box)) add_in_cone(fragments_[f], sides, p_, n_, seen);
  if (!seen.any) return 0.0;  // all of it hidden
  for (int i = 0; i < part.n && !partly; ++i) partly = n_.dot(part.v[i] - p_) < 0;
  // Else compare what the fragments show of the part with its front, both in the polygon's plane,
  // up to the slack of clip()'s snapping along the part's outline (tol::kHiddenAreaRelative).
  if (!partly) {
    InCone whole;
    add_in_cone(front_, sides, p_, n_, whole);
    double outline_m = 0;
    for (int i = 0; i < front.n; ++i) outline_m += (front.v[(i + 1) % front.n] - front.v[i]).norm();
    const double slack_m2 = tol::kHiddenAreaRelative * whole.area_m2 + tol::kPlaneDistance_m * outline_m;
    partly = seen.area_m2 < whole.area_m2 - slack_m2;
  }
  return seen.form_factor;
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
