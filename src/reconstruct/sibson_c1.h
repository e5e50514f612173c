#pragma once
// Sibson's C1 natural-neighbour interpolant in Farin's form (Farin 1990, "Surfaces over Dirichlet
// tessellations", CAGD 7), and the gradients it needs, fitted at the samples (Sibson 1981;
// CGAL's sibson_gradient_fitting). Internal to the natural-neighbour methods (natural_neighbour.h).
//
// Farin's form: with Sibson's coordinates lambda_i of q over its natural neighbours p_i, the value
// is the cubic Bezier simplex  sum_{i,j,k} b_ijk lambda_i lambda_j lambda_k  whose control points
// come from the values f_i and gradients g_i:
//   b_iii = f_i,
//   b_iij = f_i + g_i . (p_j - p_i) / 3,
//   b_ijk = (b_iij + b_iik + b_jji + b_jjk + b_kki + b_kkj) / 4 - (f_i + f_j + f_k) / 6  (i, j, k distinct).
// It is exact at the samples, C1 away from them, and reproduces quadratic functions when the
// gradients are exact (Sibson's own form reproduces only spherical quadratics). Along a hull edge
// (two coordinates) it is the cubic Hermite curve through the ends' values and slopes.

#include <span>
#include <utility>
#include <vector>

#include "reconstruct/barriers.h"
#include "reconstruct/nn_delaunay.h"

namespace radrecon::nn {

/// The gradient at every sample, per channel: out[(i * channels + c) * 2 + {0, 1}] (value units
/// per metre), the weighted least-squares plane through p_i fitted to its Delaunay neighbours p_j:
///   g_i = argmin_g sum_j w_j (f_j - f_i - g . (p_j - p_i))^2,
/// w_j = lambda_j / |p_j - p_i|^2 with lambda_j the Sibson coordinates of p_i among the other
/// samples (Sibson's choice, CGAL's sibson_gradient_fitting); on the hull, where those do not
/// exist, w_j = 1 / |p_j - p_i|^2, as also where the fit with Sibson's weights is
/// ill-conditioned (tol::kGradientFitConditionRelative: next to the hull), the two blended just
/// above it (tol::kGradientFitBlendRelative), so no gradient jumps there. Neighbours a barrier
/// hides from p_i are left out. A sample whose remaining neighbours lie (nearly) on one line
/// through it gets the gradient of the plane fitted along that line, and none across it; one
/// that has none, gradient 0.
/// `vertex_of[i]` is sample i's vertex in `dt`.
std::vector<double> fit_gradients(const Delaunay& dt, std::span<const Delaunay::Vertex_handle> vertex_of,
                                  std::span<const Vec2> points, std::span<const double> values, int channels,
                                  const Barriers& barriers);

/// Farin's C1 form at the point whose coordinates are `coords` (pairs (sample index, lambda),
/// summing to one) over `points` with `values` and `gradients` (fit_gradients' layout), per
/// channel, into out. O(m^2) in the m coordinates (its sum over triples regrouped by pairs).
void farin_c1(std::span<const std::pair<unsigned, double>> coords, std::span<const Vec2> points,
              std::span<const double> values, std::span<const double> gradients, int channels, double* out);

}  // namespace radrecon::nn
