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

/// The part of `in` inside the half-space (Sutherland-Hodgman for one plane). Vertices within
/// tol::kPlaneDistance_m of the plane count as on it, so nearly coincident planes (quads that
/// share an edge) add no sliver vertices.
inline ConvexPolygon clip(const ConvexPolygon& in, const HalfSpace& h) {
  ConvexPolygon out;
  if (in.n == 0) return out;
  std::array<double, ConvexPolygon::kCapacity> d;
  bool all_in = true, all_out = true;
  const double on_plane = h.on_plane >= 0 ? h.on_plane : tol::kPlaneDistance_m * h.normal.norm();
  for (int i = 0; i < in.n; ++i) {
    d[i] = h.eval(in.v[i]);
    if (std::abs(d[i]) <= on_plane) d[i] = 0;
    all_in = all_in && d[i] >= 0;
    all_out = all_out && d[i] <= 0;
  }
  if (all_in) return in;
  if (all_out) return out;
  for (int i = 0; i < in.n; ++i) {
    const int k = i + 1 < in.n ? i + 1 : 0;
    if (d[i] >= 0) out.push(in.v[i]);
    if ((d[i] > 0 && d[k] < 0) || (d[i] < 0 && d[k] > 0)) {
      double t = d[i] / (d[i] - d[k]);
      out.push(in.v[i] + t * (in.v[k] - in.v[i]));
    }
  }
  return out;
}

}  // namespace radrecon
