#include "solver/covered.h"

#include <algorithm>

#include "scene/contacts.h"

namespace radrecon {

namespace {

/// The area of a planar polygon, m^2.
double area(const ConvexPolygon& p) {
  Vec3 twice = Vec3::Zero();
  for (int k = 0; k < p.n; ++k) twice += p.v[k].cross(p.v[(k + 1) % p.n]);
  return 0.5 * twice.norm();
}

}  // namespace

std::vector<ConvexPolygon> covers_of(const Scene& scene, size_t surface) {
  std::vector<ConvexPolygon> out;
  for (size_t k = 0; k < scene.surfaces.size(); ++k) {
    if (k == surface || !lies_on(scene.surfaces[k], scene.surfaces[surface])) continue;
    ConvexPolygon p;
    for (const Vec3& c : scene.surfaces[k].polygon()) p.push(c);
    out.push_back(p);
  }
  return out;
}

double exposed_fraction(const ConvexPolygon& part, const Vec3& normal, std::span<const ConvexPolygon> covers) {
  const double whole = area(part);
  if (covers.empty() || !(whole > 0)) return 1.0;
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
    if (!inside.empty()) covered += area(inside);
  }
  return std::clamp(1.0 - covered / whole, 0.0, 1.0);
}

}  // namespace radrecon
