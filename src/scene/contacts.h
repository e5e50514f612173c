#pragma once
// Where surfaces touch: the lines on a surface side along which another surface of the scene
// stands on it or passes through it (the foot of a wall on the ground, a block on a floor). The
// radiosity jumps across them (a D0 discontinuity), so reconstructions treat them as barriers.
// And the parts of a side that nothing sees: under a surface lying flat on it, or enclosed by
// surfaces standing on it.

#include <array>
#include <cstddef>
#include <span>
#include <vector>

#include "core/vec.h"
#include "scene/scene.h"
#include "scene/covering.h"
#include "scene/side.h"

namespace radrecon {

/// A segment in a side's metric coordinates (s, t) = (u * length_u_m, v * length_v_m), metres.
struct Segment2 {
  Vec2 a, b;
};

/// The contact lines on `side`, the lines along which the radiosity of the side may jump:
/// - for every other surface whose polygon meets the side's plane (within tol::kContactRelative
///   of that surface's size) from the side's front half-space (or crosses the plane), the segment
///   where it meets it, clipped to the side's quad;
/// - for every other surface lying flat on the side (lies_on()), the edges of its polygon clipped
///   to the side's quad (the outline of the region it covers, see excluded_regions()).
/// Segments that lie on the quad's border are left out (nothing lies beyond them), as are
/// zero-length ones and repeats (both ends within tol::kContactJoinRelative of the side's longer
/// edge of an earlier segment's: a wall's foot along the edge of a box's bottom lying on the
/// floor is one line). Each segment runs from its lexicographically smaller end point; the list
/// is in surface order, a lying surface's edges counter-clockwise around its clipped outline.
std::vector<Segment2> contact_lines(const Scene& scene, SideRef side);


/// The parts of `side` that are neither samples nor queries, as closed polygons in the side's
/// (s, t) metres: each a simple polygon of at least 3 vertices, counter-clockwise in (s, t),
/// starting at its lexicographically smallest vertex, the last vertex joined back to the first
/// (the first is NOT repeated at the end). Regions may overlap. They are
/// (a) covered: every other surface lying flat on the side (lies_on(): coplanar, facing either
///     way, smaller) and covering it (covers(): not the other face of a sheet), its polygon clipped to the side's quad, in surface order. The surface has no
///     thickness, so both sides of a two-sided side are covered alike;
/// (b) enclosed: every area bounded by a closed loop of the side's contact_lines() chained end to
///     end (ends within tol::kContactJoinRelative of the side's longer edge are one point), e.g.
///     the four walls of a box standing on a floor: the bounded faces of that graph of lines
///     after removing dangling lines, each as its outline polygon, unless equal to a covered
///     region of (a) (a box's bottom lying on the floor and its walls standing around it give one
///     region). Lines are joined at their end points only: lines crossing in their middles, or
///     one ending in the middle of another, close no loop, nor do lines dropped along the
///     quad's border (a box standing in a corner of the floor, or the walls of a closed box on
///     its bottom, enclose nothing). An area that a surface standing on one of its lines faces
///     (its front half-space holds it; a two-sided surface faces both ways) may be seen (the
///     floor of a room whose walls face in, even standing inside the floor's edge) or not (the
///     inside of a closed two-sided box): geometry alone cannot tell, and it is left out here
///     (ContactFinder::at() lists it as `faced`; the solver keeps it only if no light reaches
///     it). Two one-sided surfaces back to back on one line (boxes touching) hide each other.
///     Beyond that, enclosure is read from the lines alone: four walls facing out without a roof
///     enclose their yard too.
/// Collinear vertices (within tol::kContactJoinRelative) are dropped, and so are regions no wider
/// than that (a coplanar neighbour touching the side along its border). A quad side that is not a
/// parallelogram maps the vertices exactly and joins them by straight lines in (s, t).
std::vector<Polyline> excluded_regions(const Scene& scene, SideRef side);

/// Whether the point (s, t) lies inside the closed polygon `region` (crossing number; a point on
/// its outline may count either way).
bool in_region(const Polyline& region, const Vec2& st);

/// A side's contact_lines() and excluded_regions() together, and the enclosed areas that a
/// surface standing on their outline faces.
struct SideContactSet {
  std::vector<Segment2> lines;
  /// excluded_regions(), then the faced enclosed areas (the last `faced` of them): each may be
  /// seen or hidden, as light reaches it or not.
  std::vector<Polyline> excluded;
  /// The first `covered` of `excluded` are covered (excluded_regions() (a)); those after them,
  /// up to the faced, enclosed ((b)).
  size_t covered = 0;
  size_t faced = 0;
};

/// The contacts of many sides of one scene: the surfaces' bounding boxes are made once, and a
/// side looks only at the surfaces whose box meets its own (within the contact tolerances), so
/// a scene of n surfaces costs n^2 box tests rather than n^2 plane sections (a model of 11,000
/// triangles: 0.3 s instead of 27 s for the whole solve command outside its solver). The same values as the functions above. The scene must
/// outlive it and not change.
class ContactFinder {
 public:
  explicit ContactFinder(const Scene& scene);
  SideContactSet at(SideRef side) const;

 private:
  const Scene& scene_;
  std::vector<std::array<Vec3, 2>> boxes_;  ///< per surface: its widened bounding box, low and high
};

}  // namespace radrecon
