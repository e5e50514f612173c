// NaturalNeighbour with barriers (natural_neighbour.h): a query's coordinates over the samples
// it sees, in the triangulation of every one of them (few samples) or of its nearest ones.

#include "reconstruct/natural_neighbour_impl.h"

#include <cmath>

namespace radrecon {

NaturalNeighbour::Impl::Kind NaturalNeighbour::Impl::whole_visible_coordinates(const Vec2& q, Scratch& s) const {
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
  return normalise_inside(dt, q, f, nn::hole_coordinates(dt, p, s.hole, rule, s.coords), s.coords) ? Kind::coordinates
                                                                                                     : Kind::nothing;
}

NaturalNeighbour::Impl::Kind NaturalNeighbour::Impl::visible_coordinates(const Vec2& q, Scratch& s) const {
  if (visibility) return whole_visible_coordinates(q, s);
  constexpr size_t kFirstRound = 16;
  const size_t n = points.size();
  const Point p(q.x(), q.y());
  for (size_t k = std::min(kFirstRound, n);; k = std::min({2 * k, n, kMaxVisibleNeighbours})) {
    // The k nearest visible samples, and a lower bound on the next one's distance (the
    // certificate's): its distance when found, infinity when every sample was tried, else the
    // distance of the farthest candidate tried.
    const size_t found = nearest_visible(tree(), points, barriers, q, std::min(k + 1, n), s.visible);
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
      if (normalise_inside(dt, q, f, norm, s.coords)) return Kind::coordinates;  // within rounding of a sample
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

}  // namespace radrecon
