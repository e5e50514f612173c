#pragma once
// NaturalNeighbour's implementation (natural_neighbour.h), shared by natural_neighbour.cpp (the
// triangulation of all samples, the queries) and natural_neighbour_visible.cpp (the coordinates
// over the samples a query sees past barriers). Internal to reconstruct/.

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include "core/check.h"
#include "core/once.h"
#include "core/tolerances.h"
#include "reconstruct/delaunay.h"
#include "reconstruct/hull_chain.h"
#include "reconstruct/kdtree.h"
#include "reconstruct/natural_neighbour.h"
#include "reconstruct/nearest_segment.h"
#include "reconstruct/nn_delaunay.h"
#include "reconstruct/sibson_c1.h"
#include "reconstruct/sibson_raster.h"
#include "reconstruct/subset_cache.h"

namespace radrecon {

using nn::Delaunay;
using nn::Point;

struct NaturalNeighbour::Impl {
  Delaunay dt;
  std::vector<double> values;
  int channels = 1;
  OutsideHull outside = OutsideHull::nearest;
  NeighbourRule rule = NeighbourRule::sibson;
  std::vector<double> gradients;  ///< sibson-c1: per sample and channel, d/ds and d/dt (sibson_c1.h)
  /// CGAL's hull edges (sample indices; whether a query lies on the hull up to rounding is
  /// judged against them), by sample the indices of the two it ends or the one it splits, and the
  /// height over each of the triangle on it.
  std::vector<std::pair<unsigned, unsigned>> hull_edges;
  std::vector<std::array<int, 2>> hull_edges_at;
  std::vector<double> hull_edge_height_m;
  /// The hull through every sample on it up to rounding (hull_chain.h): the hull edges' pieces,
  /// and by hull edge its pieces' range [begin, end). A query's value on the hull is taken on them.
  std::vector<std::pair<unsigned, unsigned>> hull_pieces;
  std::unique_ptr<NearestSegment> nearest_piece;  ///< over hull_pieces, ties to the smaller pair
  std::vector<std::pair<size_t, size_t>> hull_edge_pieces;
  std::vector<double> hull_edge_depth_m;  ///< by hull edge: how far inside it its pieces' ends lie
  HullBandBound hull_band_bound;  ///< bounds every hull edge's band (hull_chain.h)
  std::vector<Vec2> points;
  std::vector<Delaunay::Vertex_handle> vertex_of;  ///< by sample index
  /// The samples' k-d tree, to start walks near a query and to find the samples one sees past
  /// barriers: made on first use (a raster served face by face needs none).
  const KdTree2& tree() const {
    return tree_.get([&] { return std::make_unique<KdTree2>(points); });
  }
  Barriers barriers;
  /// With barriers and at most kMaxWholeVisibleSamples samples: which samples a query sees, and
  /// the triangulations of the sets seen (whole_visible_coordinates()).
  std::unique_ptr<PointVisibility> visibility;
  SubsetCache<Delaunay> visible_triangulations{kMaxCachedTriangulationSamples};
  /// Sibson's rule over rasters (evaluate_raster()), made on first use.
  MadeOnce<SibsonRaster> raster;
  MadeOnce<KdTree2> tree_;

  /// Buffers of coordinates(), reused from query to query.
  struct Scratch {
    std::vector<std::pair<unsigned, double>> coords;
    std::vector<Delaunay::Edge> hole;  ///< boundary of the conflict zone
    // With barriers: the visible samples near the query and their triangulation.
    VisibleNeighbours visible;
    Delaunay local;
    std::vector<std::pair<Point, unsigned>> local_input;
    std::vector<Delaunay::Face_handle> conflicts;
    /// The last query's conflict zone (Sibson's coordinates). It outlives its query (within a
    /// chunk of queries: evaluate()), which parallel_for_with_scratch's rule forbids, and safely
    /// so: a query gets the same bits from a reused zone as from its own (nn::ConflictZone).
    nn::ConflictZone zone;
    // With barriers and few samples: the samples visible from the query, and the triangulation
    // of those the last query saw (whole_visible_coordinates()).
    std::vector<unsigned> visible_idx;
    std::vector<char> hidden;
    std::vector<unsigned> visible_key;
    std::shared_ptr<const Delaunay> visible_dt;
    Delaunay::Face_handle visible_hint;
  };

  /// Coordinates into `out`, normalised by their sum `norm`; false when that is not positive.
  static bool normalise(double norm, std::vector<std::pair<unsigned, double>>& out) {
    if (!(norm > 0)) return false;
    for (auto& [index, w] : out) w /= norm;
    return true;
  }

  /// normalise(), or, when the sum is not positive for q inside the hull and q lies within
  /// rounding of a sample (tol::kNearSampleRelative of the face's longest side, or
  /// tol::kCoordinateRounding of q's magnitude: a query 1 ulp off a sample, whose Voronoi cell's
  /// areas cancel to nothing), that sample's whole weight, the coordinates' limit there; true if
  /// either. The sample is the nearest to q of those in `out` (q's natural neighbours) and the
  /// corners of f, a finite face of `dt` at q. Before, such a point was taken for one outside the
  /// hull: NaN, or the value of a hull edge (an outside-in trial). False otherwise (`out` as it
  /// is): the caller's rule for a failed sum stands.
  bool normalise_inside(const Delaunay& dt, const Vec2& q, const Delaunay::Face_handle& f, double norm,
                        std::vector<std::pair<unsigned, double>>& out) const {
    if (normalise(norm, out)) return true;
    if (f == Delaunay::Face_handle() || dt.is_infinite(f)) return false;
    unsigned nearest = 0;
    double nearest_sq = std::numeric_limits<double>::infinity(), longest_sq = 0;
    const auto consider = [&](unsigned i) {
      const double d_sq = (points[i] - q).squaredNorm();
      if (d_sq < nearest_sq || (d_sq == nearest_sq && i < nearest)) nearest_sq = d_sq, nearest = i;
    };
    for (const auto& [index, w] : out) consider(index);
    for (int k = 0; k < 3; ++k) {
      consider(f->vertex(k)->info());
      const Vec2 side = points[f->vertex(k)->info()] - points[f->vertex((k + 1) % 3)->info()];
      longest_sq = std::max(longest_sq, side.squaredNorm());
    }
    const double rounding_m = std::max(tol::kNearSampleRelative * std::sqrt(longest_sq),
                                       tol::kCoordinateRounding * q.cwiseAbs().maxCoeff());
    if (!(nearest_sq <= rounding_m * rounding_m)) return false;
    out.assign(1, {nearest, 1.0});
    return true;
  }

  /// What a query gets: Sibson coordinates, the value of a point on a hull edge (outside the
  /// hull), or nothing (NaN).
  enum class Kind { coordinates, on_hull, nothing };

  /// A finite face's sample indices, sorted: a canonical order of faces.
  static std::array<unsigned, 3> face_key(const Delaunay::Face_handle& f) {
    std::array<unsigned, 3> key = {f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()};
    std::sort(key.begin(), key.end());
    return key;
  }

  /// Coordinates of q into scratch.coords; `hint` is a face near q (updated), or a default handle.
  /// Without regard to barriers.
  bool coordinates(const Vec2& q, Delaunay::Face_handle& hint, Scratch& scratch) const {
    std::vector<std::pair<unsigned, double>>& out = scratch.coords;
    std::vector<Delaunay::Edge>& hole = scratch.hole;
    out.clear();
    // The last query's conflict zone, when q certainly has the same: no walk, no conflict search.
    if (rule != NeighbourRule::laplace && scratch.zone.holds(q)) {
      hint = scratch.zone.face();
      if (normalise(scratch.zone.sibson(q, out), out)) return true;
      scratch.zone.forget();  // a sum that cancelled: q's own conflict zone below decides
      out.clear();
    }
    const Point p(q.x(), q.y());
    Delaunay::Locate_type lt;
    int li;
    hint = dt.locate(p, lt, li, hint);
    if (lt == Delaunay::OUTSIDE_AFFINE_HULL) return false;
    if (lt == Delaunay::VERTEX) {
      out.emplace_back(hint->vertex(li)->info(), 1.0);
      return true;
    }
    // On a hull edge up to rounding (a point computed as a + t (b - a) may land a little inside
    // or outside): linear along the edge, the limit of the coordinates from inside. Inside,
    // within rounding of the edge, the conflict zone's circumcentres are far off and the
    // coordinates' sums cancel catastrophically; outside, the point would get no value.
    if (lt == Delaunay::OUTSIDE_CONVEX_HULL)
      hint = nearest_hull_face(dt, points, q, hint, hull_band_bound.at(q));  // not where the walk ended
    if (near_hull_edge(q, hint, out)) return true;
    if (lt == Delaunay::OUTSIDE_CONVEX_HULL) return false;
    // A point on an inner edge lies in both of its faces, and the walk may end in either (it
    // depends on where it started). The conflict zone is the same from both, but the order of
    // its boundary, and so the last bits of the sums, is not: start from the face with the
    // smaller sorted sample indices, so that the result depends on the point alone (a batch
    // gives what one point at a time gives).
    if (lt == Delaunay::EDGE) {
      const Delaunay::Face_handle other = hint->neighbor(li);
      if (face_key(other) < face_key(hint)) hint = other;
    }
    // The conflict zone into reused buffers (CGAL's own entry point builds a std::list per
    // query), then the coordinates over it.
    hole.clear();
    if (rule == NeighbourRule::laplace) {
      dt.get_boundary_of_conflicts(p, std::back_inserter(hole), hint);
      return normalise_inside(dt, q, hint, nn::hole_coordinates(dt, p, hole, rule, out), out);
    }
    scratch.conflicts.clear();
    dt.get_conflicts_and_boundary(p, std::back_inserter(scratch.conflicts), std::back_inserter(hole), hint);
    const auto hull_vertex = [&](unsigned i) { return hull_edges_at[i][0] >= 0; };
    if (scratch.zone.build(dt, scratch.conflicts, hole, hull_vertex))
      return normalise_inside(dt, q, hint, scratch.zone.sibson(q, out), out);
    scratch.zone.forget();
    return normalise_inside(dt, q, hint, nn::hole_coordinates(dt, p, hole, rule, out), out);  // CGAL's areas
  }

  /// Whether q lies on a hull edge at a vertex of face f up to rounding (hull_edge_distance(),
  /// delaunay.h): then the coordinates of its nearest point on the nearest such edge, into `out`
  /// (ends in sample order).
  bool near_hull_edge(const Vec2& q, const Delaunay::Face_handle& f, std::vector<std::pair<unsigned, double>>& out) const {
    double best_excess = 0;
    int best = -1;
    for (int k = 0; k < 3; ++k) {
      const Delaunay::Vertex_handle v = f->vertex(k);
      if (dt.is_infinite(v)) continue;
      for (const int e : hull_edges_at[v->info()]) {
        if (e < 0 || e == best) continue;
        auto [ia, ib] = hull_edges[static_cast<size_t>(e)];
        if (ib < ia) std::swap(ia, ib);
        const HullEdgeDistance d = hull_edge_distance(points[ia], points[ib], q, hull_edge_height_m[static_cast<size_t>(e)],
                                                      hull_edge_depth_m[static_cast<size_t>(e)]);
        if (d.in_bands <= 1 && (best < 0 || d.in_bands < best_excess)) best = e, best_excess = d.in_bands;
      }
    }
    if (best < 0) return false;
    // The value on the edge's nearest piece (the edge itself when it is whole).
    const auto [begin, end] = hull_edge_pieces[static_cast<size_t>(best)];
    nearest_on_edges(q, std::span(hull_pieces).subspan(begin, end - begin), out);
    return true;
  }

  /// The point of `edges` (pairs of sample indices) nearest to q, as coordinates of its edge's
  /// end points into `out` (pairs in sample order, as the plain hull rule).
  void nearest_on_edges(const Vec2& q, std::span<const std::pair<unsigned, unsigned>> edges,
                        std::vector<std::pair<unsigned, double>>& out) const {
    double best = std::numeric_limits<double>::infinity(), best_t = 0;
    std::pair<unsigned, unsigned> best_edge{0, 0};
    for (auto e : edges) {
      if (e.second < e.first) std::swap(e.first, e.second);
      const Vec2 a = points[e.first], b = points[e.second];
      const double t = nearest_on_segment_t(q, a, b);
      const double d = (a + t * (b - a) - q).squaredNorm();
      if (d < best || (d == best && e < best_edge)) best = d, best_t = t, best_edge = e;
    }
    out.clear();
    out.emplace_back(best_edge.first, 1 - best_t);
    out.emplace_back(best_edge.second, best_t);
  }

  /// The nearest point of the hull to q, as nearest_on_edges() over every piece gives it (ties:
  /// the smaller pair), found through nearest_piece (reconstruct/nearest_segment.h): a scan of the
  /// whole hull took 30 s for a raster around 100,000 samples on a circle, and a walk along it from
  /// where q was located stopped at a local minimum of the distance (a long, thin hull).
  void nearest_on_hull_pieces(const Vec2& q, std::vector<std::pair<unsigned, double>>& out) const {
    const std::optional<NearestSegment::Found> found = nearest_piece->nearest(q);
    if (!found) return nearest_on_edges(q, hull_pieces, out);  // every distance overflowed: as the scan does
    // In sample order, as nearest_on_edges() gives it: the same coordinates, bit for bit.
    const auto [a, b] = hull_pieces[found->segment];
    const double t = a < b ? found->t : 1 - found->t;
    out.clear();
    out.emplace_back(std::min(a, b), 1 - t);
    out.emplace_back(std::max(a, b), t);
  }

  /// The nearest point to q of the hull of a triangulation (of the samples visible from q) as
  /// nearest_on_edges() gives it: a point, a segment, or the edges of the infinite faces.
  void nearest_on_hull(const Delaunay& dt, const Vec2& q, std::vector<std::pair<unsigned, double>>& out) const {
    std::vector<std::pair<unsigned, unsigned>> edges;
    if (dt.dimension() < 2) {
      if (dt.dimension() == 0) edges.emplace_back(dt.finite_vertices_begin()->info(), dt.finite_vertices_begin()->info());
      for (auto e = dt.finite_edges_begin(); e != dt.finite_edges_end(); ++e)
        edges.emplace_back(e->first->vertex(Delaunay::cw(e->second))->info(), e->first->vertex(Delaunay::ccw(e->second))->info());
    } else {
      // The hull through every sample on it up to rounding (hull_chain.h).
      for (const auto& e : HullChains<Delaunay>(dt, points).pieces) edges.emplace_back(e.a, e.b);
    }
    nearest_on_edges(q, edges, out);
  }

  /// The interpolant from a point's coordinates, per channel, into o: the sum of coordinates
  /// times values, or (sibson-c1) Farin's C1 form.
  void combine(std::span<const std::pair<unsigned, double>> coords, double* o) const {
    if (rule == NeighbourRule::sibson_c1) return nn::farin_c1(coords, points, values, gradients, channels, o);
    for (int c = 0; c < channels; ++c) o[c] = 0;
    for (const auto& [index, w] : coords)
      for (int c = 0; c < channels; ++c) o[c] += w * values[index * static_cast<size_t>(channels) + c];
  }

  bool all_visible(const Vec2& q, std::span<const std::pair<unsigned, double>> coords) const {
    // No barrier within reach of the farthest neighbour: nothing to test.
    double reach_sq = 0;
    for (const auto& [index, w] : coords) reach_sq = std::max(reach_sq, (points[index] - q).squaredNorm());
    if (barriers.none_within(q, std::sqrt(reach_sq))) return true;
    for (const auto& [index, w] : coords)
      if (barriers.blocks(q, points[index])) return false;
    return true;
  }

  /// What q gets (the rules of the header), into scratch.coords; `hint` as in coordinates().
  Kind query(const Vec2& q, Delaunay::Face_handle& hint, Scratch& s) const {
    if (coordinates(q, hint, s)) {
      if (barriers.empty() || all_visible(q, s.coords)) return Kind::coordinates;
    } else {
      // Outside the hull: no value with outside=none (its nearest point would go unused).
      if (barriers.empty() && outside == OutsideHull::none) return Kind::on_hull;
      nearest_on_hull_pieces(q, s.coords);
      // Its nearest point, if nothing hides it (or its edge) from q.
      if (barriers.empty()) return Kind::on_hull;
      Vec2 nearest = Vec2::Zero();
      for (const auto& [index, w] : s.coords) nearest += w * points[index];
      if (all_visible(q, s.coords) && !barriers.blocks(q, nearest) &&
          !barriers.blocks(points[s.coords[0].first], points[s.coords[1].first]))
        return Kind::on_hull;
    }
    return visible_coordinates(q, s);
  }

  /// With barriers and few samples (visibility set): what q gets over every sample visible from
  /// it, in the Delaunay triangulation of exactly those, into s.coords. A triangulation is built
  /// once per set of visible samples (neighbouring queries mostly see the same set), one point at
  /// a time in sample order: it depends on the set alone, and a point on one of its edges is
  /// taken in the face of the smaller sorted sample indices, so that the coordinates depend on
  /// the point alone.
  Kind whole_visible_coordinates(const Vec2& q, Scratch& s) const;

  /// With barriers: what q gets over the samples visible from it (the rule of the header), into
  /// scratch.coords.
  Kind visible_coordinates(const Vec2& q, Scratch& s) const;
};

}  // namespace radrecon
