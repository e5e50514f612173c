#include "reconstruct/multiquadric.h"

#include <cmath>
#include <cstdio>
#include <limits>

#include <Eigen/Core>
#include <Eigen/LU>

#include "core/check.h"
#include "core/tolerances.h"
#include "reconstruct/kdtree.h"
#include "reconstruct/multiquadric_basis.h"
#include "core/parallel.h"

namespace radrecon {

Multiquadric::Multiquadric(const ScatteredSamples& samples, double mu, std::optional<double> r_m)
    : points_(samples.points), channels_(samples.channels), mu_(mu) {
  RR_CHECK(mu != 0, "multiquadric mu must be nonzero");
  const size_t n = points_.size();
  if (n == 0) throw ReconstructionError("multiquadric needs at least one sample");
  if (!r_m && n < 2) throw ReconstructionError("multiquadric with Eck's r needs at least 2 samples (or a fixed radius r)");
  if (r_m) {
    r_sq_.assign(n, *r_m * *r_m);
  } else {
    const KdTree2 tree(points_);
    r_sq_ = eck_radii_sq(points_, tree);
  }
  Eigen::MatrixXd A(n, n);
  for (size_t i = 0; i < n; ++i)
    for (size_t j = 0; j < n; ++j) A(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) =
        multiquadric_basis((points_[i] - points_[j]).squaredNorm() + r_sq_[j], mu_);
  Eigen::MatrixXd B(n, channels_);
  for (size_t i = 0; i < n; ++i)
    for (int c = 0; c < channels_; ++c) B(static_cast<Eigen::Index>(i), c) = samples.values[i * channels_ + c];
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(A);
  rcond_ = lu.rcond();
  if (!(rcond_ > 0) || !std::isfinite(rcond_))
    throw ReconstructionError("the multiquadric system is singular (duplicate samples?)");
  if (rcond_ < tol::kPoorConditioning)
    std::fprintf(stderr, "radrecon: warning: multiquadric system is poorly conditioned (reciprocal condition %.2e); "
                         "results may be inaccurate\n", rcond_);
  const Eigen::MatrixXd alpha = lu.solve(B);
  if (!alpha.allFinite())
    throw ReconstructionError("the multiquadric coefficients overflow: the sample values are too large for the "
                              "system (scale them down)");
  alpha_by_channel_.resize(n * static_cast<size_t>(channels_));
  for (size_t i = 0; i < n; ++i)
    for (int c = 0; c < channels_; ++c) alpha_by_channel_[static_cast<size_t>(c) * n + i] = alpha(static_cast<Eigen::Index>(i), c);
  px_.resize(n);
  py_.resize(n);
  for (size_t i = 0; i < n; ++i) px_[i] = points_[i].x(), py_[i] = points_[i].y();
}

void Multiquadric::evaluate(std::span<const Vec2> points, std::span<double> out) const {
  const int C = channels_;
  RR_CHECK(out.size() == points.size() * static_cast<size_t>(C), "output size does not match the query points");
  const size_t n = points_.size();
  const double* px = px_.data();
  const double* py = py_.data();
  const double* r2 = r_sq_.data();
  parallel_for_with_scratch<Eigen::ArrayXd>(0, static_cast<std::int64_t>(points.size()), [&](std::int64_t k, Eigen::ArrayXd& b) {
    const size_t q = static_cast<size_t>(k);
    const Vec2 p = points[q];
    if (!p.allFinite()) {
      for (int c = 0; c < C; ++c) out[q * C + c] = std::numeric_limits<double>::quiet_NaN();
      return;
    }
    // Basis values for all samples at once, as Eigen arrays: SIMD square roots and sums in a
    // fixed (packet) order, so results do not depend on threads.
    using Array = Eigen::Map<const Eigen::ArrayXd>;
    const Eigen::Index N = static_cast<Eigen::Index>(n);
    b = (p.x() - Array(px, N)).square() + (p.y() - Array(py, N)).square() + Array(r2, N);
    multiquadric_basis_in_place(b, mu_);
    for (int c = 0; c < C; ++c)
      out[q * C + c] = (b * Array(&alpha_by_channel_[static_cast<size_t>(c) * n], N)).sum();
  });
}

}  // namespace radrecon
