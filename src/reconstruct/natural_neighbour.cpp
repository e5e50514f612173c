#include "reconstruct/natural_neighbour.h"

#include <algorithm>
#include <array>
#include <limits>

#include "core/check.h"
#include "core/parallel.h"
#include "core/tolerances.h"
#include "reconstruct/delaunay.h"
#include "reconstruct/kdtree.h"
#include "reconstruct/nn_delaunay.h"
#include "reconstruct/sibson_c1.h"
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
  std::vector<std::pair<unsigned, unsigned>> hull_edges;  ///< sample indices
  std::vector<std::array<int, 2>> hull_edges_at;          ///< by sample: its hull edges' indices, or -1
  std::vector<Vec2> points;
  std::vector<Delaunay::Vertex_handle> vertex_of;  ///< by sample index
  std::unique_ptr<KdTree2> tree;                   ///< to start walks near a query
  Barriers barriers;
  /// With barriers and at most kMaxWholeVisibleSamples samples: which samples a query sees, and
  /// the triangulations of the sets seen (whole_visible_coordinates()).
  std::unique_ptr<PointVisibility> visibility;
  SubsetCache<Delaunay> visible_triangulations{kMaxCachedTriangulationSamples};

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
      return normalise(scratch.zone.sibson(q, out), out);
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
      return normalise(nn::hole_coordinates(dt, p, hole, rule, out), out);
    }
    scratch.conflicts.clear();
    dt.get_conflicts_and_boundary(p, std::back_inserter(scratch.conflicts), std::back_inserter(hole), hint);
    const auto hull_vertex = [&](unsigned i) { return hull_edges_at[i][0] >= 0; };
    if (scratch.zone.build(dt, scratch.conflicts, hole, hull_vertex))
      return normalise(scratch.zone.sibson(q, out), out);
    scratch.zone.forget();
    return normalise(nn::hole_coordinates(dt, p, hole, rule, out), out);  // CGAL's areas
  }

  /// Whether q lies on a hull edge at a vertex of face f up to rounding (hull_edge_distance(),
  /// delaunay.h): then the coordinates of its nearest point on the nearest such edge, into `out`
  /// (ends in sample order).
  bool near_hull_edge(const Vec2& q, const Delaunay::Face_handle& f, std::vector<std::pair<unsigned, double>>& out) const {
    double best_excess = 0, best_t = 0;
    int best = -1;
    for (int k = 0; k < 3; ++k) {
      const Delaunay::Vertex_handle v = f->vertex(k);
      if (dt.is_infinite(v)) continue;
      for (const int e : hull_edges_at[v->info()]) {
        if (e < 0 || e == best) continue;
        auto [ia, ib] = hull_edges[static_cast<size_t>(e)];
        if (ib < ia) std::swap(ia, ib);
        const HullEdgeDistance d = hull_edge_distance(points[ia], points[ib], q);
        if (d.in_bands <= 1 && (best < 0 || d.in_bands < best_excess)) best = e, best_excess = d.in_bands, best_t = d.t;
      }
    }
    if (best < 0) return false;
    auto [ia, ib] = hull_edges[static_cast<size_t>(best)];
    if (ib < ia) std::swap(ia, ib);
    out.clear();
    out.emplace_back(ia, 1 - best_t);
    out.emplace_back(ib, best_t);
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
      const Vec2 ab = b - a;
      const double t = ab.squaredNorm() > 0 ? std::clamp((q - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
      const double d = (a + t * ab - q).squaredNorm();
      if (d < best || (d == best && e < best_edge)) best = d, best_t = t, best_edge = e;
    }
    out.clear();
    out.emplace_back(best_edge.first, 1 - best_t);
    out.emplace_back(best_edge.second, best_t);
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
      const auto inf = dt.infinite_vertex();
      auto fc = dt.incident_faces(inf), done = fc;
      do {
        const int i = fc->index(inf);
        edges.emplace_back(fc->vertex(Delaunay::ccw(i))->info(), fc->vertex(Delaunay::cw(i))->info());
      } while (++fc != done);
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
      nearest_on_edges(q, hull_edges, s.coords);
      // Outside the hull: its nearest point, if nothing hides it (or its edge) from q.
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
  Kind whole_visible_coordinates(const Vec2& q, Scratch& s) const {
    visibility->visible_from(q, s.visible_idx, s.hidden);
    if (s.visible_idx.empty()) return Kind::nothing;
    if (!s.visible_dt || s.visible_key != s.visible_idx) {
      s.visible_dt = visible_triangulations.get(0, s.visible_idx, [&] {
        auto dt = std::make_shared<Delaunay>();
        Delaunay::Vertex_handle last;
        for (const unsigned i : s.visible_idx) {
          last = dt->insert(Point(points[i].x(), points[i].y()), last == Delaunay::Vertex_handle() ? Delaunay::Face_handle() : last->face());
          last->info() = i;
        }
        return std::shared_ptr<const Delaunay>(std::move(dt));
      });
      s.visible_key = s.visible_idx;
      s.visible_hint = Delaunay::Face_handle();
    }
    const Delaunay& dt = *s.visible_dt;
    if (dt.dimension() < 2) {  // one point, or all on a line: q is outside their hull
      nearest_on_hull(dt, q, s.coords);
      return Kind::on_hull;
    }
    const Point p(q.x(), q.y());
    Delaunay::Locate_type lt;
    int li;
    Delaunay::Face_handle f = dt.locate(p, lt, li, s.visible_hint);
    s.visible_hint = f;
    if (lt == Delaunay::VERTEX) {
      s.coords.assign(1, {f->vertex(li)->info(), 1.0});
      return Kind::coordinates;
    }
    const bool on_hull_edge = lt == Delaunay::EDGE && (dt.is_infinite(f) || dt.is_infinite(f->neighbor(li)));
    if (lt == Delaunay::OUTSIDE_CONVEX_HULL || on_hull_edge) {
      nearest_on_hull(dt, q, s.coords);
      return on_hull_edge ? Kind::coordinates : Kind::on_hull;
    }
    if (lt == Delaunay::EDGE) {
      const Delaunay::Face_handle other = f->neighbor(li);
      if (face_key(other) < face_key(f)) f = other;
    }
    s.conflicts.clear();
    s.hole.clear();
    dt.get_conflicts_and_boundary(p, std::back_inserter(s.conflicts), std::back_inserter(s.hole), f);
    s.coords.clear();
    return normalise(nn::hole_coordinates(dt, p, s.hole, rule, s.coords), s.coords) ? Kind::coordinates : Kind::nothing;
  }

  /// With barriers: what q gets over the samples visible from it (the rule of the header), into
  /// scratch.coords.
  Kind visible_coordinates(const Vec2& q, Scratch& s) const {
    if (visibility) return whole_visible_coordinates(q, s);
    constexpr size_t kFirstRound = 16;
    const size_t n = points.size();
    const Point p(q.x(), q.y());
    for (size_t k = std::min(kFirstRound, n);; k = std::min({2 * k, n, kMaxVisibleNeighbours})) {
      // The k nearest visible samples, and a lower bound on the next one's distance (the
      // certificate's): its distance when found, infinity when every sample was tried, else the
      // distance of the farthest candidate tried.
      const size_t found = nearest_visible(*tree, points, barriers, q, std::min(k + 1, n), s.visible);
      const size_t m = std::min(found, k);
      const bool all_tried = n <= std::max(kMaxVisibleCandidates, 2 * (k + 1));  // nearest_visible's limit
      const double next_visible_m = found > k ? std::sqrt(s.visible.dist_sq[k])
                                    : all_tried ? std::numeric_limits<double>::infinity()
                                                : std::sqrt(s.visible.candidates_dist_sq.back());
      const bool complete = found <= k && all_tried;  // every visible sample is in the triangulation
      const bool last = found <= k || k >= kMaxVisibleNeighbours;
      if (m == 0) return Kind::nothing;
      s.local_input.clear();
      for (size_t i = 0; i < m; ++i) {
        const Vec2& v = points[s.visible.idx[i]];
        s.local_input.emplace_back(Point(v.x(), v.y()), s.visible.idx[i]);
      }
      // One point at a time, nearest first: a range insertion sorts the points along a curve with
      // a random shuffle, and co-circular points (a lattice) could then be triangulated
      // differently from thread to thread.
      Delaunay& dt = s.local;
      dt.clear();
      Delaunay::Vertex_handle last_vertex;
      for (const auto& [point, index] : s.local_input) {
        last_vertex = dt.insert(point, last_vertex == Delaunay::Vertex_handle() ? Delaunay::Face_handle() : last_vertex->face());
        last_vertex->info() = index;
      }
      if (dt.dimension() < 2) {  // one point, or all on a line: q is outside their hull
        if (!last) continue;
        nearest_on_hull(dt, q, s.coords);
        return Kind::on_hull;
      }
      Delaunay::Locate_type lt;
      int li;
      Delaunay::Face_handle f = dt.locate(p, lt, li);
      if (lt == Delaunay::VERTEX) {
        s.coords.assign(1, {f->vertex(li)->info(), 1.0});
        return Kind::coordinates;
      }
      const bool on_hull_edge = lt == Delaunay::EDGE && (dt.is_infinite(f) || dt.is_infinite(f->neighbor(li)));
      if (lt == Delaunay::OUTSIDE_CONVEX_HULL || on_hull_edge) {
        // Outside (or on) the hull of these samples: a farther visible sample may still close it.
        if (!last) continue;
        nearest_on_hull(dt, q, s.coords);
        return on_hull_edge ? Kind::coordinates : Kind::on_hull;
      }
      // Inside: the conflict zone, its boundary, and the certificate.
      s.conflicts.clear();
      s.hole.clear();
      dt.get_conflicts_and_boundary(p, std::back_inserter(s.conflicts), std::back_inserter(s.hole), f);
      double r_max_sq = 0, rho_max_sq = 0;
      for (const auto& face : s.conflicts)
        r_max_sq = std::max(r_max_sq, CGAL::squared_radius(face->vertex(0)->point(), face->vertex(1)->point(),
                                                           face->vertex(2)->point()));
      for (const auto& [face, i] : s.hole) {
        const Point& a = face->vertex(Delaunay::ccw(i))->point();
        const Point& b = face->vertex(Delaunay::cw(i))->point();
        rho_max_sq = std::max(rho_max_sq, CGAL::squared_radius(p, a, b));
      }
      s.coords.clear();
      const double norm = nn::hole_coordinates(dt, p, s.hole, rule, s.coords);
      if (!(norm > 0)) {
        if (!last) continue;
        return Kind::nothing;
      }
      const double rho = std::sqrt(rho_max_sq), bound = rho + std::max(rho, std::sqrt(r_max_sq));
      const bool certified = std::isfinite(bound) && (complete || next_visible_m > bound * (1 + tol::kSibsonCertificateRelative));
      if (!certified && !last) continue;
      for (auto& [index, w] : s.coords) w /= norm;
      return Kind::coordinates;
    }
  }
};

NaturalNeighbour::NaturalNeighbour(const ScatteredSamples& samples, OutsideHull outside, Barriers barriers,
                                   NeighbourRule rule)
    : impl_(std::make_unique<Impl>()) {
  impl_->barriers = std::move(barriers);
  impl_->rule = rule;
  const std::string name = rule == NeighbourRule::sibson ? "natural-neighbour" : rule == NeighbourRule::laplace ? "laplace" : "sibson-c1";
  const size_t n = samples.points.size();
  if (n < 3) throw ReconstructionError(name + " interpolation needs at least 3 samples, got " + std::to_string(n));
  impl_->values = samples.values;
  impl_->channels = samples.channels;
  impl_->outside = outside;
  impl_->points = samples.points;
  std::vector<std::pair<Point, unsigned>> input;
  input.reserve(n);
  for (size_t i = 0; i < n; ++i) input.emplace_back(Point(samples.points[i].x(), samples.points[i].y()), static_cast<unsigned>(i));
  impl_->dt.insert(input.begin(), input.end());
  if (impl_->dt.number_of_vertices() != n)
    throw ReconstructionError(std::to_string(n - impl_->dt.number_of_vertices()) +
                                   " duplicate sample point(s); " + name + " needs distinct points");
  if (impl_->dt.dimension() < 2) throw ReconstructionError("all samples lie on one line; " + name + " needs a 2-D spread");
  impl_->vertex_of.resize(n);
  for (auto v = impl_->dt.finite_vertices_begin(); v != impl_->dt.finite_vertices_end(); ++v) impl_->vertex_of[v->info()] = v;
  impl_->tree = std::make_unique<KdTree2>(impl_->points);
  if (!impl_->barriers.empty() && n <= kMaxWholeVisibleSamples &&
      n * impl_->barriers.segments().size() <= kMaxWholeVisiblePairs)
    impl_->visibility = std::make_unique<PointVisibility>(impl_->points, impl_->barriers);
  // Hull edges: the finite edges of the infinite faces.
  auto inf = impl_->dt.infinite_vertex();
  auto fc = impl_->dt.incident_faces(inf), done = fc;
  do {
    const int i = fc->index(inf);
    impl_->hull_edges.emplace_back(fc->vertex(Delaunay::ccw(i))->info(), fc->vertex(Delaunay::cw(i))->info());
  } while (++fc != done);
  impl_->hull_edges_at.assign(n, {-1, -1});
  for (size_t e = 0; e < impl_->hull_edges.size(); ++e)
    for (const unsigned end : {impl_->hull_edges[e].first, impl_->hull_edges[e].second}) {
      std::array<int, 2>& at = impl_->hull_edges_at[end];
      (at[0] < 0 ? at[0] : at[1]) = static_cast<int>(e);
    }
  if (rule == NeighbourRule::sibson_c1)
    impl_->gradients = nn::fit_gradients(impl_->dt, impl_->vertex_of, impl_->points, impl_->values, impl_->channels,
                                         impl_->barriers);
}

NaturalNeighbour::~NaturalNeighbour() = default;

int NaturalNeighbour::channels() const { return impl_->channels; }

const std::vector<std::pair<unsigned, unsigned>>& NaturalNeighbour::hull_edges() const { return impl_->hull_edges; }

std::vector<std::pair<unsigned, double>> NaturalNeighbour::coordinates(const Vec2& q) const {
  Impl::Scratch scratch;
  Delaunay::Face_handle hint;
  if (impl_->query(q, hint, scratch) != Impl::Kind::coordinates) return {};
  return std::move(scratch.coords);
}

namespace {

/// Runs body(q, kind, scratch) for every query q, kind and scratch.coords as Impl::query() leaves
/// them (kind nothing for a non-finite point), in fixed chunks: each chunk's walk starts at a face
/// of the sample nearest to its first query, then from the face found last (raster queries are
/// coherent). A query on a Delaunay edge may be located in either face, and the coordinates' last
/// bits depend on which; fixed chunks with deterministic starts make that independent of the
/// number of threads. Runs of 4 chunks are handed out to the threads, in parallel from 2 runs on:
/// a chunk costs some 10 us, far more than handing it out.
template <typename Impl, typename Body>
void for_each_query(const Impl& impl, std::span<const Vec2> points, Body&& body) {
  constexpr std::int64_t kChunk = 64, kChunksPerRun = 4;
  const std::int64_t n = static_cast<std::int64_t>(points.size());
  using Scratch = typename Impl::Scratch;
  parallel_for_with_scratch<Scratch>(0, (n + kChunk - 1) / kChunk, kChunksPerRun, 2 * kChunksPerRun, [&](std::int64_t chunk, Scratch& scratch) {
    // A chunk's conflict zones are its own: its walks start from its own first query, whatever
    // the thread ran before (which face an edge's point is located in decides the hull-edge test).
    scratch.zone.forget();
    Delaunay::Face_handle hint;
    const size_t first = static_cast<size_t>(chunk * kChunk);
    if (points[first].allFinite()) {
      unsigned nearest[1];
      double nearest_d2[1];
      impl.tree->nearest(points[first], 1, nearest, nearest_d2);
      hint = impl.vertex_of[nearest[0]]->face();
    }
    for (std::int64_t k = chunk * kChunk; k < std::min(n, (chunk + 1) * kChunk); ++k) {
      const size_t q = static_cast<size_t>(k);
      const typename Impl::Kind kind = points[q].allFinite() ? impl.query(points[q], hint, scratch) : Impl::Kind::nothing;
      body(q, kind, scratch);
    }
  });
}

}  // namespace

void NaturalNeighbour::evaluate(std::span<const Vec2> points, std::span<double> out) const {
  const int C = impl_->channels;
  RR_CHECK(out.size() == points.size() * static_cast<size_t>(C), "output size does not match the query points");
  for_each_query(*impl_, points, [&](size_t q, Impl::Kind kind, const Impl::Scratch& scratch) {
    double* o = &out[q * C];
    if (kind == Impl::Kind::coordinates || (kind == Impl::Kind::on_hull && impl_->outside == OutsideHull::nearest)) {
      impl_->combine(scratch.coords, o);
    } else {
      for (int c = 0; c < C; ++c) o[c] = std::numeric_limits<double>::quiet_NaN();
    }
  });
}

void NaturalNeighbour::visit_coordinates(
    std::span<const Vec2> points,
    const std::function<void(size_t, std::span<const std::pair<unsigned, double>>)>& visit) const {
  for_each_query(*impl_, points, [&](size_t q, Impl::Kind kind, const Impl::Scratch& scratch) {
    if (kind == Impl::Kind::coordinates) visit(q, scratch.coords);
    else visit(q, {});
  });
}

}  // namespace radrecon
