#include "io/mesh_polygons.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>

#include "core/tolerances.h"

namespace radrecon {

namespace {

/// The polygon's normal by Newell's method (its length is twice the area, m^2).
Vec3 newell_normal(std::span<const Vec3> c) {
  Vec3 n = Vec3::Zero();
  for (size_t i = 0; i < c.size(); ++i) n += c[i].cross(c[(i + 1) % c.size()]);
  return n;
}

/// Whether p lies inside or on the triangle (a, b, c) of the 2-D plane (counter-clockwise).
bool in_triangle(const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& c) {
  const auto side = [](const Vec2& o, const Vec2& e, const Vec2& q) {
    return (e - o).x() * (q - o).y() - (e - o).y() * (q - o).x();
  };
  return side(a, b, p) >= 0 && side(b, c, p) >= 0 && side(c, a, p) >= 0;
}

}  // namespace

void drop_repeated_corners(std::vector<Vec3>& corners) {
  double longest = 0;
  for (size_t i = 0; i < corners.size(); ++i) longest = std::max(longest, (corners[(i + 1) % corners.size()] - corners[i]).norm());
  const double same = tol::kRepeatedCornerRelative * longest;
  std::vector<Vec3> kept;
  for (const Vec3& c : corners)
    if (kept.empty() || (c - kept.back()).norm() > same) kept.push_back(c);
  while (kept.size() > 1 && (kept.back() - kept.front()).norm() <= same) kept.pop_back();
  corners = std::move(kept);
}

double polygon_off_plane(std::span<const Vec3> c) {
  Vec3 n = newell_normal(c), mean = Vec3::Zero();
  double longest = 0;
  for (size_t i = 0; i < c.size(); ++i) {
    mean += c[i] / static_cast<double>(c.size());
    longest = std::max(longest, (c[(i + 1) % c.size()] - c[i]).norm());
  }
  if (n.norm() == 0 || longest == 0) return 0;
  n.normalize();
  double off = 0;
  for (const Vec3& p : c) off = std::max(off, std::abs((p - mean).dot(n)));
  return off / longest;
}

bool polygon_on_a_line(std::span<const Vec3> corners) {
  if (corners.size() < 3) return true;
  // The line through the first corner's farthest and that one's farthest.
  const auto farthest = [&](const Vec3& from) {
    size_t best = 0;
    for (size_t k = 1; k < corners.size(); ++k)
      if ((corners[k] - from).squaredNorm() > (corners[best] - from).squaredNorm()) best = k;
    return corners[best];
  };
  const Vec3 a = farthest(corners[0]), b = farthest(a);
  const double length = (b - a).norm();
  if (!(length > 0)) return true;
  const Vec3 along = (b - a) / length;
  for (const Vec3& c : corners)
    if ((c - a).cross(along).norm() > tol::kDegenerateAreaRelative * length) return false;
  return true;
}

std::vector<std::array<int, 3>> triangulate_polygon(std::span<const Vec3> corners) {
  const int n = static_cast<int>(corners.size());
  std::vector<std::array<int, 3>> out;
  if (n < 3) return out;
  const Vec3 normal = newell_normal(corners);
  if (!normal.allFinite() || normal.norm() == 0) return out;
  const Vec3 w = normal.normalized();
  const Vec3 u = (std::abs(w.x()) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0)).cross(w).normalized();
  const Vec3 v = w.cross(u);
  std::vector<Vec2> p(n);
  for (int i = 0; i < n; ++i) p[i] = Vec2(corners[i].dot(u), corners[i].dot(v));
  std::vector<int> left(n);
  for (int i = 0; i < n; ++i) left[i] = i;
  const auto cross = [&](int a, int b, int c) {
    return (p[b] - p[a]).x() * (p[c] - p[a]).y() - (p[b] - p[a]).y() * (p[c] - p[a]).x();
  };
  while (left.size() > 3) {
    const int m = static_cast<int>(left.size());
    bool cut = false;
    for (int k = 0; k < m && !cut; ++k) {
      const int a = left[(k + m - 1) % m], b = left[k], c = left[(k + 1) % m];
      if (cross(a, b, c) <= 0) continue;  // reflex or straight corner: not an ear
      // A corner at the place of one of the ear's own is no obstacle: a weakly simple polygon
      // (a ring and its hole, joined by an edge walked there and back) visits such places twice.
      bool empty = true;
      for (int q : left)
        if (q != a && q != b && q != c && p[q] != p[a] && p[q] != p[b] && p[q] != p[c] && in_triangle(p[q], p[a], p[b], p[c]))
          empty = false;
      if (!empty) continue;
      out.push_back({a, b, c});
      left.erase(left.begin() + k);
      cut = true;
    }
    if (!cut) return {};
  }
  if (cross(left[0], left[1], left[2]) <= 0) return {};
  out.push_back({left[0], left[1], left[2]});
  // The ears cover the polygon exactly once: their areas add up to its own (Newell's), else the
  // polygon crosses itself in a way the cuts did not see.
  double area = 0;
  for (const auto& [a, b, c] : out) area += 0.5 * cross(a, b, c);
  if (!(std::abs(area - 0.5 * normal.norm()) <= tol::kTriangulationAreaRelative * 0.5 * normal.norm())) return {};
  return out;
}

namespace {

using Key = std::array<double, 3>;
Key key(const Vec3& p) { return {p.x(), p.y(), p.z()}; }

bool same_material(const Surface& a, const Surface& b) {
  return (a.reflectance == b.reflectance).all() && (a.emission_w_m2 == b.emission_w_m2).all() && a.two_sided == b.two_sided &&
         a.max_divisions == b.max_divisions;
}

/// The quad (a, d, b, c) of triangle t = (a, b, c) rotated so that its edge `edge` comes first
/// (a -> b) and d is the partner's corner off that edge; nullopt unless planar and convex.
std::optional<Surface> merged_quad(const Surface& t, int edge, const Vec3& d) {
  const Vec3 a = t.corners[edge], b = t.corners[(edge + 1) % 3], c = t.corners[(edge + 2) % 3];
  Surface q = t;
  q.corner_count = 4;
  q.corners = {a, d, b, c};
  double longest_sq = 0;
  for (int i = 0; i < 4; ++i) longest_sq = std::max(longest_sq, (q.corners[(i + 1) % 4] - q.corners[i]).squaredNorm());
  const Vec3 n = q.normal();
  if (!n.allFinite() || longest_sq == 0) return std::nullopt;
  const Vec3 centroid = 0.25 * (a + b + c + d);
  for (const Vec3& corner : q.corners)
    if (std::abs((corner - centroid).dot(n)) > 0.5 * tol::kPlanarityRelative * std::sqrt(longest_sq)) return std::nullopt;
  for (int i = 0; i < 4; ++i) {
    const Vec3 e0 = q.corners[(i + 1) % 4] - q.corners[i], e1 = q.corners[(i + 2) % 4] - q.corners[(i + 1) % 4];
    if (e0.cross(e1).dot(n) <= tol::kQuadMergeTurnRelative * longest_sq) return std::nullopt;
  }
  return q;
}

}  // namespace

size_t merge_coplanar_triangle_pairs(std::vector<Surface>& surfaces) {
  // Directed edge (from, to) -> the triangles walking it, and the edge's index in each.
  std::map<std::pair<Key, Key>, std::vector<std::pair<size_t, int>>> edges;
  for (size_t i = 0; i < surfaces.size(); ++i) {
    if (!surfaces[i].is_triangle()) continue;
    for (int e = 0; e < 3; ++e)
      edges[{key(surfaces[i].corners[e]), key(surfaces[i].corners[(e + 1) % 3])}].push_back({i, e});
  }
  std::vector<bool> gone(surfaces.size(), false), merged(surfaces.size(), false);
  size_t pairs = 0;
  for (size_t i = 0; i < surfaces.size(); ++i) {
    const Surface& t = surfaces[i];
    if (!t.is_triangle() || merged[i]) continue;
    std::optional<Surface> best;
    size_t best_j = 0;
    double best_length = -1;
    for (int e = 0; e < 3; ++e) {
      const Vec3& a = t.corners[e];
      const Vec3& b = t.corners[(e + 1) % 3];
      const auto it = edges.find({key(b), key(a)});
      if (it == edges.end()) continue;
      const double length = (b - a).norm();
      for (const auto& [j, f] : it->second) {
        if (j == i || merged[j] || !same_material(t, surfaces[j])) continue;
        if (length < best_length || (length == best_length && j > best_j)) continue;
        const Vec3 d = surfaces[j].corners[(f + 2) % 3];
        if (std::optional<Surface> q = merged_quad(t, e, d)) {
          best = std::move(q);
          best_j = j;
          best_length = length;
        }
      }
    }
    if (!best) continue;
    surfaces[i] = std::move(*best);
    merged[i] = merged[best_j] = true;
    gone[best_j] = true;
    ++pairs;
  }
  size_t kept = 0;
  for (size_t i = 0; i < surfaces.size(); ++i)
    if (!gone[i]) {
      if (kept != i) surfaces[kept] = std::move(surfaces[i]);
      ++kept;
    }
  surfaces.resize(kept);
  return pairs;
}

}  // namespace radrecon
