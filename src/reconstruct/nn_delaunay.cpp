#include "reconstruct/nn_delaunay.h"

#include <array>
#include <cmath>

#include "core/tolerances.h"

#include <CGAL/natural_neighbor_coordinates_2.h>

namespace radrecon::nn {

namespace {

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

ConflictZone::CircleTest ConflictZone::circle_test(const std::array<Vec2, 3>& p) {
  // det |x y x^2+y^2 1| of the corners (counterclockwise) and q, expanded along q's row.
  std::array<double, 3> x, y, l;
  for (size_t k = 0; k < 3; ++k) x[k] = p[k].x(), y[k] = p[k].y(), l[k] = p[k].squaredNorm();
  const auto minor = [](const std::array<double, 3>& r, const std::array<double, 3>& s) {  // det |r s 1|
    return r[0] * (s[1] - s[2]) + r[1] * (s[2] - s[0]) + r[2] * (s[0] - s[1]);
  };
  const double m44 = x[0] * (y[1] * l[2] - y[2] * l[1]) - x[1] * (y[0] * l[2] - y[2] * l[0]) + x[2] * (y[0] * l[1] - y[1] * l[0]);
  return {-minor(x, y), -minor(y, l), minor(x, l), m44};
}

bool ConflictZone::holds(const Vec2& q) const {
  if (!reusable_) return false;
  const Vec2 r = (q - origin_) * scale_;
  const double rr = r.squaredNorm();
  // Each coefficient is a sum of 6 products of corner coordinates (at most e = 2 in magnitude,
  // a lift at most 2 e^2): its terms, and those of s, are bounded by the sums below.
  const double e = 2, e2 = e * e;
  const double bound = tol::kConflictZoneTestRelative * (6 * e2 * rr + 12 * e2 * e * (std::abs(r.x()) + std::abs(r.y())) + 12 * e2 * e2);
  for (const CircleTest& t : inside_)
    if (!(t.a * rr + t.b * r.x() + t.c * r.y() + t.d > bound)) return false;
  for (const CircleTest& t : outside_)
    if (!(t.a * rr + t.b * r.x() + t.c * r.y() + t.d < -bound)) return false;
  return true;
}

double ConflictZone::sibson(const Vec2& q, std::vector<std::pair<unsigned, double>>& out) const {
  // The new Voronoi vertex over boundary edge k, g_k = the circumcentre of (q, v_k, v_{k+1});
  // v_k's share is the polygon g_{k-1}, g_k, then the old Voronoi vertices (its chain's
  // circumcentres), all relative to q: convex, so its shoelace sum's magnitude is twice its area.
  const size_t m = vertex_.size();
  const Vec2 r = (q - origin_) * scale_;
  thread_local std::vector<Vec2> g;
  g.resize(m);
  for (size_t k = 0; k < m; ++k) g[k] = circumcentre_from(r, at_[k], at_[(k + 1) % m]);
  double sum = 0;
  for (size_t k = 0; k < m; ++k) {
    const Vec2& g_in = g[(k + m - 1) % m];
    Vec2 previous = g[k];
    double twice = cross(g_in, previous);
    for (int c = chain_first_[k]; c < chain_first_[k + 1]; ++c) {
      const Vec2 next = centre_[static_cast<size_t>(chain_[static_cast<size_t>(c)])] - r;
      twice += cross(previous, next);
      previous = next;
    }
    twice += cross(previous, g_in);
    const double area = 0.5 * std::abs(twice);
    if (!std::isfinite(area)) return 0;
    if (area == 0) continue;
    out.emplace_back(vertex_[k], area);
    sum += area;
  }
  return sum;
}

double hole_coordinates(const Delaunay& dt, const Point& p, const std::vector<Delaunay::Edge>& hole,
                        NeighbourRule rule, std::vector<std::pair<unsigned, double>>& out) {
  // A conflict zone reaching the infinite vertex (a point on the hull that the hull rules did not
  // catch) has no coordinates: its vertex carries no sample, and CGAL's hole overload would hand
  // out its unset index.
  for (const auto& [face, i] : hole)
    if (dt.is_infinite(face->vertex(Delaunay::ccw(i))) || dt.is_infinite(face->vertex(Delaunay::cw(i)))) return 0;
  if (rule == NeighbourRule::laplace) return laplace(p, hole, out);
  const auto result = CGAL::natural_neighbor_coordinates_2(dt, p, std::back_inserter(out), VertexIndex(), hole.begin(),
                                                           hole.end());
  return result.third && result.second > 0 ? static_cast<double>(result.second) : 0.0;
}

}  // namespace radrecon::nn
