#include "solver/visibility.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "core/tolerances.h"
#include "solver/form_factor.h"
#include "solver/shadow_subtraction.h"

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
