#pragma once
// The one home of Hardy's multiquadric basis and Eck's radii, shared by the global multiquadric
// (multiquadric.h) and its partition of unity of local patches (local_multiquadric.h).

#include <cmath>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "core/vec.h"

namespace radrecon {

class KdTree2;

/// (d^2 + r^2)^mu from dist_sq_plus_r_sq = d^2 + r^2 (m^2), with mu = 1/2 (Hardy's choice and the
/// default) and -1/2 without pow().
inline double multiquadric_basis(double dist_sq_plus_r_sq, double mu) {
  if (mu == 0.5) return std::sqrt(dist_sq_plus_r_sq);
  if (mu == -0.5) return 1.0 / std::sqrt(dist_sq_plus_r_sq);
  return std::pow(dist_sq_plus_r_sq, mu);
}

/// The same basis over an array of d^2 + r^2, in place, with Eigen's packet functions (SIMD):
/// sqrt for mu = 1/2, rsqrt for -1/2, pow otherwise. Its last bits may differ from the scalar
/// form's (rsqrt is not 1 / sqrt in every lane); each evaluator uses one form throughout.
inline void multiquadric_basis_in_place(Eigen::ArrayXd& dist_sq_plus_r_sq, double mu) {
  if (mu == 0.5) dist_sq_plus_r_sq = dist_sq_plus_r_sq.sqrt();
  else if (mu == -0.5) dist_sq_plus_r_sq = dist_sq_plus_r_sq.rsqrt();
  else dist_sq_plus_r_sq = dist_sq_plus_r_sq.pow(mu);
}

/// Eck's radii, squared (m^2): r_i^2 = squared distance from points[i] to its nearest other
/// point, found with `tree` (built over `points`). Needs at least 2 points; throws
/// ReconstructionError naming the point when two coincide.
std::vector<double> eck_radii_sq(std::span<const Vec2> points, const KdTree2& tree);

}  // namespace radrecon
