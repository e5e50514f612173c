#pragma once
// Hardy's multiquadrics (the paper's sec. 2.2.2): B(q) = sum_j alpha_j (d(q, p_j)^2 + r_j^2)^mu,
// with alpha from the interpolation conditions B(p_i) = B_i, solved densely by LU with partial
// pivoting (Eigen). r_j is a constant r, or by Eck's rule the distance from p_j to its nearest
// other sample. A poorly conditioned system (reciprocal condition estimate below
// kPoorConditioning) is reported on stderr.

#include <optional>

#include "reconstruct/interpolant.h"
#include "reconstruct/samples.h"

namespace radrecon {

class Multiquadric final : public Interpolant {
 public:
  /// mu != 0; r > 0 if given. Needs 2 distinct samples without r, 1 with it.
  Multiquadric(const ScatteredSamples& samples, double mu, std::optional<double> r_m);
  int channels() const override { return channels_; }
  void evaluate(std::span<const Vec2> points, std::span<double> out) const override;

  /// The reciprocal condition number estimate of the interpolation matrix (LU's rcond()).
  double reciprocal_condition() const { return rcond_; }
  /// r_j^2 per sample, m^2.
  const std::vector<double>& r_sq() const { return r_sq_; }

 private:
  std::vector<Vec2> points_;
  std::vector<double> px_, py_;             ///< the points as a structure of arrays
  std::vector<double> r_sq_;
  std::vector<double> alpha_by_channel_;  ///< channels * points.size(), channel by channel
  int channels_;
  double mu_;
  double rcond_ = 1;
};

}  // namespace radrecon
