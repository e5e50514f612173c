#include "scene/covering.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/tolerances.h"
#include "scene/contacts.h"

namespace radrecon {

namespace {

/// Whether one-sided `t` lies in one-sided `s`'s plane (in_plane_of()) facing the other way.
bool back_to_back(const Surface& t, const Surface& s) {
  return !t.two_sided && !s.two_sided && t.normal().dot(s.normal()) < 0 && in_plane_of(t, s);
}

}  // namespace

bool sheet_face(const Scene& scene, size_t surface, std::span<const size_t> candidates) {
  const Surface& s = scene.surfaces[surface];
  if (s.two_sided) return false;
  const SurfaceFrame frame = s.frame();
  const double join_m = tol::kContactJoinRelative * std::max(frame.length_u_m, frame.length_v_m);
  std::vector<Polyline> behind;  // the outlines of the surfaces back to back with it, clipped to it
  for (const size_t k : candidates)
    if (k != surface && back_to_back(scene.surfaces[k], s))
      if (std::optional<Polyline> region = overlap_region(scene.surfaces[k], s)) behind.push_back(std::move(*region));
  if (behind.empty()) return false;
  const int m = tol::kSheetProbes;
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < m; ++i) {
      const Vec2 uv((i + 0.5) / m, (j + 0.5) / m);
      if (s.is_triangle() && uv.sum() >= 1) continue;
      const Vec2 st = frame.st(uv);
      // Inside an outline, or on it (within join_m): a point on the line between two of them
      // (a probe on the diagonal two triangles share) may count as in neither.
      const auto covered = [&](const Polyline& r) {
        if (in_region(r, st)) return true;
        for (size_t e = 0; e < r.size(); ++e) {
          const Vec2 &a = r[e], &b = r[(e + 1) % r.size()];
          if ((a + nearest_on_segment_t(st, a, b) * (b - a) - st).norm() <= join_m) return true;
        }
        return false;
      };
      if (std::none_of(behind.begin(), behind.end(), covered)) return false;
    }
  return true;
}

bool covers(const Scene& scene, size_t other, size_t base, bool base_is_sheet_face, std::span<const size_t> candidates) {
  const Surface &o = scene.surfaces[other], &b = scene.surfaces[base];
  if (!lies_on(o, b)) return false;
  if (!base_is_sheet_face || !back_to_back(o, b)) return true;
  // Back to back with a sheet's face: the sheet's other face, unless it lies on a part of that
  // (a box's bottom standing on the plate overlaps the plate's bottom; the bottom's own pieces
  // only touch along their edges).
  for (const size_t k : candidates) {
    if (k == other || k == base) continue;
    const Surface& t = scene.surfaces[k];
    if (t.normal().dot(o.normal()) > 0 && lies_on(o, t) && overlap_region(o, t)) return true;
  }
  return false;
}

bool in_plane_of(const Surface& other, const Surface& base) {
  const Vec3 n = base.normal();
  const double offset = n.dot(base.corners[0]);
  const double touch_m = contact_tolerance_m(other);
  for (const Vec3& c : other.corners)
    if (std::abs(n.dot(c) - offset) > touch_m) return false;
  return true;
}

bool lies_on(const Surface& other, const Surface& base) {
  return in_plane_of(other, base) && other.area_m2() < (1 - tol::kLyingSmallerRelative) * base.area_m2();
}

}  // namespace radrecon
