#pragma once
// Small helpers of the solver's visibility tests: a surface as a convex polygon, and a scene's
// occluders as the pointer list visible_form_factor() takes.

#include <vector>

#include "solver/visibility.h"

namespace radrecon::testing_support {

inline ConvexPolygon polygon_of(const Surface& s) {
  ConvexPolygon poly;
  for (const Vec3& c : s.polygon()) poly.push(c);
  return poly;
}

/// Every occluder but those of the surfaces a and b (the receiver's and the shooter's).
inline std::vector<const Occluder*> all_but(const std::vector<Occluder>& occ, size_t a, size_t b) {
  std::vector<const Occluder*> out;
  for (const Occluder& o : occ)
    if (o.scene_surface != a && o.scene_surface != b) out.push_back(&o);
  return out;
}

}  // namespace radrecon::testing_support
