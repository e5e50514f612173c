#include "reconstruct/delaunay.h"

#include <algorithm>
#include <map>
#include <utility>

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include "core/tolerances.h"
#include "reconstruct/hull_chain.h"
#include "reconstruct/interpolant.h"
#include "reconstruct/kdtree.h"
#include "reconstruct/nearest_segment.h"

namespace radrecon {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<unsigned, K>;        // sample index
using Fb = CGAL::Triangulation_face_base_with_info_2<std::int64_t, K>;      // face index, -1 if infinite
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using Delaunay = CGAL::Delaunay_triangulation_2<K, Tds>;
using Point = K::Point_2;

}  // namespace

struct DelaunayMesh::Impl {
  Delaunay dt;
  std::vector<Delaunay::Face_handle> handles;             ///< by face index
  std::vector<std::pair<std::int64_t, int>> vertex_face;  ///< by sample: a face and its corner there
  std::unique_ptr<HullChains<Delaunay>> chains;  ///< CGAL's hull edges and their pieces
  std::unique_ptr<NearestSegment> nearest_piece;  ///< over chains->pieces, ties to the smaller sample pair
  /// By sample: the infinite faces of the hull edges it ends (two), or of the one it splits.
  std::vector<std::array<Delaunay::Face_handle, 2>> hull_at;
  std::unique_ptr<KdTree2> tree;
};

DelaunayMesh::DelaunayMesh(std::span<const Vec2> points, const std::string& method)
    : impl_(std::make_unique<Impl>()), points_(points.begin(), points.end()) {
  const size_t n = points_.size();
  if (n < 3) throw ReconstructionError(method + " interpolation needs at least 3 samples, got " + std::to_string(n));
  Impl& m = *impl_;
  std::vector<std::pair<Point, unsigned>> input;
  input.reserve(n);
  for (size_t i = 0; i < n; ++i) input.emplace_back(Point(points_[i].x(), points_[i].y()), static_cast<unsigned>(i));
  // CGAL sorts the points along a Hilbert curve after a shuffle by a default-seeded generator:
  // the same input gives the same triangulation, co-circular points included.
  m.dt.insert(input.begin(), input.end());
  if (m.dt.number_of_vertices() != n)
    throw ReconstructionError(std::to_string(n - m.dt.number_of_vertices()) + " duplicate sample point(s); " + method +
                              " needs distinct points");
  if (m.dt.dimension() < 2) throw ReconstructionError("all samples lie on one line; " + method + " needs a 2-D spread");

  for (auto f = m.dt.all_faces_begin(); f != m.dt.all_faces_end(); ++f) f->info() = -1;
  for (auto f = m.dt.finite_faces_begin(); f != m.dt.finite_faces_end(); ++f) {
    f->info() = static_cast<std::int64_t>(m.handles.size());
    m.handles.push_back(f);
  }
  const size_t nf = m.handles.size();
  vertices_.resize(nf);
  neighbours_.resize(nf);
  affine_.resize(nf);
  m.vertex_face.assign(n, {-1, 0});
  for (size_t f = 0; f < nf; ++f) {
    const Delaunay::Face_handle h = m.handles[f];
    for (int k = 0; k < 3; ++k) {
      vertices_[f][k] = h->vertex(k)->info();
      neighbours_[f][k] = h->neighbor(k)->info();
      auto& vf = m.vertex_face[vertices_[f][k]];
      if (vf.first < 0) vf = {static_cast<std::int64_t>(f), k};
    }
    const Vec2 &p0 = points_[vertices_[f][0]], &p1 = points_[vertices_[f][1]], &p2 = points_[vertices_[f][2]];
    const double a = p1.x() - p0.x(), b = p2.x() - p0.x(), c = p1.y() - p0.y(), d = p2.y() - p0.y();
    const double det = a * d - b * c;  // > 0: a Delaunay face is counter-clockwise and not flat
    affine_[f] = {p0.x(), p0.y(), d / det, -b / det, -c / det, a / det};
    // A sliver: its height over its longest edge (det over that edge squared) below the limit.
    const std::array<double, 3> edge_sq = {(p2 - p1).squaredNorm(), (p0 - p2).squaredNorm(), (p1 - p0).squaredNorm()};
    const int longest = static_cast<int>(std::max_element(edge_sq.begin(), edge_sq.end()) - edge_sq.begin());
    if (!(std::abs(det) > tol::kDelaunaySliverRelative * edge_sq[static_cast<size_t>(longest)])) affine_[f].sliver_corner = longest;
  }
  m.chains = std::make_unique<HullChains<Delaunay>>(m.dt, points_);
  {
    std::vector<std::pair<unsigned, unsigned>> pieces, keys;
    for (const auto& e : m.chains->pieces) pieces.emplace_back(e.a, e.b), keys.push_back(std::minmax(e.a, e.b));
    m.nearest_piece = std::make_unique<NearestSegment>(points_, std::move(pieces), std::move(keys));
  }
  // By sample: the hull edges it ends, two; or, no vertex of CGAL's hull, the one it splits (a
  // thin set's hull vertex within rounding of the edge across it keeps its own two).
  m.hull_at.assign(n, {});
  auto fc = m.dt.incident_faces(m.dt.infinite_vertex()), done = fc;
  do {
    const int i = fc->index(m.dt.infinite_vertex());
    for (const int end : {Delaunay::ccw(i), Delaunay::cw(i)}) {
      auto& at = m.hull_at[fc->vertex(end)->info()];
      (at[0] == Delaunay::Face_handle() ? at[0] : at[1]) = fc;
    }
  } while (++fc != done);
  do {
    const auto pieces = m.chains->of(fc, fc->index(m.dt.infinite_vertex()));
    for (size_t k = 1; k < pieces.size(); ++k)
      if (auto& at = m.hull_at[pieces[k].a]; at[0] == Delaunay::Face_handle()) at[0] = fc;
  } while (++fc != done);
  m.tree = std::make_unique<KdTree2>(points_);
}

DelaunayMesh::~DelaunayMesh() = default;

namespace {
void on_edge(std::span<const Vec2> points, const std::array<unsigned, 3>& vertices, int k, const Vec2& q,
             std::array<double, 3>& b);
}  // namespace

std::array<double, 3> DelaunayMesh::barycentric(size_t f, const Vec2& p) const {
  const Affine& t = affine_[f];
  if (t.sliver_corner >= 0) {
    // The sliver as the polyline through its corners along its longest edge: p projected onto
    // the short edge on its side of the middle corner (whose foot lies between the longest
    // edge's ends), so that a row of samples a rounding error off one line is interpolated
    // sample by sample, not between the row's far ends.
    const int k = t.sliver_corner;
    const std::array<unsigned, 3>& v = vertices_[f];
    const Vec2 &a = points_[v[(k + 1) % 3]], &b = points_[v[(k + 2) % 3]], &c = points_[v[k]];
    const Vec2 ab = b - a;
    const double tc = (c - a).dot(ab), tp = (p - a).dot(ab);
    std::array<double, 3> out;
    on_edge(points_, v, tp <= tc ? (k + 2) % 3 : (k + 1) % 3, p, out);  // (a, c) lies opposite b's corner
    return out;
  }
  const double dx = p.x() - t.x0, dy = p.y() - t.y0;
  const double b1 = t.m00 * dx + t.m01 * dy, b2 = t.m10 * dx + t.m11 * dy;
  return {1 - b1 - b2, b1, b2};
}

std::int64_t DelaunayMesh::face_near(const Vec2& q) const {
  unsigned nearest[1];
  double d2[1];
  impl_->tree->nearest(q, 1, nearest, d2);
  return impl_->vertex_face[nearest[0]].first;
}

namespace {

/// The coordinates of q projected onto the edge opposite corner k of a face with corners
/// `vertices`: 0 at corner k, linear along the edge from its end of smaller sample index, so
/// that both faces of the edge give the same pair.
void on_edge(std::span<const Vec2> points, const std::array<unsigned, 3>& vertices, int k, const Vec2& q,
             std::array<double, 3>& b) {
  int ca = (k + 1) % 3, cb = (k + 2) % 3;
  if (vertices[cb] < vertices[ca]) std::swap(ca, cb);
  const Vec2 &pa = points[vertices[ca]], &pb = points[vertices[cb]];
  const double t = nearest_on_segment_t(q, pa, pb);
  b[k] = 0;
  b[ca] = 1 - t;
  b[cb] = t;
}

}  // namespace

HullEdgeDistance hull_edge_distance(const Vec2& a, const Vec2& b, const Vec2& q, double height_m, double slack_m) {
  const Vec2 ab = b - a;
  const double t = std::clamp((q - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  const double band = slack_m + tol::kHullEdgeBandRelative * std::min(ab.norm(), height_m) +
                      tol::kCoordinateRounding * std::max({a.cwiseAbs().maxCoeff(), b.cwiseAbs().maxCoeff(), q.cwiseAbs().maxCoeff()});
  return {(a + t * ab - q).norm() / band, t};
}

bool DelaunayMesh::locate(const Vec2& q, OutsideHull outside, std::int64_t& hint, Location& out) const {
  if (!q.allFinite()) return false;
  const Impl& m = *impl_;
  // q on the piece of a hull edge nearest to it (hull_chain.h): the coordinates of its face there.
  const auto on_piece = [&](std::span<const HullChainEdge<Delaunay::Face_handle>> pieces, const Vec2& p, Location& at) {
    const auto [piece, t] = HullChains<Delaunay>::nearest(pieces, points_, p);
    at.face = piece->inner->info();
    on_edge(points_, vertices_[static_cast<size_t>(at.face)], piece->corner, p, at.b);
  };
  // q's distance from the hull edge of infinite face e in units of its band, widened by the depth
  // of its pieces (<= 1: on it up to rounding).
  const auto bands_to = [&](const Delaunay::Face_handle& e) {
    const int ei = e->index(m.dt.infinite_vertex());
    const auto& pa = e->vertex(Delaunay::ccw(ei))->point();
    const auto& pb = e->vertex(Delaunay::cw(ei))->point();
    return hull_edge_distance(Vec2(pa.x(), pa.y()), Vec2(pb.x(), pb.y()), q, std::numeric_limits<double>::infinity(),
                              m.chains->depth_m(e, ei))
        .in_bands;
  };
  // Whether q lies on a hull edge at a vertex of face g up to rounding; then q on its nearest
  // piece, into `out`.
  const auto near_hull = [&](const Delaunay::Face_handle& g) {
    double best_bands = 1;
    Delaunay::Face_handle on;
    for (int k = 0; k < 3; ++k)
      for (const Delaunay::Face_handle& e : m.hull_at[g->vertex(k)->info()]) {
        if (e == Delaunay::Face_handle()) continue;
        if (const double bands = bands_to(e); bands <= best_bands) best_bands = bands, on = e;
      }
    if (on == Delaunay::Face_handle()) return false;
    on_piece(m.chains->of(on, on->index(m.dt.infinite_vertex())), q, out);
    hint = out.face;
    return true;
  };
  const Point p(q.x(), q.y());
  Delaunay::Locate_type lt;
  int li;
  const Delaunay::Face_handle f =
      m.dt.locate(p, lt, li, hint >= 0 ? m.handles[static_cast<size_t>(hint)] : Delaunay::Face_handle());
  switch (lt) {
    case Delaunay::VERTEX: {
      const auto [face, corner] = m.vertex_face[f->vertex(li)->info()];
      out.face = face;
      out.b = {0, 0, 0};
      out.b[static_cast<size_t>(corner)] = 1;
      hint = face;
      return true;
    }
    case Delaunay::EDGE: {
      // On a hull edge: its nearest piece (hull_chain.h).
      if (m.dt.is_infinite(f) || m.dt.is_infinite(f->neighbor(li))) {
        const Delaunay::Face_handle outer = m.dt.is_infinite(f) ? f : f->neighbor(li);
        on_piece(m.chains->of(outer, outer->index(m.dt.infinite_vertex())), q, out);
        hint = out.face;
        return true;
      }
      if (near_hull(f)) return true;  // near a hull edge, up to rounding: its nearest piece
      // On an inner edge: the face of smaller index among its two.
      const Delaunay::Face_handle g = f->neighbor(li);
      std::int64_t face = f->info();
      int corner = li;
      if (face < 0 || (g->info() >= 0 && g->info() < face)) face = g->info(), corner = m.dt.mirror_index(f, li);
      out.face = face;
      on_edge(points_, vertices_[static_cast<size_t>(face)], corner, q, out.b);
      hint = face;
      return true;
    }
    case Delaunay::FACE:
      // Inside, on a hull edge up to rounding (between it and the samples it was split at):
      // the nearest piece.
      if (near_hull(f)) return true;
      out.face = f->info();
      out.b = barycentric(static_cast<size_t>(out.face), q);
      hint = out.face;
      return true;
    case Delaunay::OUTSIDE_CONVEX_HULL: {
      // Outside by rounding only: on the hull edge nearest q (whatever edge CGAL's walk ended
      // at), or on one of its two neighbours (the edges at its ends), whichever is nearest in
      // bands; its value on that edge's nearest piece.
      const Delaunay::Vertex_handle infinite = m.dt.infinite_vertex();
      const Delaunay::Face_handle nearest_edge = nearest_hull_face(m.dt, points_, q, f, m.chains->band_bound.at(q));
      const int i = nearest_edge->index(infinite);
      double best_bands = 1;
      Delaunay::Face_handle on;
      for (const Delaunay::Face_handle& g :
           {nearest_edge, nearest_edge->neighbor(Delaunay::ccw(i)), nearest_edge->neighbor(Delaunay::cw(i))})
        if (const double bands = bands_to(g); bands <= best_bands) best_bands = bands, on = g;
      if (on != Delaunay::Face_handle()) {
        on_piece(m.chains->of(on, on->index(infinite)), q, out);
        hint = out.face;
        return true;
      }
      if (outside == OutsideHull::none) return false;
      // The nearest point of the hull: on its nearest piece (reconstruct/nearest_segment.h; ties:
      // the piece of smaller sample indices), whatever the queries before.
      const std::optional<NearestSegment::Found> found = m.nearest_piece->nearest(q);
      const HullChainEdge<Delaunay::Face_handle>* nearest = found ? &m.chains->pieces[found->segment] : nullptr;
      if (!nearest) return false;  // q so far away that every distance overflowed
      out.face = nearest->inner->info();
      on_edge(points_, vertices_[static_cast<size_t>(out.face)], nearest->corner, q, out.b);
      hint = out.face;
      return true;
    }
    case Delaunay::OUTSIDE_AFFINE_HULL: return false;  // not for a 2-D triangulation
  }
  return false;
}

}  // namespace radrecon
