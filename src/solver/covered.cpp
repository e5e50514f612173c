#include "solver/covered.h"

#include <algorithm>

#include "core/tolerances.h"
#include "scene/contacts.h"

namespace radrecon {

std::vector<std::vector<size_t>> covering_surfaces(const Scene& scene) {
  const size_t n = scene.surfaces.size();
  std::vector<std::vector<size_t>> out(n);
  // Bounding boxes, widened by a margin far below any surface's size: a cover outside a
  // surface's box hides none of it.
  std::vector<Vec3> lo(n), hi(n);
  double extent = 0;
  for (size_t k = 0; k < n; ++k) {
    lo[k] = hi[k] = scene.surfaces[k].corners[0];
    for (const Vec3& c : scene.surfaces[k].polygon()) lo[k] = lo[k].cwiseMin(c), hi[k] = hi[k].cwiseMax(c);
    extent = std::max(extent, (hi[k] - lo[k]).maxCoeff());
  }
  const double margin = tol::kContactRelative * extent;
  std::vector<size_t> order(n);
  for (size_t k = 0; k < n; ++k) order[k] = k;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return lo[a].x() < lo[b].x() || (lo[a].x() == lo[b].x() && a < b); });
  // By base, the surfaces in its plane whose box meets its own (in surface order after the
  // sort below), and those of them lying on it (lies_on()); a pair facing opposite ways asks
  // whether base is one face of a sheet (covers(), contacts.h), over the former.
  std::vector<std::vector<size_t>> in_plane(n), lying(n);
  const auto add = [&](size_t other, size_t base) {
    if (!in_plane_of(scene.surfaces[other], scene.surfaces[base])) return;
    in_plane[base].push_back(other);
    if (lies_on(scene.surfaces[other], scene.surfaces[base])) lying[base].push_back(other);
  };
  for (size_t i = 0; i < n; ++i)
    for (size_t j = i + 1; j < n && lo[order[j]].x() <= hi[order[i]].x() + margin; ++j) {
      const size_t a = order[i], b = order[j];
      if (((lo[a].array() - margin) <= hi[b].array()).all() && (lo[b].array() <= (hi[a].array() + margin)).all()) {
        add(a, b);
        add(b, a);
      }
    }
  for (size_t base = 0; base < n; ++base) {
    if (lying[base].empty()) continue;
    const Surface& b = scene.surfaces[base];
    std::sort(in_plane[base].begin(), in_plane[base].end());  // surface order, whatever the sweep's
    std::sort(lying[base].begin(), lying[base].end());
    const bool facing_back = std::any_of(lying[base].begin(), lying[base].end(),
                                         [&](size_t c) { return scene.surfaces[c].normal().dot(b.normal()) < 0; });
    const bool sheet = facing_back && sheet_face(scene, base, in_plane[base]);
    for (const size_t cover : lying[base])
      if (covers(scene, cover, base, sheet, in_plane[base])) out[base].push_back(cover);
  }
  return out;
}

std::vector<std::vector<ConvexPolygon>> covers_by_surface(const Scene& scene) {
  const std::vector<std::vector<size_t>> covering = covering_surfaces(scene);
  std::vector<std::vector<ConvexPolygon>> out(covering.size());
  for (size_t base = 0; base < covering.size(); ++base)
    for (const size_t cover : covering[base]) {
      ConvexPolygon p;
      for (const Vec3& c : scene.surfaces[cover].polygon()) p.push(c);
      out[base].push_back(p);
    }
  return out;
}

double exposed_fraction(std::span<const Vec3> corners, const Vec3& normal, std::span<const ConvexPolygon> covers) {
  if (covers.empty()) return 1.0;
  ConvexPolygon part;
  for (const Vec3& c : corners) part.push(c);
  const double whole = area_m2(part);
  if (!(whole > 0)) return 1.0;
  double covered = 0;
  for (const ConvexPolygon& cover : covers) {
    // The part clipped to the cover's inside: the half-spaces of its edges, each bounded by the
    // plane through the edge along the normal (the cover turned counter-clockwise about it).
    Vec3 turn = Vec3::Zero();
    for (int k = 0; k < cover.n; ++k) turn += cover.v[k].cross(cover.v[(k + 1) % cover.n]);
    const double sign = turn.dot(normal) >= 0 ? 1.0 : -1.0;
    ConvexPolygon inside = part;
    for (int k = 0; k < cover.n && !inside.empty(); ++k) {
      const Vec3& a = cover.v[k];
      const Vec3 inward = sign * normal.cross(cover.v[(k + 1) % cover.n] - a);
      inside = clip(inside, HalfSpace{inward, inward.dot(a)});
    }
    if (!inside.empty()) covered += area_m2(inside);
  }
  return std::clamp(1.0 - covered / whole, 0.0, 1.0);
}

}  // namespace radrecon
