#pragma once
// Small convex planar polygons in 3-D and their clipping by half-spaces: the geometry kernel of
// the form factor and exact visibility computations. Fixed capacity, no allocation.

#include <algorithm>
#include <array>
#include <cmath>

#include "core/check.h"
#include "core/tolerances.h"
#include "core/vec.h"

namespace radrecon {

/// A convex polygon with at most kCapacity vertices, in order.
struct ConvexPolygon {
  /// Clipping a convex polygon by a plane adds at most one vertex; a quad clipped by the
  /// receiver's horizon and up to six occluders' five planes each stays below this, and the
  /// visibility code cuts larger fragments in two before clipping them further.
  static constexpr int kCapacity = 40;
  std::array<Vec3, kCapacity> v;
  int n = 0;

  ConvexPolygon() = default;
  // Copies only the vertices in use: polygons are copied in the innermost loop of the solver.
  ConvexPolygon(const ConvexPolygon& o) : n(o.n) { std::copy_n(o.v.begin(), o.n, v.begin()); }
  ConvexPolygon& operator=(const ConvexPolygon& o) {
    n = o.n;
    std::copy_n(o.v.begin(), o.n, v.begin());
    return *this;
  }

  bool empty() const { return n < 3; }
  void push(const Vec3& p) {
    RR_CHECK(n < kCapacity, "convex polygon capacity exceeded");
    v[n++] = p;
  }
};

/// The area of a convex (planar) polygon, m^2: half the norm of its fan's summed cross products.
inline double area_m2(const ConvexPolygon& q) {
  Vec3 twice = Vec3::Zero();
  for (int i = 1; i + 1 < q.n; ++i) twice += (q.v[i] - q.v[0]).cross(q.v[i + 1] - q.v[0]);
  return 0.5 * twice.norm();
}

/// A half-space {x : dot(normal, x) >= offset}; the normal need not be unit length.
struct HalfSpace {
  Vec3 normal;
  double offset;
  /// tol::kPlaneDistance_m times |normal|: clip()'s tolerance in eval()'s units, made once by
  /// with_tolerance() for a plane that clips many polygons; negative: clip() makes it.
  double on_plane = -1;
  double eval(const Vec3& x) const { return normal.dot(x) - offset; }
  HalfSpace complement() const { return {-normal, -offset, on_plane}; }
  HalfSpace with_tolerance() const { return {normal, offset, tol::kPlaneDistance_m * normal.norm()}; }
};

/// Where a polygon lies against a half-space: wholly inside (clip() keeps it as it is), wholly
/// outside, or across its plane.
enum class Side { inside, outside, across };

/// The signed distances of `in`'s vertices to h's plane (HalfSpace::eval(), zero within
/// tol::kPlaneDistance_m of it, so nearly coincident planes (quads that share an edge) add no
/// sliver vertices) into d, and where the polygon lies. A polygon in the plane counts as inside;
/// a NaN distance as neither inside nor outside.
inline Side distances(const ConvexPolygon& in, const HalfSpace& h, std::array<double, ConvexPolygon::kCapacity>& d) {
  const double on_plane = h.on_plane >= 0 ? h.on_plane : tol::kPlaneDistance_m * h.normal.norm();
  int inside = 0, outside = 0;  // counts, not a chain of && : no branch per vertex
  for (int i = 0; i < in.n; ++i) {
    const double e = h.eval(in.v[i]);
    d[i] = std::abs(e) <= on_plane ? 0.0 : e;
    inside += d[i] >= 0;
    outside += d[i] <= 0;
  }
  return inside == in.n ? Side::inside : outside == in.n ? Side::outside : Side::across;
}

/// The part of a polygon across h's plane on one side of it, from distances(): `sign` +1 keeps
/// d >= 0 (the half-space), -1 keeps d <= 0 (its complement, bit for bit what clip() by
/// h.complement() gives: negating the distances is exact).
inline void cut(const ConvexPolygon& in, const std::array<double, ConvexPolygon::kCapacity>& d, double sign,
                ConvexPolygon& out) {
  out.n = 0;
  for (int i = 0; i < in.n; ++i) {
    const int k = i + 1 < in.n ? i + 1 : 0;
    const double di = sign * d[i], dk = sign * d[k];
    if (di >= 0) out.push(in.v[i]);
    if ((di > 0 && dk < 0) || (di < 0 && dk > 0)) {
      const double t = di / (di - dk);
      out.push(in.v[i] + t * (in.v[k] - in.v[i]));
    }
  }
}

/// The part of `in` inside the half-space (Sutherland-Hodgman for one plane), to distances()'
/// tolerance.
inline ConvexPolygon clip(const ConvexPolygon& in, const HalfSpace& h) {
  ConvexPolygon out;
  if (in.n == 0) return out;
  std::array<double, ConvexPolygon::kCapacity> d;
  switch (distances(in, h, d)) {
    case Side::inside: return in;
    case Side::outside: return out;
    case Side::across: cut(in, d, 1.0, out); return out;
  }
  return out;
}

/// `in` cut by h's plane: its part inside the half-space into `inside` and the rest into
/// `outside`, each what clip() by h and by h.complement() gives, for one evaluation of the
/// distances. A polygon in the plane goes to both.
inline void split(const ConvexPolygon& in, const HalfSpace& h, ConvexPolygon& inside, ConvexPolygon& outside) {
  inside.n = outside.n = 0;
  if (in.n == 0) return;
  std::array<double, ConvexPolygon::kCapacity> d;
  const Side side = distances(in, h, d);
  const bool in_plane = side == Side::inside && std::all_of(d.begin(), d.begin() + in.n, [](double x) { return x == 0; });
  if (side == Side::inside) inside = in;
  if (side == Side::outside || in_plane) outside = in;
  if (side != Side::across) return;
  cut(in, d, 1.0, inside);
  cut(in, d, -1.0, outside);
}

}  // namespace radrecon
