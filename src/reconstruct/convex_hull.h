#pragma once
// The convex hull of a small planar point set (CGAL's Akl-Toussaint, exact predicates),
// and the nearest point of it to a query: where a local fit (reconstruct/local_multiquadric.h)
// stops trusting itself and holds its boundary value instead of extrapolating.

#include <span>
#include <vector>

#include "core/vec.h"

namespace radrecon {

class ConvexHull2 {
 public:
  ConvexHull2() = default;
  /// The hull of points[subset] (or of all points when subset is empty); at least one point.
  /// Collinear points give a segment, coincident ones a point.
  ConvexHull2(std::span<const Vec2> points, std::span<const unsigned> subset);

  /// The hull's vertices, counter-clockwise, no three collinear (1 or 2 for a point or segment).
  const std::vector<Vec2>& vertices() const { return vertices_; }

  /// q itself when it lies in the hull (boundary included) or the hull is empty (default
  /// constructed), else the hull's nearest point to q.
  Vec2 nearest(const Vec2& q) const;

  /// The distance from c to the hull's boundary when c lies inside, else 0: every point within
  /// it of c is in the hull (a shortcut past nearest()).
  double depth(const Vec2& c) const;

 private:
  std::vector<Vec2> vertices_;
};

}  // namespace radrecon
