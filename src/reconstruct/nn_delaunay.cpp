#include "reconstruct/nn_delaunay.h"

#include <cmath>

#include <CGAL/natural_neighbor_coordinates_2.h>

namespace radrecon::nn {

namespace {

/// The circumcentre of the triangle (p, a, b), relative to p (metres).
Vec2 circumcentre_from(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 u = a - p, v = b - p;
  const double d = 2 * (u.x() * v.y() - u.y() * v.x());
  const double uu = u.squaredNorm(), vv = v.squaredNorm();
  return Vec2((v.y() * uu - u.y() * vv) / d, (u.x() * vv - v.x() * uu) / d);
}

double laplace(const Point& p, const std::vector<Delaunay::Edge>& hole, std::vector<std::pair<unsigned, double>>& out) {
  // Consecutive boundary edges (f, i) share the vertex f->vertex(cw(i)) of the second (CGAL's
  // order), so the Voronoi edge facing that vertex joins the circumcentres over the two edges.
  const size_t m = hole.size();
  if (m < 3) return 0;
  const Vec2 q(p.x(), p.y());
  thread_local std::vector<Vec2> centres;
  centres.resize(m);
  for (size_t k = 0; k < m; ++k) {
    const auto& [face, i] = hole[k];
    const Point& a = face->vertex(Delaunay::ccw(i))->point();
    const Point& b = face->vertex(Delaunay::cw(i))->point();
    centres[k] = circumcentre_from(q, Vec2(a.x(), a.y()), Vec2(b.x(), b.y()));
  }
  double sum = 0;
  for (size_t k = 0; k < m; ++k) {
    const size_t next = (k + 1) % m;
    const auto& [face, i] = hole[next];
    const Delaunay::Vertex_handle v = face->vertex(Delaunay::cw(i));  // shared by edges k and next
    const double dist = (Vec2(v->point().x(), v->point().y()) - q).norm();
    const double w = (centres[next] - centres[k]).norm() / dist;
    if (!std::isfinite(w)) return 0;
    if (w == 0) continue;  // co-circular: a neighbour only by a point of p's cell (as Sibson's)
    out.emplace_back(v->info(), w);
    sum += w;
  }
  return sum;
}

}  // namespace

double hole_coordinates(const Delaunay& dt, const Point& p, const std::vector<Delaunay::Edge>& hole,
                        NeighbourRule rule, std::vector<std::pair<unsigned, double>>& out) {
  if (rule == NeighbourRule::laplace) return laplace(p, hole, out);
  const auto result = CGAL::natural_neighbor_coordinates_2(dt, p, std::back_inserter(out), VertexIndex(), hole.begin(),
                                                           hole.end());
  return result.third && result.second > 0 ? static_cast<double>(result.second) : 0.0;
}

}  // namespace radrecon::nn
