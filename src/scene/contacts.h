#pragma once
// Where surfaces touch: the lines on a surface side along which another surface of the scene
// stands on it or passes through it (the foot of a wall on the ground, a block on a floor). The
// radiosity jumps across them (a D0 discontinuity), so reconstructions treat them as barriers.

#include <vector>

#include "core/vec.h"
#include "scene/scene.h"
#include "scene/side.h"

namespace radrecon {

/// A segment in a side's metric coordinates (s, t) = (u * length_u_m, v * length_v_m), metres.
struct Segment2 {
  Vec2 a, b;
};

/// The contact lines on `side`: for every other surface whose polygon meets the side's plane
/// (within tol::kContactRelative of that surface's size) from the side's front half-space (or
/// crosses the plane), the segment where it meets it, clipped to the side's quad. Segments that
/// lie on the quad's border are left out (nothing lies beyond them), as are zero-length ones.
/// Each segment runs from its lexicographically smaller end point; the list is in surface order.
/// Not yet: surfaces lying flat on the side (coplanar), whose covered area is not excluded.
std::vector<Segment2> contact_lines(const Scene& scene, SideRef side);

}  // namespace radrecon
