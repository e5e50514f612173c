#pragma once
// Brute-force Voronoi geometry for tests, independent of CGAL: cells by clipping a large box
// with the half-planes of the bisectors.

#include <cmath>
#include <vector>

#include "core/vec.h"

namespace radrecon::testing {

using Polygon = std::vector<Vec2>;

/// The part of `poly` closer to a than to b (half-plane clip).
inline Polygon clip_closer(const Polygon& poly, const Vec2& a, const Vec2& b) {
  const Vec2 n = b - a;
  const double c = 0.5 * (b.squaredNorm() - a.squaredNorm());  // n . x <= c on a's side
  Polygon out;
  for (size_t i = 0; i < poly.size(); ++i) {
    const Vec2& p = poly[i];
    const Vec2& q = poly[(i + 1) % poly.size()];
    const double dp = n.dot(p) - c, dq = n.dot(q) - c;
    if (dp <= 0) out.push_back(p);
    if ((dp < 0 && dq > 0) || (dp > 0 && dq < 0)) out.push_back(p + dp / (dp - dq) * (q - p));
  }
  return out;
}

inline double area(const Polygon& p) {
  double a = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    const Vec2& u = p[i];
    const Vec2& v = p[(i + 1) % p.size()];
    a += u.x() * v.y() - u.y() * v.x();
  }
  return 0.5 * std::abs(a);
}

/// The Voronoi cell of `site` among `others`, inside a large box.
inline Polygon voronoi_cell(const Vec2& site, const std::vector<Vec2>& others) {
  const double L = 1e3;
  Polygon cell = {Vec2(-L, -L), Vec2(L, -L), Vec2(L, L), Vec2(-L, L)};
  for (const Vec2& o : others)
    if (o != site) cell = clip_closer(cell, site, o);
  return cell;
}

}  // namespace radrecon::testing
