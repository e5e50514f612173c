#pragma once
// The parts of a side that surfaces standing on it enclose (scene/contacts.h excluded_regions(),
// (b)): the floor under a block that has no bottom. No light reaches them and none leaves them,
// so an element of the progressive solver partly over one absorbs, reflects and emits over its
// exposed part only, and gathers at points of that part: the element whose centre lay under a
// block's foot gathered nothing while its exposed part was lit, and one whose centre lay outside
// reflected from its whole area, the part under the block into the block's inside (0.7% of the
// power of a closed Cornell box lost at grid:16, an outside-in trial; docs/method.md, "Enclosed
// parts").

#include <cstddef>
#include <span>
#include <vector>

#include "core/vec.h"
#include "mesh/grid_mesh.h"
#include "scene/contacts.h"
#include "scene/scene.h"
#include "solver/gather.h"

namespace radrecon {

/// An element that an enclosed region overlaps.
struct EnclosedElement {
  size_t side = 0, element = 0;  ///< its index in the mesh
  /// The fraction of its area outside the enclosed regions, in [0, 1).
  double exposed = 0;
  /// Points of its exposed part where it gathers, (u, v): the midpoints of the cells of a
  /// regular subdivision of the element (kEnclosedSubdivision per edge) that lie outside every
  /// enclosed region; empty when none does (a sliver) or when every one does (the region only
  /// clips a corner between them): the element then gathers where it would.
  std::vector<Vec2> exposed_uv;
};

/// The regions of one side that surfaces standing on it enclose (scene/contacts.h
/// excluded_regions() (b), not the faced ones: those may be seen), in the side's (s, t) metres,
/// and the fraction of a cell of the side's parameter domain that they leave exposed. Regions are
/// taken as not overlapping each other.
class EnclosedRegions {
 public:
  EnclosedRegions() = default;
  /// The enclosed regions of `set` (a side's contacts), on a side of surface frame `frame`.
  EnclosedRegions(const SideContactSet& set, const SurfaceFrame& frame);
  bool empty() const { return regions_.empty(); }
  const std::vector<Polyline>& regions() const { return regions_; }
  const SurfaceFrame& frame() const { return frame_; }
  /// The fraction of the area of `cell` (its vertices joined by straight lines in (s, t)) outside
  /// every region, in [0, 1]: exactly 1 where no region overlaps it.
  double exposed_fraction(const ParamCell& cell) const;
  /// Whether the parameter point (u, v) lies in a region.
  bool encloses(const Vec2& uv) const;

 private:
  struct Box {
    Vec2 lo, hi;  ///< low and high corners in (s, t)
  };
  std::vector<Polyline> regions_;
  std::vector<Box> boxes_;  ///< by region
  SurfaceFrame frame_;
};

/// Cells of the subdivision along each edge of an element, for EnclosedElement::exposed_uv.
inline constexpr int kEnclosedSubdivision = 8;

/// Every element of the mesh that an enclosed region of its side overlaps, by side and element.
/// Enclosed regions are taken as they are listed (not faced ones: those may be seen), and as not
/// overlapping each other.
std::vector<EnclosedElement> enclosed_elements(const Scene& scene, const Mesh& mesh, const ContactFinder& contacts);
/// The same from each mesh side's contacts, found already (ContactFinder::at(), by mesh side).
std::vector<EnclosedElement> enclosed_elements(const Scene& scene, const Mesh& mesh,
                                               std::span<const SideContactSet> contacts_by_side);

/// Moves the receiver's centre and Gauss points onto the element's exposed part
/// (EnclosedElement::exposed_uv, not empty): its centre to the exposed point nearest their mean;
/// its Gauss points (equal weights, as the Gauss rule's) to one point of each of four groups of
/// them of equal count (halved along u, each half along v), the one nearest the group's mean; to
/// all of them when there are fewer than 4.
void move_to_exposed_part(const Surface& surface, const std::vector<Vec2>& exposed_uv, Receiver& r);

/// The area of the part of the simple polygon `region` that lies inside the convex polygon
/// `convex` (counter-clockwise), in the same 2-D coordinates.
double overlap_area(const Polyline& region, const std::vector<Vec2>& convex);

}  // namespace radrecon
