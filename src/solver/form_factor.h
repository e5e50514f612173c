#pragma once
// Form factors from a differential receiver area to polygons.

#include <array>
#include <span>

#include "solver/polygon.h"

namespace radrecon {

/// Form factor F(dA -> P) from a differential area at `p` with unit normal `n` to the planar
/// polygon `polygon`, by Lambert's contour integral:
///   F = 1/(2 pi) * | sum_i angle(r_i, r_{i+1}) * dot(n, unit(r_i x r_{i+1})) |,  r_i = v_i - p.
/// Exact (to round-off) when the whole polygon lies in the closed front half-space of the
/// receiver; use receiver_form_factor() otherwise. Dimensionless, in [0, 1].
double lambert_form_factor(const Vec3& p, const Vec3& n, const ConvexPolygon& polygon);

/// lambert_form_factor() at four points with the same normal: out[k] for points[k]. One contour
/// integral over the polygon's edges with the points in the lanes of AVX2 vectors (a scalar loop
/// without AVX2); the same values as four calls to round-off.
void lambert_form_factors4(const std::array<Vec3, 4>& points, const Vec3& n, const ConvexPolygon& polygon,
                           std::array<double, 4>& out);

/// The polygon clipped to the receiver's front half-space {x : dot(n, x - p) >= 0}.
ConvexPolygon clip_to_horizon(const Vec3& p, const Vec3& n, const ConvexPolygon& polygon);

}  // namespace radrecon
