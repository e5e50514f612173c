#pragma once
// The Delaunay triangulation of the natural-neighbour methods (natural_neighbour.h) and the
// coordinates of a query over the boundary of its conflict zone: Sibson's (the areas the query's
// Voronoi cell steals, by CGAL) or Laplace's (the lengths of its Voronoi edges over the distances).
// Internal to reconstruct/: the CGAL types stay out of the public headers.

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include "core/vec.h"
#include "reconstruct/natural_neighbour.h"

namespace radrecon::nn {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<unsigned, K>;  ///< info: the sample index
using Tds = CGAL::Triangulation_data_structure_2<Vb>;
using Delaunay = CGAL::Delaunay_triangulation_2<K, Tds>;
using Point = K::Point_2;

/// Turns CGAL's (vertex, weight) pairs into (sample index, weight): the output functor of CGAL's
/// coordinate functions.
struct VertexIndex {
  using argument_type = std::pair<Delaunay::Vertex_handle, K::FT>;
  using result_type = std::pair<unsigned, double>;
  result_type operator()(const argument_type& p) const { return {p.first->info(), p.second}; }
};

/// The circumcentre of the triangle (p, a, b), relative to p (in the points' unit).
inline Vec2 circumcentre_from(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 u = a - p, v = b - p;
  const double d = 2 * cross(u, v);
  const double uu = u.squaredNorm(), vv = v.squaredNorm();
  return Vec2((v.y() * uu - u.y() * vv) / d, (u.x() * vv - v.x() * uu) / d);
}

/// The natural-neighbour coordinates of p, a point strictly inside the triangulation's hull and on
/// no vertex, over the boundary `hole` of its conflict zone (as get_boundary_of_conflicts() gives
/// it, counterclockwise), into `out` as (sample index, weight) pairs, unnormalised. Returns the
/// sum of the weights, or 0 when they are not defined (a degenerate hole).
///   Sibson:  weight_i = the area of p's Voronoi cell taken from sample i's (CGAL's
///            natural_neighbor_coordinates_2).
///   Laplace: weight_i = |e_i| / |p - x_i|, e_i the edge of p's Voronoi cell facing sample i
///            (Belikov & Semenov 1997; Sugihara 1999: non-Sibsonian coordinates). Its ends are the
///            circumcentres of the triangles (p, a, b) over the two boundary edges at x_i.
/// Returns the weights' sum, 0 when there are none (a hole reaching the infinite vertex).
double hole_coordinates(const Delaunay& dt, const Point& p, const std::vector<Delaunay::Edge>& hole,
                        NeighbourRule rule, std::vector<std::pair<unsigned, double>>& out);

/// The conflict zone of a query (the Delaunay faces whose circumcircles hold it) with what its
/// Sibson coordinates need, kept so that the next query can reuse it: a raster's neighbouring
/// queries mostly have the same zone, and then only the new Voronoi vertices (the circumcentres
/// of the query with each boundary edge) change. Everything is relative to `origin`, the hole
/// vertex of smallest sample index, and in a canonical order, so that the coordinates of a point
/// do not depend on which query built the zone (a batch gives what one point at a time gives).
class ConflictZone {
 public:
  /// Builds the zone from CGAL's conflict faces and boundary (get_conflicts_and_boundary()) of a
  /// query inside the triangulation's hull. `hull_vertex(i)`: whether sample i is on the hull.
  /// False (the zone unusable: CGAL's own coordinates then) when a conflict face is infinite or
  /// the boundary edges do not join up into one cycle around the zone.
  template <class HullVertex>
  bool build(const Delaunay& dt, const std::vector<Delaunay::Face_handle>& conflicts,
             const std::vector<Delaunay::Edge>& hole, HullVertex hull_vertex);

  /// Whether q (another query) certainly has this zone: every circle test of the zone decided
  /// beyond its rounding bound (tol::kConflictZoneTestRelative). Only a zone away from the hull
  /// (no face with a hull vertex) is ever reused: near the hull the hull rules of the caller
  /// apply (a point on a hull edge up to rounding).
  bool holds(const Vec2& q) const;

  /// Sibson's coordinates of q (metres), a point of this zone, into `out` as (sample index,
  /// weight) pairs, unnormalised (the area of q's Voronoi cell taken from each neighbour's, in
  /// the zone's scaled units, scale_^2 per m^2). Returns their sum, or 0 when not finite.
  double sibson(const Vec2& q, std::vector<std::pair<unsigned, double>>& out) const;

  bool reusable() const { return reusable_; }
  void forget() { reusable_ = false; }
  /// A face of the zone: a walk's start for the next query.
  Delaunay::Face_handle face() const { return face_; }

 private:
  /// s(q) = a (qx^2 + qy^2) + b qx + c qy + d (q in the zone's scaled coordinates): the 4 x 4 in-circle
  /// determinant of a face's corners and q, positive inside its circle. Faces inside the zone
  /// must stay positive, the faces across its boundary negative.
  struct CircleTest {
    double a, b, c, d;
  };
  static CircleTest circle_test(const std::array<Vec2, 3>& corners);

  Vec2 origin_ = Vec2::Zero();  ///< metres
  /// Coordinates below are (x - origin_) times this (a power of two, 1/m): their largest
  /// magnitude over the zone's and the tested faces' corners lies in [1, 2).
  double scale_ = 1;
  std::vector<unsigned> vertex_;     ///< hole vertices v_k, counterclockwise from the smallest index
  std::vector<Vec2> at_;             ///< their positions (scaled coordinates)
  std::vector<Vec2> centre_;         ///< circumcentres of the conflict faces (scaled coordinates)
  std::vector<int> chain_first_;     ///< v_k's chain: chain_[chain_first_[k], chain_first_[k + 1])
  std::vector<int> chain_;           ///< centres of the faces around v_k, from edge k's to edge k-1's
  std::vector<CircleTest> inside_, outside_;
  bool reusable_ = false;
  Delaunay::Face_handle face_;
};

template <class HullVertex>
bool ConflictZone::build(const Delaunay& dt, const std::vector<Delaunay::Face_handle>& conflicts,
                         const std::vector<Delaunay::Edge>& hole, HullVertex hull_vertex) {
  reusable_ = false;
  const size_t m = hole.size();
  if (m < 3 || conflicts.empty()) return false;
  for (const auto& f : conflicts)
    if (dt.is_infinite(f)) return false;
  // CGAL gives each boundary edge as (f, i), f the face outside the zone: the edge runs
  // counterclockwise around the zone from a = cw(i) to b = ccw(i) of f. Order the edges into
  // the cycle v_0 v_1 ... from the smallest sample index.
  struct HoleEdge {
    Delaunay::Vertex_handle a, b;
    Delaunay::Face_handle face, outer;
  };
  thread_local std::vector<HoleEdge> cycle;
  cycle.clear();
  size_t start = 0;
  for (const auto& [f, i] : hole) {
    cycle.push_back({f->vertex(Delaunay::cw(i)), f->vertex(Delaunay::ccw(i)), f->neighbor(i), f});
    if (dt.is_infinite(cycle.back().a) || dt.is_infinite(cycle.back().b)) return false;
    if (cycle.back().a->info() < cycle[start].a->info()) start = cycle.size() - 1;
  }
  // CGAL lists them counterclockwise: each edge starts where the one before ends.
  for (size_t k = 0; k < m; ++k)
    if (cycle[k].b != cycle[(k + 1) % m].a) return false;
  std::rotate(cycle.begin(), cycle.begin() + static_cast<std::ptrdiff_t>(start), cycle.end());
  const Point& o = cycle.front().a->point();
  origin_ = Vec2(o.x(), o.y());
  // Coordinates relative to the origin, scaled by a power of two (exactly) to an extent in
  // [1, 2): the tests' degree-4 terms neither underflow nor overflow at any sample spacing.
  double extent_m = 0;
  const auto widen = [&](const Delaunay::Face_handle& f) {
    for (int k = 0; k < 3; ++k)
      if (!dt.is_infinite(f->vertex(k))) {
        const Point& p = f->vertex(k)->point();
        extent_m = std::max({extent_m, std::abs(p.x() - origin_.x()), std::abs(p.y() - origin_.y())});
      }
  };
  for (const auto& f : conflicts) widen(f);
  for (const HoleEdge& e : cycle) widen(e.outer);
  if (!(extent_m > 0) || !std::isfinite(extent_m)) return false;
  scale_ = std::ldexp(1.0, -std::ilogb(extent_m));
  if (!std::isfinite(scale_)) return false;
  const auto rel = [&](const Point& p) { return Vec2((p.x() - origin_.x()) * scale_, (p.y() - origin_.y()) * scale_); };
  vertex_.clear();
  at_.clear();
  for (const HoleEdge& e : cycle) {
    vertex_.push_back(e.a->info());
    at_.push_back(rel(e.a->point()));
  }
  centre_.clear();
  bool near_hull = false;
  for (const auto& f : conflicts) {
    const Vec2 a = rel(f->vertex(0)->point());
    centre_.push_back(a + circumcentre_from(a, rel(f->vertex(1)->point()), rel(f->vertex(2)->point())));
    for (int k = 0; k < 3; ++k) near_hull = near_hull || hull_vertex(f->vertex(k)->info());
  }
  const auto index_of = [&](const Delaunay::Face_handle& f) {
    const auto it = std::find(conflicts.begin(), conflicts.end(), f);
    return it == conflicts.end() ? -1 : static_cast<int>(it - conflicts.begin());
  };
  // v_k's chain: the faces around it from edge k's face to edge k-1's, within the zone.
  chain_first_.assign(1, 0);
  chain_.clear();
  for (size_t k = 0; k < m; ++k) {
    const HoleEdge& out = cycle[k];
    const HoleEdge& in = cycle[(k + m - 1) % m];
    Delaunay::Face_handle f = out.face;
    Delaunay::Vertex_handle w = out.b;
    for (size_t step = 0;; ++step) {
      const int index = index_of(f);
      if (index < 0 || step > conflicts.size()) return false;
      chain_.push_back(index);
      if (f == in.face) break;
      const Delaunay::Vertex_handle third = f->vertex(3 - f->index(out.a) - f->index(w));
      f = f->neighbor(f->index(w));
      w = third;
    }
    chain_first_.push_back(static_cast<int>(chain_.size()));
  }
  face_ = conflicts.front();
  // Reused only away from the hull, where every face tested is finite.
  inside_.clear();
  outside_.clear();
  if (near_hull) return true;
  const auto corners = [&](const Delaunay::Face_handle& f) {
    std::array<Vec2, 3> c;
    for (int k = 0; k < 3; ++k) c[static_cast<size_t>(k)] = rel(f->vertex(k)->point());
    return c;
  };
  for (const auto& f : conflicts) inside_.push_back(circle_test(corners(f)));
  for (const HoleEdge& e : cycle) {
    if (dt.is_infinite(e.outer)) return true;
    outside_.push_back(circle_test(corners(e.outer)));
  }
  reusable_ = true;
  return true;
}

}  // namespace radrecon::nn
