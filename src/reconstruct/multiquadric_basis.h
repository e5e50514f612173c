#pragma once
// The one home of Hardy's multiquadric basis and Eck's radii, shared by the global multiquadric
// (multiquadric.h) and its partition of unity of local patches (local_multiquadric.h).

#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <shared_mutex>
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

/// The multiquadric through the samples `subset` of `points`: coefficients alpha_j for
/// sum_j alpha_j (d(q, p_j)^2 + r_j^2)^mu, by dense LU with partial pivoting (Eigen).
struct MultiquadricFit {
  std::vector<unsigned> subset;  ///< sample indices
  std::vector<double> alpha;     ///< subset.size() * channels, sample-major
  double rcond = 1;              ///< reciprocal condition estimate of the system
  // The same for evaluation as arrays (SIMD): the subset's coordinates, r^2, and alpha channel by
  // channel.
  std::vector<double> px, py, r_sq, alpha_by_channel;
};

/// Fits the multiquadric through `subset` (values: channels per point, point-major). Throws
/// ReconstructionError when the system is singular or its coefficients overflow.
MultiquadricFit fit_multiquadric(std::span<const Vec2> points, std::span<const double> r_sq,
                                 std::span<const double> values, int channels, double mu,
                                 std::vector<unsigned> subset);

/// Fits over subsets of the samples, each solved once and shared: with barriers, a query's
/// multiquadric is the one through the samples it sees, and neighbouring queries see the same.
/// Thread-safe; a fit depends on its subset alone, so results do not depend on which thread
/// solved it first.
class MultiquadricFitCache {
 public:
  /// The fit through `subset` (sorted sample indices) under `key` (e.g. a patch), solved with
  /// `solve` the first time.
  template <typename Solve>
  std::shared_ptr<const MultiquadricFit> get(unsigned key, const std::vector<unsigned>& subset, Solve&& solve) const {
    {
      std::shared_lock lock(mutex_);
      const auto it = fits_.find({key, subset});
      if (it != fits_.end()) return it->second;
    }
    auto fit = std::make_shared<const MultiquadricFit>(solve());
    std::unique_lock lock(mutex_);
    return fits_.try_emplace({key, subset}, std::move(fit)).first->second;
  }

 private:
  mutable std::shared_mutex mutex_;
  mutable std::map<std::pair<unsigned, std::vector<unsigned>>, std::shared_ptr<const MultiquadricFit>> fits_;
};

}  // namespace radrecon
