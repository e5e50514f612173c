#pragma once
// Global radial basis function interpolants (multiquadric_basis.h has the basis and the system):
// - Hardy's multiquadrics (the paper's sec. 2.2.2): B(q) = sum_j alpha_j (d(q, p_j)^2 + r_j^2)^mu,
//   with alpha from the interpolation conditions B(p_i) = B_i; r_j is a constant r, or by Eck's
//   rule the distance from p_j to its nearest other sample. Optionally (RbfKernel::poly = 1)
//   plus a linear polynomial with the side conditions, which the paper did not use.
// - the thin-plate spline: d^2 log d, always with the linear polynomial (Duchon's minimiser of
//   the bending energy among the interpolants); no shape parameter, independent of the unit of
//   length.
// Solved densely by LU with partial pivoting (Eigen). A poorly conditioned system (reciprocal
// condition estimate below kPoorConditioning) is a warning (core/error.h warn(): stderr, or a
// Python UserWarning). Defined everywhere: outside the samples' hull the multiquadric grows like
// d^(2 mu) (without a polynomial) and the thin-plate spline is its linear polynomial plus a term
// growing like log d.
//
// With barriers (barriers.h): a query's value is the RBF through the samples it sees (the same
// radii r_j; its own polynomial), each such subset's system solved once and shared by every
// query that sees it: the distinct subsets of a call's queries are found first, and most are
// derived from the factorisation of a nearby one (fit_rbf_near(): a few samples added or
// dropped) instead of being factorised afresh. A derived fit is the same interpolant to the
// solves' rounding (checked by its backward error, tol::kRbfNearFitBackwardError), so a value may
// differ in its last ~1e-11 with the other queries of the call (which subset is its root); never
// with the threads or the other channels. Exact at the samples, continuous except across barriers and the sight
// lines grazing a barrier's free end; a query that sees no sample gets NaN. With a polynomial,
// linear functions are reproduced everywhere, barriers or not.

#include <memory>
#include <optional>

#include <Eigen/Core>

#include "reconstruct/barriers.h"
#include "reconstruct/interpolant.h"
#include "reconstruct/multiquadric_basis.h"
#include "reconstruct/samples.h"

namespace radrecon {

/// The global RBF interpolant of any RbfKernel (named after the paper's method).
class Multiquadric final : public Interpolant {
 public:
  /// The multiquadric: kernel.mu != 0; r > 0 if given. Needs 2 distinct samples without r, 1
  /// with it. The thin-plate spline: no r; needs 1 sample, distinct ones.
  Multiquadric(const ScatteredSamples& samples, const RbfKernel& kernel, std::optional<double> r_m,
               Barriers barriers = {});
  /// Hardy's multiquadric without a polynomial, as in the paper.
  Multiquadric(const ScatteredSamples& samples, double mu, std::optional<double> r_m, Barriers barriers = {})
      : Multiquadric(samples, RbfKernel::multiquadric(mu), r_m, std::move(barriers)) {}
  int channels() const override { return channels_; }
  void evaluate(std::span<const Vec2> points, std::span<double> out) const override;

  /// The reciprocal condition number estimate of the interpolation matrix (LU's rcond()).
  double reciprocal_condition() const { return rcond_; }
  /// r_j^2 per sample, m^2 (zeros for the thin-plate spline).
  const std::vector<double>& r_sq() const { return r_sq_; }
  /// The fit through all samples.
  const RbfFit& fit() const { return fit_; }

 private:
  std::vector<Vec2> points_;
  std::vector<double> r_sq_;
  int channels_;
  RbfKernel kernel_;
  RbfFit fit_;  ///< through all samples
  double rcond_ = 1;
  // With barriers: the samples' values, and the fits through the subsets queries see.
  Barriers barriers_;
  std::vector<double> values_;
  RbfFitCache fits_;
  std::unique_ptr<PointVisibility> visibility_;
  /// With barriers: the fits through the subsets the queries see, those not kept yet made at
  /// once (fits_); per query, the index of its fit in the result, or kSeesAll / kSeesNone.
  static constexpr int kSeesAll = -1, kSeesNone = -2;
  std::vector<std::shared_ptr<const RbfFit>> visible_fits(std::span<const Vec2> points, std::vector<int>& fit_of) const;
};

}  // namespace radrecon
