#include "reconstruct/natural_neighbour.h"

#include <algorithm>
#include <array>
#include <limits>

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/natural_neighbor_coordinates_2.h>

#include "core/check.h"
#include "reconstruct/kdtree.h"
#include "core/parallel.h"

namespace radrecon {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<unsigned, K>;
using Tds = CGAL::Triangulation_data_structure_2<Vb>;
using Delaunay = CGAL::Delaunay_triangulation_2<K, Tds>;
using Point = K::Point_2;

/// Turns CGAL's (vertex, weight) pairs into (sample index, weight).
struct VertexIndex {
  using argument_type = std::pair<Delaunay::Vertex_handle, K::FT>;
  using result_type = std::pair<unsigned, double>;
  result_type operator()(const argument_type& p) const { return {p.first->info(), p.second}; }
};

}  // namespace

struct NaturalNeighbour::Impl {
  Delaunay dt;
  std::vector<double> values;
  int channels = 1;
  OutsideHull outside = OutsideHull::nearest;
  std::vector<std::pair<unsigned, unsigned>> hull_edges;  ///< sample indices
  std::vector<Vec2> points;
  std::vector<Delaunay::Vertex_handle> vertex_of;  ///< by sample index
  std::unique_ptr<KdTree2> tree;                   ///< to start walks near a query

  /// Buffers of coordinates(), reused from query to query.
  struct Scratch {
    std::vector<std::pair<unsigned, double>> coords;
    std::vector<Delaunay::Edge> hole;  ///< boundary of the conflict zone
  };

  /// A finite face's sample indices, sorted: a canonical order of faces.
  static std::array<unsigned, 3> face_key(const Delaunay::Face_handle& f) {
    std::array<unsigned, 3> key = {f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()};
    std::sort(key.begin(), key.end());
    return key;
  }

  /// Coordinates of q into scratch.coords; `hint` is a face near q (updated), or a default handle.
  bool coordinates(const Vec2& q, Delaunay::Face_handle& hint, Scratch& scratch) const {
    std::vector<std::pair<unsigned, double>>& out = scratch.coords;
    std::vector<Delaunay::Edge>& hole = scratch.hole;
    out.clear();
    const Point p(q.x(), q.y());
    Delaunay::Locate_type lt;
    int li;
    hint = dt.locate(p, lt, li, hint);
    if (lt == Delaunay::OUTSIDE_CONVEX_HULL || lt == Delaunay::OUTSIDE_AFFINE_HULL) return false;
    if (lt == Delaunay::VERTEX) {
      out.emplace_back(hint->vertex(li)->info(), 1.0);
      return true;
    }
    if (lt == Delaunay::EDGE && (dt.is_infinite(hint) || dt.is_infinite(hint->neighbor(li)))) {
      // On the hull: linear along the edge (the limit of the coordinates from inside), its ends
      // in sample order, whichever face the walk found.
      auto a = hint->vertex(Delaunay::cw(li)), b = hint->vertex(Delaunay::ccw(li));
      if (b->info() < a->info()) std::swap(a, b);
      const Vec2 pa(a->point().x(), a->point().y()), pb(b->point().x(), b->point().y());
      const double t = std::clamp((q - pa).dot(pb - pa) / (pb - pa).squaredNorm(), 0.0, 1.0);
      out.emplace_back(a->info(), 1 - t);
      out.emplace_back(b->info(), t);
      return true;
    }
    // A point on an inner edge lies in both of its faces, and the walk may end in either (it
    // depends on where it started). The conflict zone is the same from both, but the order of
    // its boundary, and so the last bits of the sums, is not: start from the face with the
    // smaller sorted sample indices, so that the result depends on the point alone (a batch
    // gives what one point at a time gives).
    if (lt == Delaunay::EDGE) {
      const Delaunay::Face_handle other = hint->neighbor(li);
      if (face_key(other) < face_key(hint)) hint = other;
    }
    // The boundary of the conflict zone into a reused buffer (CGAL's own entry point builds a
    // std::list per query), then CGAL's Sibson areas over that hole.
    hole.clear();
    dt.get_boundary_of_conflicts(p, std::back_inserter(hole), hint);
    const auto result = CGAL::natural_neighbor_coordinates_2(dt, p, std::back_inserter(out), VertexIndex(), hole.begin(),
                                                             hole.end());
    if (!result.third || !(result.second > 0)) return false;
    const double norm = result.second;
    for (auto& [index, w] : out) w /= norm;
    return true;
  }

  /// The value at the point of the hull nearest to q, interpolated along its hull edge.
  void nearest_on_hull(const Vec2& q, double* o) const {
    double best = std::numeric_limits<double>::infinity(), best_t = 0;
    std::pair<unsigned, unsigned> best_edge{0, 0};
    for (const auto& e : hull_edges) {
      const Vec2 a = points[e.first], b = points[e.second];
      const Vec2 ab = b - a;
      const double t = std::clamp((q - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
      const double d = (a + t * ab - q).squaredNorm();
      if (d < best) best = d, best_t = t, best_edge = e;
    }
    for (int c = 0; c < channels; ++c)
      o[c] = (1 - best_t) * values[best_edge.first * static_cast<size_t>(channels) + c] +
             best_t * values[best_edge.second * static_cast<size_t>(channels) + c];
  }
};

NaturalNeighbour::NaturalNeighbour(const ScatteredSamples& samples, OutsideHull outside) : impl_(std::make_unique<Impl>()) {
  const size_t n = samples.points.size();
  if (n < 3) throw ReconstructionError("natural-neighbour interpolation needs at least 3 samples, got " + std::to_string(n));
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
                                   " duplicate sample point(s); natural-neighbour needs distinct points");
  if (impl_->dt.dimension() < 2) throw ReconstructionError("all samples lie on one line; natural-neighbour needs a 2-D spread");
  impl_->vertex_of.resize(n);
  for (auto v = impl_->dt.finite_vertices_begin(); v != impl_->dt.finite_vertices_end(); ++v) impl_->vertex_of[v->info()] = v;
  impl_->tree = std::make_unique<KdTree2>(impl_->points);
  // Hull edges: the finite edges of the infinite faces.
  auto inf = impl_->dt.infinite_vertex();
  auto fc = impl_->dt.incident_faces(inf), done = fc;
  do {
    const int i = fc->index(inf);
    impl_->hull_edges.emplace_back(fc->vertex(Delaunay::ccw(i))->info(), fc->vertex(Delaunay::cw(i))->info());
  } while (++fc != done);
}

NaturalNeighbour::~NaturalNeighbour() = default;

int NaturalNeighbour::channels() const { return impl_->channels; }

std::vector<std::pair<unsigned, double>> NaturalNeighbour::coordinates(const Vec2& q) const {
  Impl::Scratch scratch;
  Delaunay::Face_handle hint;
  impl_->coordinates(q, hint, scratch);
  return std::move(scratch.coords);
}

void NaturalNeighbour::evaluate(std::span<const Vec2> points, std::span<double> out) const {
  const int C = impl_->channels;
  RR_CHECK(out.size() == points.size() * static_cast<size_t>(C), "output size does not match the query points");
  // Queries in fixed chunks: each chunk's walk starts at a face of the sample nearest to its
  // first query, then from the face found last (raster queries are coherent). A query on a
  // Delaunay edge may be located in either face, and the coordinates' last bits depend on which;
  // fixed chunks with deterministic starts make that independent of the number of threads.
  constexpr std::int64_t kChunk = 64;
  const std::int64_t n = static_cast<std::int64_t>(points.size());
  parallel_for_with_scratch<Impl::Scratch>(0, (n + kChunk - 1) / kChunk, [&](std::int64_t chunk, Impl::Scratch& scratch) {
    Delaunay::Face_handle hint;
    const size_t first = static_cast<size_t>(chunk * kChunk);
    if (points[first].allFinite()) {
      unsigned nearest[1];
      double nearest_d2[1];
      impl_->tree->nearest(points[first], 1, nearest, nearest_d2);
      hint = impl_->vertex_of[nearest[0]]->face();
    }
    for (std::int64_t k = chunk * kChunk; k < std::min(n, (chunk + 1) * kChunk); ++k) {
      const size_t q = static_cast<size_t>(k);
      double* o = &out[q * C];
      if (!points[q].allFinite()) {
        for (int c = 0; c < C; ++c) o[c] = std::numeric_limits<double>::quiet_NaN();
        continue;
      }
      if (!impl_->coordinates(points[q], hint, scratch)) {
        if (impl_->outside == OutsideHull::nearest) {
          impl_->nearest_on_hull(points[q], o);
        } else {
          for (int c = 0; c < C; ++c) o[c] = std::numeric_limits<double>::quiet_NaN();
        }
        continue;
      }
      for (int c = 0; c < C; ++c) o[c] = 0;
      for (const auto& [index, w] : scratch.coords)
        for (int c = 0; c < C; ++c) o[c] += w * impl_->values[index * static_cast<size_t>(C) + c];
    }
  });
}

}  // namespace radrecon
