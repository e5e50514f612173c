#pragma once
// The hull of a CGAL Delaunay triangulation through every sample on it up to rounding. Samples
// meant to lie on one line (the centroids along a triangle's hypotenuse, a survey track) land a
// little inside or outside it once rounded; CGAL's exact predicates then make a hull edge from
// one end of the row to the other over the samples just inside, and the value "at the nearest
// point of the hull" blended the row's two ends (an export's texels by a triangle's hypotenuse
// erred by 32 of 255 levels). Each such edge is split at those samples, which lie under it in a
// fan of slivers: the faces inside it whose vertex across it is within
// tol::kDelaunaySliverRelative of its length from its line.
// Internal to reconstruct/: CGAL's types stay out of the public headers.

#include <cmath>
#include <span>
#include <utility>
#include <vector>

#include "core/tolerances.h"
#include "core/vec.h"

namespace radrecon {

/// One edge of the hull as hull_chain() gives it.
template <class Face_handle>
struct HullChainEdge {
  unsigned a = 0, b = 0;  ///< sample indices, counter-clockwise around the hull (a, then b)
  Face_handle inner;      ///< the finite face on the edge
  int corner = 0;         ///< that face's corner across the edge
  double height_m = 0;    ///< that corner's distance from the edge's line
};

/// The hull edge of `infinite_face` (a face of `dt` at its infinite vertex) split at the samples
/// on it up to rounding, in order from its first end to its last, into `out` (appended).
/// `points` are the samples by vertex info.
template <class DT>
void hull_chain(const DT& dt, typename DT::Face_handle infinite_face, std::span<const Vec2> points,
                std::vector<HullChainEdge<typename DT::Face_handle>>& out) {
  using Face_handle = typename DT::Face_handle;
  using Vertex_handle = typename DT::Vertex_handle;
  const int i = infinite_face->index(dt.infinite_vertex());
  const Vertex_handle first = infinite_face->vertex(DT::ccw(i)), last = infinite_face->vertex(DT::cw(i));
  const Vec2 a0 = points[first->info()], ab = points[last->info()] - a0;
  const double length_sq = ab.squaredNorm();
  // Pieces still to split, last first, so that they are taken from the first end on.
  struct Piece {
    Vertex_handle a, b;
    Face_handle inner;
  };
  std::vector<Piece> pending{{first, last, infinite_face->neighbor(i)}};
  while (!pending.empty()) {
    const Piece p = pending.back();
    pending.pop_back();
    const int ia = p.inner->index(p.a), ib = p.inner->index(p.b), ic = 3 - ia - ib;
    const Vertex_handle c = p.inner->vertex(ic);
    const Vec2 pa = points[p.a->info()], pb = points[p.b->info()];
    if (!dt.is_infinite(c)) {
      const Vec2 pc = points[c->info()];
      const auto along = [&](const Vec2& x) { return (x - a0).dot(ab) / length_sq; };
      const double t = along(pc);
      const bool on_line = std::abs(cross(ab, pc - a0)) <= tol::kDelaunaySliverRelative * length_sq;
      if (on_line && t > along(pa) && t < along(pb)) {
        const Face_handle before = p.inner->neighbor(ib), after = p.inner->neighbor(ia);  // across (a, c), (c, b)
        if (!dt.is_infinite(before) && !dt.is_infinite(after)) {
          pending.push_back({c, p.b, after});
          pending.push_back({p.a, c, before});
          continue;
        }
      }
    }
    const Vec2 edge = pb - pa;
    const double height_m = dt.is_infinite(c) ? 0.0 : std::abs(cross(edge, points[c->info()] - pa)) / edge.norm();
    out.push_back({p.a->info(), p.b->info(), p.inner, ic, height_m});
  }
}

}  // namespace radrecon
