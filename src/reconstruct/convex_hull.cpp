#include "reconstruct/convex_hull.h"

#include <algorithm>
#include <iterator>
#include <limits>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/convex_hull_2.h>

#include "core/check.h"

namespace radrecon {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

/// The point of the segment [a, b] nearest to q.
Vec2 nearest_on_segment(const Vec2& a, const Vec2& b, const Vec2& q) { return a + nearest_on_segment_t(q, a, b) * (b - a); }

}  // namespace

ConvexHull2::ConvexHull2(std::span<const Vec2> points, std::span<const unsigned> subset) {
  std::vector<Kernel::Point_2> in;
  if (subset.empty()) {
    for (const Vec2& p : points) in.emplace_back(p.x(), p.y());
  } else {
    for (const unsigned s : subset) in.emplace_back(points[s].x(), points[s].y());
  }
  RR_CHECK(!in.empty(), "the convex hull of no points");
  std::vector<Kernel::Point_2> hull;
  CGAL::ch_akl_toussaint(in.begin(), in.end(), std::back_inserter(hull), Kernel());
  // CGAL returns counter-clockwise extreme points; all coincident points give one.
  if (hull.empty()) hull.push_back(in.front());
  for (const auto& p : hull) vertices_.emplace_back(p.x(), p.y());
}

Vec2 ConvexHull2::nearest(const Vec2& q) const {
  const size_t n = vertices_.size();
  if (n == 0) return q;
  if (n == 1) return vertices_[0];
  if (n == 2) return nearest_on_segment(vertices_[0], vertices_[1], q);
  bool inside = true;
  for (size_t i = 0; i < n && inside; ++i)
    inside = cross(vertices_[(i + 1) % n] - vertices_[i], q - vertices_[i]) >= 0;
  if (inside) return q;
  Vec2 best = vertices_[0];
  double best_sq = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < n; ++i) {
    const Vec2 p = nearest_on_segment(vertices_[i], vertices_[(i + 1) % n], q);
    const double d_sq = (p - q).squaredNorm();
    if (d_sq < best_sq) best_sq = d_sq, best = p;
  }
  return best;
}

double ConvexHull2::depth(const Vec2& c) const {
  const size_t n = vertices_.size();
  if (n < 3) return 0;
  double d = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < n; ++i) {
    const Vec2 edge = vertices_[(i + 1) % n] - vertices_[i];
    const double signed_distance = cross(edge, c - vertices_[i]) / edge.norm();
    if (!(signed_distance > 0)) return 0;
    d = std::min(d, signed_distance);
  }
  return d;
}

}  // namespace radrecon
