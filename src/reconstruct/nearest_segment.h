#pragma once
// The segment nearest to a point among many (the pieces of a triangulation's hull), through a
// hierarchy of their boxes searched nearest box first: every query is exact, whatever the
// queries before it. A walk along a convex hull from where a point was located, while the
// distance fell, stopped at a local minimum: the distance from a point outside a long, thin
// hull to its edges has two (a sheared triangle of samples: the value at the hull's "nearest"
// point was 0.52 where it is 0.97, and depended on the query before; an outside-in trial).

#include <cstddef>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "core/box_hierarchy.h"
#include "core/vec.h"

namespace radrecon {

class NearestSegment {
 public:
  /// Segments (points[a], points[b]) by sample indices; `keys` (one per segment) break ties
  /// between segments at the same distance: the smaller key wins. `points` must outlive this.
  NearestSegment(std::span<const Vec2> points, std::vector<std::pair<unsigned, unsigned>> segments,
                 std::vector<std::pair<unsigned, unsigned>> keys);

  struct Found {
    size_t segment = 0;  ///< its index in the list given
    double t = 0;        ///< the nearest point's parameter on it, from its end a, in [0, 1]
  };
  /// The segment nearest to q (ties: the smaller key); none when there are no segments or every
  /// distance overflows (q beyond any finite distance).
  std::optional<Found> nearest(const Vec2& q) const;

  bool empty() const { return segments_.empty(); }

 private:
  std::span<const Vec2> points_;
  std::vector<std::pair<unsigned, unsigned>> segments_, keys_;
  std::vector<BoxNode> nodes_;
  std::vector<int> order_;
};

}  // namespace radrecon
