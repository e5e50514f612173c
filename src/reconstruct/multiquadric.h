#pragma once
// Hardy's multiquadrics (the paper's sec. 2.2.2): B(q) = sum_j alpha_j (d(q, p_j)^2 + r_j^2)^mu,
// with alpha from the interpolation conditions B(p_i) = B_i, solved densely by LU with partial
// pivoting (Eigen). r_j is a constant r, or by Eck's rule the distance from p_j to its nearest
// other sample. A poorly conditioned system (reciprocal condition estimate below
// kPoorConditioning) is reported on stderr.
//
// With barriers (barriers.h): a query's value is the multiquadric through the samples it sees
// (the same radii r_j), each such subset's system solved once and shared by every query that
// sees it. Exact at the samples, continuous except across barriers and the sight lines grazing a
// barrier's free end; a query that sees no sample gets NaN.

#include <memory>
#include <optional>

#include <Eigen/Core>

#include "reconstruct/barriers.h"
#include "reconstruct/interpolant.h"
#include "reconstruct/multiquadric_basis.h"
#include "reconstruct/samples.h"

namespace radrecon {

class Multiquadric final : public Interpolant {
 public:
  /// mu != 0; r > 0 if given. Needs 2 distinct samples without r, 1 with it.
  Multiquadric(const ScatteredSamples& samples, double mu, std::optional<double> r_m, Barriers barriers = {});
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
  // With barriers: the samples' values, and the fits through the subsets queries see.
  Barriers barriers_;
  std::vector<double> values_;
  MultiquadricFitCache fits_;
  std::unique_ptr<PointVisibility> visibility_;
  /// Per-thread buffers of evaluate_visible(), and the fit it used last.
  struct VisibleScratch {
    std::vector<unsigned> visible;
    std::vector<char> hidden;
    std::shared_ptr<const MultiquadricFit> last;
    Eigen::ArrayXd b;
  };
  /// The value at p from the samples visible from it, into out; false (nothing written) when p
  /// sees every sample.
  bool evaluate_visible(const Vec2& p, VisibleScratch& s, double* out) const;
};

}  // namespace radrecon
