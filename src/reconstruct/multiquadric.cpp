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

Multiquadric::Multiquadric(const ScatteredSamples& samples, double mu, std::optional<double> r_m, Barriers barriers)
    : points_(samples.points), channels_(samples.channels), mu_(mu), barriers_(std::move(barriers)) {
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
  std::vector<unsigned> all(n);
  for (size_t i = 0; i < n; ++i) all[i] = static_cast<unsigned>(i);
  const MultiquadricFit fit = fit_multiquadric(points_, r_sq_, samples.values, channels_, mu_, std::move(all));
  rcond_ = fit.rcond;
  if (rcond_ < tol::kPoorConditioning)
    std::fprintf(stderr, "radrecon: warning: multiquadric system is poorly conditioned (reciprocal condition %.2e); "
                         "results may be inaccurate\n", rcond_);
  alpha_by_channel_.resize(n * static_cast<size_t>(channels_));
  for (size_t i = 0; i < n; ++i)
    for (int c = 0; c < channels_; ++c) alpha_by_channel_[static_cast<size_t>(c) * n + i] = fit.alpha[i * channels_ + c];
  px_.resize(n);
  py_.resize(n);
  for (size_t i = 0; i < n; ++i) px_[i] = points_[i].x(), py_[i] = points_[i].y();
  if (!barriers_.empty()) {
    values_ = samples.values;
    visibility_ = std::make_unique<PointVisibility>(points_, barriers_);
  }
}

bool Multiquadric::evaluate_visible(const Vec2& p, VisibleScratch& s, double* out) const {
  std::vector<unsigned>& visible = s.visible;
  visibility_->visible_from(p, visible, s.hidden);
  if (visible.size() == points_.size()) return false;  // the global fit, as without barriers
  if (visible.empty()) {
    for (int c = 0; c < channels_; ++c) out[c] = std::numeric_limits<double>::quiet_NaN();
    return true;
  }
  // The last query's fit when it saw the same (coherent queries mostly do), else the cache's.
  if (!s.last || s.last->subset != visible)
    s.last = fits_.get(0, visible, [&] { return fit_multiquadric(points_, r_sq_, values_, channels_, mu_, visible); });
  const MultiquadricFit* fit = s.last.get();
  // As the plain path: basis values as Eigen arrays, sums in a fixed packet order.
  using Array = Eigen::Map<const Eigen::ArrayXd>;
  const Eigen::Index m = static_cast<Eigen::Index>(fit->subset.size());
  s.b = (p.x() - Array(fit->px.data(), m)).square() + (p.y() - Array(fit->py.data(), m)).square() +
        Array(fit->r_sq.data(), m);
  multiquadric_basis_in_place(s.b, mu_);
  for (int c = 0; c < channels_; ++c)
    out[c] = (s.b * Array(&fit->alpha_by_channel[static_cast<size_t>(c) * static_cast<size_t>(m)], m)).sum();
  return true;
}

void Multiquadric::evaluate(std::span<const Vec2> points, std::span<double> out) const {
  const int C = channels_;
  RR_CHECK(out.size() == points.size() * static_cast<size_t>(C), "output size does not match the query points");
  const size_t n = points_.size();
  const double* px = px_.data();
  const double* py = py_.data();
  const double* r2 = r_sq_.data();
  struct Scratch {
    Eigen::ArrayXd b;
    VisibleScratch visible;
  };
  parallel_for_with_scratch<Scratch>(0, static_cast<std::int64_t>(points.size()), [&](std::int64_t k, Scratch& s) {
    const size_t q = static_cast<size_t>(k);
    const Vec2 p = points[q];
    if (!p.allFinite()) {
      for (int c = 0; c < C; ++c) out[q * C + c] = std::numeric_limits<double>::quiet_NaN();
      return;
    }
    if (!barriers_.empty() && evaluate_visible(p, s.visible, &out[q * C])) return;
    Eigen::ArrayXd& b = s.b;
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
