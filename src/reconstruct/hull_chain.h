#pragma once
// The hull of a CGAL Delaunay triangulation through every sample on it up to rounding. Samples
// meant to lie on one line (the centroids along a triangle's hypotenuse, a survey track) land a
// little inside or outside it once rounded; CGAL's exact predicates then make a hull edge from
// one end of the row to the other over the samples just inside, and the value "at the nearest
// point of the hull" blended the row's two ends (an export's texels by a triangle's hypotenuse
// erred by 32 of 255 levels). Each such edge is split at those samples, which lie under it in a
// fan of slivers: the faces inside it whose vertex across it is within tol::kHullChainRelative
// of its length from its line. Whether a query is on the hull up to rounding is still judged
// against CGAL's edge (hull_edge_distance(), delaunay.h); its value is then taken on the
// nearest piece.
// Internal to reconstruct/: CGAL's types stay out of the public headers.

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <span>
#include <utility>
#include <vector>

#include "core/tolerances.h"
#include "core/vec.h"

namespace radrecon {

/// A piece of a hull edge as hull_chain() gives it.
template <class Face_handle>
struct HullChainEdge {
  unsigned a = 0, b = 0;  ///< sample indices, in the order of the hull edge's ends (a, then b)
  Face_handle inner;      ///< the finite face on the piece
  int corner = 0;         ///< that face's corner across the piece
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
    if (!dt.is_infinite(c)) {
      const Vec2 pa = points[p.a->info()], pb = points[p.b->info()];
      const Vec2 pc = points[c->info()];
      const auto along = [&](const Vec2& x) { return (x - a0).dot(ab) / length_sq; };
      const double t = along(pc);
      const bool on_line = std::abs(cross(ab, pc - a0)) <= tol::kHullChainRelative * length_sq;  // |cross| = distance x length
      if (on_line && t > along(pa) && t < along(pb)) {
        const Face_handle before = p.inner->neighbor(ib), after = p.inner->neighbor(ia);  // across (a, c), (c, b)
        if (!dt.is_infinite(before) && !dt.is_infinite(after)) {
          pending.push_back({c, p.b, after});
          pending.push_back({p.a, c, before});
          continue;
        }
      }
    }
    out.push_back({p.a->info(), p.b->info(), p.inner, ic});
  }
}

/// A bound on the band of every hull edge of a triangulation (hull_edge_distance(), delaunay.h:
/// its pieces' depth, plus kHullEdgeBandRelative of its length, plus kCoordinateRounding of the
/// largest coordinate): no point farther than at(q) from the hull is on it up to rounding.
struct HullBandBound {
  double fixed_m = 0;              ///< the largest depth plus kHullEdgeBandRelative of the longest edge, metres
  double largest_coordinate = 0;   ///< the hull vertices' largest |coordinate|, metres
  double at(const Vec2& q) const { return fixed_m + tol::kCoordinateRounding * std::max(largest_coordinate, q.cwiseAbs().maxCoeff()); }
};

/// For q outside the hull of `dt` (a 2-D triangulation; `points` its samples by vertex info) and
/// within rounding of it: the infinite face whose hull edge is nearest to q, found from
/// `outside`, an infinite face whose hull edge q lies outside of (what CGAL's locate() returns
/// there, which depends on where its walk began: along collinear hull edges, such as a lattice's
/// side, any of them). Walks along the hull from it while the distance falls. That finds a local
/// minimum of the distance only: from a point farther out, a long, thin hull has two, and the
/// one found depended on the query before (an outside-in trial); the nearest point of the hull
/// is found by reconstruct/nearest_segment.h. Within rounding of the hull the walk's edge is q's.
///
/// `band_bound_m` bounds every hull edge's band (HullBandBound::at()): q farther outside
/// `outside`'s line than that lies at least as far from the whole hull (it stands on the line's
/// other side), so it is outside by more than rounding, and `outside` is returned as it is, with
/// no walk (a raster's cells far outside the hull would each walk a share of it).
template <class DT>
typename DT::Face_handle nearest_hull_face(const DT& dt, std::span<const Vec2> points, const Vec2& q,
                                           typename DT::Face_handle outside, double band_bound_m) {
  using Face_handle = typename DT::Face_handle;
  const auto infinite = dt.infinite_vertex();
  {
    const int i = outside->index(infinite);
    const Vec2 a = points[outside->vertex(DT::ccw(i))->info()], ab = points[outside->vertex(DT::cw(i))->info()] - a;
    if (std::abs(cross(ab, q - a)) > band_bound_m * ab.norm()) return outside;  // |cross| = distance x length
  }
  const auto distance_sq_to = [&](const Face_handle& e) {
    const int i = e->index(infinite);
    const Vec2 a = points[e->vertex(DT::ccw(i))->info()], b = points[e->vertex(DT::cw(i))->info()];
    return (a + nearest_on_segment_t(q, a, b) * (b - a) - q).squaredNorm();
  };
  // The infinite faces on the hull edges at e's two ends.
  const auto hull_neighbours = [&](const Face_handle& e) {
    const int i = e->index(infinite);
    return std::array<Face_handle, 2>{e->neighbor(DT::ccw(i)), e->neighbor(DT::cw(i))};
  };
  Face_handle nearest = outside;
  double nearest_sq = distance_sq_to(outside);
  for (const Face_handle& first : hull_neighbours(outside)) {
    Face_handle previous = outside, e = first;
    for (double d = distance_sq_to(e); d < nearest_sq; d = distance_sq_to(e)) {
      nearest_sq = d, nearest = e;
      const std::array<Face_handle, 2> next = hull_neighbours(e);
      previous = std::exchange(e, next[0] == previous ? next[1] : next[0]);
    }
  }
  return nearest;
}

/// Every hull edge of `dt` (a 2-D triangulation) split by hull_chain(): the pieces, hull edge by
/// hull edge, and by each hull edge (its ends as the infinite face has them: ccw(i), cw(i)) the
/// range of its pieces.
template <class DT>
struct HullChains {
  /// A hull edge's pieces, [begin, end) in `pieces`, and the largest distance of their ends from
  /// its line, metres (0 when it is whole).
  struct Range {
    size_t begin = 0, end = 0;
    double depth_m = 0;
  };
  std::vector<HullChainEdge<typename DT::Face_handle>> pieces;
  std::map<std::pair<unsigned, unsigned>, Range> of_edge;

  explicit HullChains(const DT& dt, std::span<const Vec2> points) {
    const auto inf = dt.infinite_vertex();
    auto fc = dt.incident_faces(inf), done = fc;
    double longest_m = 0, deepest_m = 0;
    do {
      Range r{pieces.size(), 0, 0};
      hull_chain(dt, fc, points, pieces);
      r.end = pieces.size();
      const int i = fc->index(inf);
      const Vec2 a = points[fc->vertex(DT::ccw(i))->info()], ab = points[fc->vertex(DT::cw(i))->info()] - a;
      for (size_t k = r.begin + 1; k < r.end; ++k)
        r.depth_m = std::max(r.depth_m, std::abs(cross(ab, points[pieces[k].a] - a)) / ab.norm());
      of_edge[key(fc, i)] = r;
      longest_m = std::max(longest_m, ab.norm());
      deepest_m = std::max(deepest_m, r.depth_m);
      for (const int end : {DT::ccw(i), DT::cw(i)})
        band_bound.largest_coordinate = std::max(band_bound.largest_coordinate, points[fc->vertex(end)->info()].cwiseAbs().maxCoeff());
    } while (++fc != done);
    band_bound.fixed_m = deepest_m + tol::kHullEdgeBandRelative * longest_m;
  }

  /// A bound on every hull edge's band.
  HullBandBound band_bound;

  /// The range of the hull edge of infinite face f, whose infinite vertex is its corner i.
  const Range& range(typename DT::Face_handle f, int i) const { return of_edge.at(key(f, i)); }
  /// Its pieces.
  std::span<const HullChainEdge<typename DT::Face_handle>> of(typename DT::Face_handle f, int i) const {
    const Range& r = range(f, i);
    return std::span(pieces).subspan(r.begin, r.end - r.begin);
  }
  /// How far inside it its pieces' ends lie, metres.
  double depth_m(typename DT::Face_handle f, int i) const { return range(f, i).depth_m; }

  /// The piece of `range` nearest to q, and the parameter t in [0, 1] of q's nearest point on it,
  /// from its end a (ties: the first in the range).
  static std::pair<const HullChainEdge<typename DT::Face_handle>*, double> nearest(
      std::span<const HullChainEdge<typename DT::Face_handle>> range, std::span<const Vec2> points, const Vec2& q) {
    double best = std::numeric_limits<double>::infinity(), best_t = 0;
    const HullChainEdge<typename DT::Face_handle>* found = range.empty() ? nullptr : &range.front();
    for (const auto& e : range) {
      const Vec2 a = points[e.a], ab = points[e.b] - a;
      const double t = nearest_on_segment_t(q, a, points[e.b]);
      const double d = (a + t * ab - q).squaredNorm();
      if (d < best) best = d, best_t = t, found = &e;
    }
    return {found, best_t};
  }

 private:
  static std::pair<unsigned, unsigned> key(typename DT::Face_handle f, int i) {
    return {f->vertex(DT::ccw(i))->info(), f->vertex(DT::cw(i))->info()};
  }
};

}  // namespace radrecon
