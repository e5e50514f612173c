#include "solver/convex_solids.h"

#include <algorithm>
#include <numeric>
#include <tuple>

#include "core/tolerances.h"

namespace radrecon {

bool ConvexSolid::sees_from_outside(const Vec3& p) const {
  if (opening && opening->eval(p) > tol::kPlaneDistance_m) return false;
  return std::any_of(faces.begin(), faces.end(), [&](const HalfSpace& f) { return f.eval(p) > tol::kPlaneDistance_m; });
}

bool ConvexSolid::behind_horizon(const Vec3& p, const Vec3& n) const {
  const auto supports = [&](const HalfSpace& plane) { return plane.normal == n && plane.eval(p) >= -tol::kPlaneDistance_m; };
  return std::any_of(faces.begin(), faces.end(), supports) || (opening && supports(*opening));
}

namespace {

/// A directed edge of a surface's outline, its ends in a canonical (lexicographic) order for
/// matching: `flipped` when the surface runs it from `hi` to `lo`.
struct Edge {
  Vec3 lo, hi;
  bool flipped;
  size_t surface;
};

bool lex_less(const Vec3& a, const Vec3& b) {
  return std::tie(a.x(), a.y(), a.z()) < std::tie(b.x(), b.y(), b.z());
}

bool same_ends(const Edge& a, const Edge& b) { return a.lo == b.lo && a.hi == b.hi; }

struct DisjointSets {
  std::vector<size_t> parent;
  explicit DisjointSets(size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), size_t{0}); }
  size_t find(size_t k) {
    while (parent[k] != k) k = parent[k] = parent[parent[k]];
    return k;
  }
  void join(size_t a, size_t b) { parent[find(a)] = find(b); }
};

/// The plane through the points with all of `inside` on or behind it (within `tolerance`), unit
/// normal pointing away from them; nullopt when the points are collinear or not coplanar.
std::optional<HalfSpace> supporting_plane(const std::vector<Vec3>& points, const std::vector<Vec3>& inside,
                                          double tolerance) {
  if (points.size() < 3) return std::nullopt;
  const Vec3& a = points[0];
  const Vec3& b = *std::max_element(points.begin(), points.end(), [&](const Vec3& x, const Vec3& y) {
    return (x - a).squaredNorm() < (y - a).squaredNorm();
  });
  Vec3 normal = Vec3::Zero();
  for (const Vec3& c : points) {
    const Vec3 m = (b - a).cross(c - a);
    if (m.squaredNorm() > normal.squaredNorm()) normal = m;
  }
  if (!(normal.norm() > tolerance * (b - a).norm())) return std::nullopt;  // collinear
  normal.normalize();
  HalfSpace plane{normal, normal.dot(a)};
  for (const Vec3& c : points)
    if (std::abs(plane.eval(c)) > tolerance) return std::nullopt;
  double highest = 0, lowest = 0;
  for (const Vec3& c : inside) highest = std::max(highest, plane.eval(c)), lowest = std::min(lowest, plane.eval(c));
  if (highest > tolerance && lowest < -tolerance) return std::nullopt;  // points on both sides
  if (highest > tolerance) plane = plane.complement();
  return plane;
}

/// The solid bounded by the surfaces `faces` (one connected set, every edge shared by two of
/// them but `open_edges`), or null when they do not bound a convex solid with outward normals.
std::shared_ptr<const ConvexSolid> convex_solid(const Scene& scene, const std::vector<size_t>& faces,
                                                const std::vector<Edge>& open_edges) {
  std::vector<Vec3> corners;
  for (const size_t k : faces)
    for (const Vec3& c : scene.surfaces[k].polygon()) corners.push_back(c);
  Vec3 lo = corners[0], hi = corners[0];
  for (const Vec3& c : corners) lo = lo.cwiseMin(c), hi = hi.cwiseMax(c);
  const double tolerance = std::max(tol::kPlaneDistance_m, tol::kPlanarityRelative * (hi - lo).norm());
  auto solid = std::make_shared<ConvexSolid>();
  for (const size_t k : faces) {
    const Surface& s = scene.surfaces[k];
    const Vec3 n = s.normal();
    const HalfSpace plane{n, n.dot(s.corners[0])};
    // Convex with outward normals: every corner on or behind each face's plane, some strictly.
    double lowest = 0;
    for (const Vec3& c : corners) {
      const double d = plane.eval(c);
      if (!(d <= tolerance)) return nullptr;  // a corner in front (or NaN): not convex, or facing in
      lowest = std::min(lowest, d);
    }
    if (!(lowest < -tolerance)) return nullptr;  // flat: no corner behind
    solid->faces.push_back(plane);
  }
  if (!open_edges.empty()) {
    std::vector<Vec3> rim;
    for (const Edge& e : open_edges) rim.push_back(e.lo), rim.push_back(e.hi);
    solid->opening = supporting_plane(rim, corners, tolerance);
    if (!solid->opening) return nullptr;
  }
  return solid;
}

}  // namespace

std::vector<std::shared_ptr<const ConvexSolid>> find_convex_solids(const Scene& scene) {
  const size_t n = scene.surfaces.size();
  std::vector<Edge> edges;
  for (size_t k = 0; k < n; ++k) {
    const std::span<const Vec3> poly = scene.surfaces[k].polygon();
    for (size_t i = 0; i < poly.size(); ++i) {
      const Vec3 &a = poly[i], &b = poly[(i + 1) % poly.size()];
      const bool flipped = lex_less(b, a);
      edges.push_back({flipped ? b : a, flipped ? a : b, flipped, k});
    }
  }
  std::sort(edges.begin(), edges.end(), [](const Edge& x, const Edge& y) {
    if (x.lo != y.lo) return lex_less(x.lo, y.lo);
    if (x.hi != y.hi) return lex_less(x.hi, y.hi);
    return x.surface < y.surface;
  });
  // Surfaces joined by edges that two of them run in opposite directions; an edge run by one
  // surface only is open; an edge of three surfaces, or two running it the same way, is no
  // boundary of a solid, and neither surface bounds one.
  DisjointSets sets(n);
  std::vector<bool> spoiled(n, false);
  std::vector<Edge> open;
  for (size_t first = 0; first < edges.size();) {
    size_t last = first + 1;
    while (last < edges.size() && same_ends(edges[first], edges[last])) ++last;
    if (last - first == 1) {
      open.push_back(edges[first]);
    } else if (last - first == 2 && edges[first].flipped != edges[first + 1].flipped &&
               edges[first].surface != edges[first + 1].surface) {
      sets.join(edges[first].surface, edges[first + 1].surface);
    } else {
      for (size_t k = first; k < last; ++k) spoiled[edges[k].surface] = true;
    }
    first = last;
  }
  std::vector<std::vector<size_t>> members(n);
  for (size_t k = 0; k < n; ++k) members[sets.find(k)].push_back(k);
  std::vector<std::vector<Edge>> open_of(n);
  for (const Edge& e : open) open_of[sets.find(e.surface)].push_back(e);

  std::vector<std::shared_ptr<const ConvexSolid>> out(n);
  for (size_t root = 0; root < n; ++root) {
    const std::vector<size_t>& faces = members[root];
    if (faces.size() < 3 || faces.size() > kMaxSolidFaces) continue;  // a solid has 3 faces or more, an opening included
    if (std::any_of(faces.begin(), faces.end(), [&](size_t k) { return spoiled[k]; })) continue;
    const std::shared_ptr<const ConvexSolid> solid = convex_solid(scene, faces, open_of[root]);
    if (solid)
      for (const size_t k : faces) out[k] = solid;
  }
  return out;
}

}  // namespace radrecon
