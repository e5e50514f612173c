#include "reconstruct/multiquadric.h"

#include <cmath>
#include <cstdio>
#include <limits>

#include <Eigen/Core>

#include "core/check.h"
#include "core/parallel.h"
#include "core/tolerances.h"
#include "reconstruct/kdtree.h"
#include "reconstruct/multiquadric_basis.h"

namespace radrecon {

Multiquadric::Multiquadric(const ScatteredSamples& samples, const RbfKernel& kernel, std::optional<double> r_m,
                           Barriers barriers)
    : points_(samples.points), channels_(samples.channels), kernel_(kernel), barriers_(std::move(barriers)) {
  RR_CHECK(kernel.is_thin_plate() || kernel.mu != 0, "multiquadric mu must be nonzero");
  RR_CHECK(!kernel.is_thin_plate() || !r_m, "the thin-plate spline has no radius");
  const size_t n = points_.size();
  const std::string name = kernel_.name();
  if (n == 0) throw ReconstructionError(name + " needs at least one sample");
  if (kernel_.is_thin_plate()) {
    if (n >= 2) eck_radii_sq(points_, KdTree2(points_));  // refuses duplicate samples by name
    r_sq_.assign(n, 0.0);
  } else if (r_m) {
    r_sq_.assign(n, *r_m * *r_m);
  } else {
    if (n < 2) throw ReconstructionError("multiquadric with Eck's r needs at least 2 samples (or a fixed radius r)");
    const KdTree2 tree(points_);
    r_sq_ = eck_radii_sq(points_, tree);
  }
  std::vector<unsigned> all(n);
  for (size_t i = 0; i < n; ++i) all[i] = static_cast<unsigned>(i);
  fit_ = fit_rbf(points_, r_sq_, samples.values, channels_, kernel_, std::move(all));
  rcond_ = fit_.rcond;
  if (rcond_ < tol::kPoorConditioning)
    std::fprintf(stderr, "radrecon: warning: %s system is poorly conditioned (reciprocal condition %.2e); "
                         "results may be inaccurate\n", name.c_str(), rcond_);
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
    s.last = fits_.get(0, visible, [&] { return fit_rbf(points_, r_sq_, values_, channels_, kernel_, visible); });
  evaluate_rbf_fit(*s.last, kernel_, channels_, p, s.b, out);
  return true;
}

void Multiquadric::evaluate(std::span<const Vec2> points, std::span<double> out) const {
  const int C = channels_;
  RR_CHECK(out.size() == points.size() * static_cast<size_t>(C), "output size does not match the query points");
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
    evaluate_rbf_fit(fit_, kernel_, C, p, s.b, &out[q * C]);
  });
}

}  // namespace radrecon
