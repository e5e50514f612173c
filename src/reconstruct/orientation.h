#pragma once
// The orientation predicate of the barriers' visibility rule (barriers.h), exact, shared by
// Barriers and PointVisibility: the double determinant decides when it clears its error bound
// (almost always), CGAL's exact predicate decides the rest. Internal to reconstruct/.

#include <cmath>

#include "core/vec.h"

namespace radrecon {

/// Shewchuk's bound on the round-off of the orientation determinant computed in doubles
/// ("Adaptive precision floating-point arithmetic", 1997: ccwerrboundA): when the computed value
/// exceeds it in magnitude, its sign is the exact sign.
inline constexpr double kOrientationErrorBound = (3.0 + 16.0 * 0x1p-53) * 0x1p-53;

/// Sign of the orientation of (a, b, c) by CGAL's exact predicate: +1 counter-clockwise, -1
/// clockwise, 0 collinear (out of line: barriers.cpp).
[[gnu::noinline]] int exact_orientation(const Vec2& a, const Vec2& b, const Vec2& c);

/// Sign of the orientation of (a, b, c), exact: the double path inlined into the visibility
/// loops, exact_orientation() where it cannot decide.
inline int orientation(const Vec2& a, const Vec2& b, const Vec2& c) {
  const double left = (b.x() - a.x()) * (c.y() - a.y()), right = (b.y() - a.y()) * (c.x() - a.x());
  const double det = left - right;
  const double bound = kOrientationErrorBound * (std::abs(left) + std::abs(right));
  if (det > bound) return 1;
  if (det < -bound) return -1;
  return exact_orientation(a, b, c);
}

}  // namespace radrecon
