#pragma once
// Closed-form form factors from Howell's catalogue of radiation configuration factors, the
// independent answers the solvers are checked against.

#include <cmath>
#include <numbers>

namespace radrecon::testing_support {

/// Configuration B-3: a differential area parallel to a rectangle of sides a, b (metres) at
/// distance c, facing it, opposite one of its corners.
inline double parallel_corner_form_factor(double a_m, double b_m, double c_m) {
  const double A = a_m / c_m, B = b_m / c_m;
  const double sa = std::sqrt(1 + A * A), sb = std::sqrt(1 + B * B);
  return (A / sa * std::atan(B / sa) + B / sb * std::atan(A / sb)) / (2.0 * std::numbers::pi);
}

/// Configuration B-2: a differential area and a rectangle in a perpendicular plane at distance
/// c (metres): one edge of the rectangle, of length a, lies in the receiver's plane and starts at
/// the foot of the receiver's perpendicular to the rectangle's plane; the other edge, of length
/// b, rises from the receiver's plane.
inline double perpendicular_corner_form_factor(double a_m, double b_m, double c_m) {
  const double X = b_m / a_m, Y = c_m / a_m;
  const double s = std::sqrt(X * X + Y * Y);
  return (std::atan(1 / Y) - Y / s * std::atan(1 / s)) / (2.0 * std::numbers::pi);
}

/// F from a point (x, y, 0) facing up to the rectangle [x0,x1] x [y0,y1] at height h facing
/// down, by superposition of B-3 over signed sub-rectangles.
inline double floor_to_rectangle(double x, double y, double x0, double y0, double x1, double y1, double h) {
  auto corner = [&](double a, double b) {
    if (a == 0 || b == 0) return 0.0;
    const double sign = (a < 0 ? -1 : 1) * (b < 0 ? -1 : 1);
    return sign * parallel_corner_form_factor(std::abs(a), std::abs(b), h);
  };
  return corner(x1 - x, y1 - y) - corner(x0 - x, y1 - y) - corner(x1 - x, y0 - y) + corner(x0 - x, y0 - y);
}

}  // namespace radrecon::testing_support
