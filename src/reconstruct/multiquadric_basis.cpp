#include "reconstruct/multiquadric_basis.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include "core/math.h"
#include "core/simd.h"

#include "core/check.h"
#include "core/error.h"
#include "core/parallel.h"
#include "core/parse.h"
#include "core/tolerances.h"
#include "reconstruct/interpolant.h"
#include "reconstruct/kdtree.h"
#include "reconstruct/rbf_system.h"

namespace radrecon {

std::vector<double> eck_radii_sq(std::span<const Vec2> points, const KdTree2& tree) {
  RR_CHECK_EQ(tree.size(), points.size(), "the tree must be built over the points");
  RR_CHECK_GE(points.size(), size_t{2}, "Eck's radii need at least 2 points");
  std::vector<double> r_sq(points.size());
  parallel_for(0, static_cast<std::int64_t>(points.size()), [&](std::int64_t k) {
    const size_t i = static_cast<size_t>(k);
    unsigned idx[2];
    double d2[2];
    tree.nearest(points[i], 2, idx, d2);  // the point itself (or a duplicate of it) and the next
    r_sq[i] = d2[1];
  });
  // The first duplicate named, whatever the threads.
  const auto duplicate = std::find(r_sq.begin(), r_sq.end(), 0.0);
  if (duplicate != r_sq.end()) {
    const Vec2& p = points[static_cast<size_t>(duplicate - r_sq.begin())];
    throw ReconstructionError("two samples at the same point (" + format_number(p.x()) + ", " + format_number(p.y()) + ")");
  }
  return r_sq;
}

namespace rbf_system {

/// The polynomial's frame for `subset`: centroid, principal axes scaled by the spreads along
/// them, and how many terms the subset determines (header: tol::kRbfFlatSubsetRelative).
void polynomial_frame(std::span<const Vec2> points, const std::vector<unsigned>& subset, RbfFit& fit) {
  Vec2 centre = Vec2::Zero();
  for (unsigned s : subset) centre += points[s];
  centre /= static_cast<double>(subset.size());
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  double size = 0;
  for (unsigned s : subset) {
    const Vec2 d = points[s] - centre;
    cov += d * d.transpose();
    size = std::max(size, d.norm());
  }
  fit.centre = centre;
  fit.terms = 1;
  if (!(size > 0)) return;  // one sample (or copies of it): the constant only
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(cov);
  const Vec2 along = eigen.eigenvectors().col(1), across = eigen.eigenvectors().col(0);
  double spread_along = 0, spread_across = 0;
  for (unsigned s : subset) {
    const Vec2 d = points[s] - centre;
    spread_along = std::max(spread_along, std::abs(along.dot(d)));
    spread_across = std::max(spread_across, std::abs(across.dot(d)));
  }
  fit.terms = 2;
  fit.axis1 = along / spread_along;
  if (spread_across > tol::kRbfFlatSubsetRelative * spread_along) {
    fit.terms = 3;
    fit.axis2 = across / spread_across;
  }
}

/// The interpolation system of `fit` (its frame and kernel scale set) through its subset, centred
/// by `mean` (per channel): A = [phi P; P^T 0] and the right-hand sides B = [f - mean; 0].
void fill_system(std::span<const double> r_sq, std::span<const double> values, int channels,
                 const RbfKernel& kernel, const RbfFit& fit, const std::vector<double>& mean, Eigen::MatrixXd& A,
                 Eigen::MatrixXd& B) {
  const std::vector<unsigned>& subset = fit.subset;
  const Eigen::Index m = static_cast<Eigen::Index>(subset.size()), t = fit.terms;
  A.resize(m + t, m + t);
  B.resize(m + t, channels);
  // The kernel column by column in packets (SIMD), by the basis evaluate_rbf_fit() uses too:
  // A(a, b) = phi(s (|p_a - p_b|^2 + r_b^2)).
  using Array = Eigen::Map<const Eigen::ArrayXd>;
  const Array sx(fit.px.data(), m), sy(fit.py.data(), m);
  Eigen::ArrayXd v(m);
  for (Eigen::Index b = 0; b < m; ++b) {
    const size_t sb = subset[static_cast<size_t>(b)];
    v = (sx - fit.px[static_cast<size_t>(b)]).square() + (sy - fit.py[static_cast<size_t>(b)]).square() + r_sq[sb];
    if (fit.kernel_scale != 1) v *= fit.kernel_scale;
    rbf_basis_in_place(v, kernel);
    A.col(b).head(m) = v.matrix();
  }
  for (Eigen::Index a = 0; a < m; ++a) {
    const unsigned sa = subset[static_cast<size_t>(a)];
    for (int c = 0; c < channels; ++c) B(a, c) = values[sa * static_cast<size_t>(channels) + c] - mean[static_cast<size_t>(c)];
    if (t > 0) {
      const Vec2 d{fit.px[static_cast<size_t>(a)] - fit.centre.x(), fit.py[static_cast<size_t>(a)] - fit.centre.y()};
      const double u[3] = {1, fit.axis1.dot(d), fit.axis2.dot(d)};
      for (Eigen::Index k = 0; k < t; ++k) A(a, m + k) = A(m + k, a) = u[k];
    }
  }
  A.bottomRightCorner(t, t).setZero();
  B.bottomRows(t).setZero();
}

/// The subset's frame (polynomial and kernel scale) and coordinates into a new fit.
RbfFit frame_fit(std::span<const Vec2> points, std::span<const double> r_sq, const RbfKernel& kernel,
                 std::vector<unsigned> subset) {
  RR_CHECK(!subset.empty(), "an RBF fit needs samples");
  RbfFit fit;
  if (kernel.poly) polynomial_frame(points, subset, fit);
  // The subset's largest squared distance from its centroid (the polynomial's centre if any).
  Vec2 centre = fit.centre;
  if (!kernel.poly) {
    centre = Vec2::Zero();
    for (unsigned s : subset) centre += points[s];
    centre /= static_cast<double>(subset.size());
  }
  double size_sq = 0;
  for (unsigned s : subset) size_sq = std::max(size_sq, (points[s] - centre).squaredNorm());
  if (kernel.is_thin_plate()) {
    if (size_sq > 0) fit.kernel_scale = 1 / size_sq;
  } else {
    // The multiquadric's s (header): a power of 4 near 1 / (size^2 + r^2), so that phi's
    // arguments are of order 1 whatever the unit (not 1e100^mu, which overflows for mu > ~3).
    // A power of 4 scales d^2 + r^2 exactly and, for mu = 1/2, phi by an exact power of 2 too:
    // the fit is the unscaled one to the bit.
    double largest_r_sq = 0;
    for (unsigned s : subset) largest_r_sq = std::max(largest_r_sq, r_sq[s]);
    const double typical_sq = size_sq + largest_r_sq;
    if (typical_sq > 0 && std::isfinite(typical_sq)) {
      int exponent = 0;  // typical_sq = m 2^exponent, m in [1/2, 1)
      std::frexp(typical_sq, &exponent);
      // s = 4^-half, s typical_sq in [1/2, 2); half >= -511 keeps s finite (2^1022 at most) for
      // samples less than 1e-154 apart.
      const int half = std::max(static_cast<int>(std::floor(exponent / 2.0)), -511);
      fit.kernel_scale = std::ldexp(1.0, -2 * half);
    }
  }
  fit.px.resize(subset.size());
  fit.py.resize(subset.size());
  for (size_t a = 0; a < subset.size(); ++a) fit.px[a] = points[subset[a]].x(), fit.py[a] = points[subset[a]].y();
  fit.subset = std::move(subset);
  return fit;
}

/// The values' mean per channel over the subset, taken out of the system into c_0 (with a
/// polynomial) or into the offset; zeros otherwise.
std::vector<double> subset_mean(std::span<const double> values, int channels, const std::vector<unsigned>& subset,
                                bool centre) {
  std::vector<double> mean(static_cast<size_t>(channels), 0.0);
  if (!centre) return mean;
  for (unsigned s : subset)
    for (int c = 0; c < channels; ++c) mean[static_cast<size_t>(c)] += values[s * static_cast<size_t>(channels) + c];
  for (double& v : mean) v /= static_cast<double>(subset.size());
  return mean;
}

/// The coefficients x (alpha of the subset's samples, then the polynomial's) into the fit.
void set_coefficients(std::span<const double> r_sq, int channels, const RbfKernel& kernel, bool centre_values,
                      const std::vector<double>& mean, const Eigen::MatrixXd& x, RbfFit& fit) {
  if (!x.allFinite())
    throw ReconstructionError("the " + kernel.name() + " coefficients overflow: the sample values are too large "
                              "for the system (scale them down)");
  const size_t count = fit.subset.size();
  const Eigen::Index m = static_cast<Eigen::Index>(count), t = fit.terms;
  fit.r_sq.resize(count);
  fit.alpha_by_channel.resize(count * static_cast<size_t>(channels));
  for (size_t a = 0; a < count; ++a) {
    fit.r_sq[a] = r_sq[fit.subset[a]];
    for (int c = 0; c < channels; ++c) fit.alpha_by_channel[static_cast<size_t>(c) * count + a] = x(static_cast<Eigen::Index>(a), c);
  }
  fit.poly.resize(static_cast<size_t>(t) * channels);
  for (int c = 0; c < channels; ++c)
    for (Eigen::Index k = 0; k < t; ++k)
      fit.poly[static_cast<size_t>(c * t + k)] = x(m + k, c) + (k == 0 ? mean[static_cast<size_t>(c)] : 0.0);
  if (t == 0 && centre_values) fit.offset = mean;
}

void check_factorisation(double rcond, const RbfKernel& kernel) {
  if (!(rcond > 0) || !std::isfinite(rcond))
    throw ReconstructionError("the " + kernel.name() + " system is singular (duplicate samples?)");
}

void warn_if_poorly_conditioned(double rcond, const std::string& system, const std::string& suffix) {
  if (!(rcond < tol::kPoorConditioning)) return;
  char condition[32];
  std::snprintf(condition, sizeof condition, "%.2e", rcond);
  warn(system + " is poorly conditioned (reciprocal condition " + condition + ")" + suffix);
}

}  // namespace rbf_system

using rbf_system::check_factorisation, rbf_system::fill_system, rbf_system::frame_fit, rbf_system::set_coefficients,
    rbf_system::subset_mean;

RbfFit fit_rbf(std::span<const Vec2> points, std::span<const double> r_sq, std::span<const double> values,
               int channels, const RbfKernel& kernel, std::vector<unsigned> subset, bool centre_values) {
  RbfFit fit = frame_fit(points, r_sq, kernel, std::move(subset));
  const std::vector<double> mean = subset_mean(values, channels, fit.subset, fit.terms > 0 || centre_values);
  Eigen::MatrixXd A, B;
  fill_system(r_sq, values, channels, kernel, fit, mean, A, B);
  const Eigen::PartialPivLU<Eigen::Ref<Eigen::MatrixXd>> lu(A);  // in place: A becomes its LU
  fit.rcond = lu.rcond();
  check_factorisation(fit.rcond, kernel);
  set_coefficients(r_sq, channels, kernel, centre_values, mean, lu.solve(B), fit);
  return fit;
}

void evaluate_rbf_fit(const RbfFit& fit, const RbfKernel& kernel, int channels, const Vec2& p, Eigen::ArrayXd& b,
                      double* out) {
  for (int c = 0; c < channels; ++c) out[c] = 0;
  add_rbf_sum(fit, kernel, channels, p, 1.0, b, out);
  for (int c = 0; c < channels; ++c) out[c] += fit.polynomial(p, c);
}

void add_rbf_sum(const RbfFit& fit, const RbfKernel& kernel, int channels, const Vec2& p, double weight,
                 Eigen::ArrayXd& b, double* out) {
#if RADRECON_SIMD
  // The multiquadric (mu = 1/2) for up to three channels in one pass over the samples, the
  // basis and the sums in registers (the general path below stores the basis first); the last
  // packet masked.
  if (!kernel.is_thin_plate() && kernel.mu == 0.5 && channels <= 3) {
    using simd::PackD;
    constexpr int L = PackD::kLanes;
    const size_t m = fit.subset.size();
    const double *xs = fit.px.data(), *ys = fit.py.data(), *rs = fit.r_sq.data();
    const double* a0 = fit.alpha_by_channel.data();
    const double* a1 = channels > 1 ? a0 + m : a0;
    const double* a2 = channels > 2 ? a0 + 2 * m : a0;
    const bool scaled = fit.kernel_scale != 1;
    const PackD x = PackD::set(p.x()), y = PackD::set(p.y()), s = PackD::set(fit.kernel_scale);
    PackD sum0 = PackD::zero(), sum1 = sum0, sum2 = sum0;
    // phi of the packet at i times its alphas into the sums; `load` reads a packet (masked or
    // not), `keep` sets the unmasked lanes' v to 0 (finite whatever the query).
    const auto add = [&](size_t i, const auto& load, const auto& keep) {
      const PackD dx = x - load(xs + i), dy = y - load(ys + i);
      PackD v = (dx * dx + dy * dy) + load(rs + i);  // as fill_system() has it: exact at the samples
      if (scaled) v = v * s;
      const PackD phi = sqrt(keep(v));
      sum0 = fmadd(phi, load(a0 + i), sum0);
      if (channels > 1) sum1 = fmadd(phi, load(a1 + i), sum1);
      if (channels > 2) sum2 = fmadd(phi, load(a2 + i), sum2);
    };
    size_t i = 0;
    for (; i + L <= m; i += L) add(i, [](const double* q) { return PackD::load(q); }, [](PackD v) { return v; });
    if (i < m) {  // the lanes past the end: phi(0) times alpha 0 adds nothing
      const PackD::Mask tail = PackD::Mask::first(static_cast<int>(m - i));
      add(i, [&](const double* q) { return PackD::load(q, tail); },
          [&](PackD v) { return PackD::select(tail, v, PackD::zero()); });
    }
    out[0] += weight * sum0.sum();
    if (channels > 1) out[1] += weight * sum1.sum();
    if (channels > 2) out[2] += weight * sum2.sum();
    return;
  }
#endif
  using Array = Eigen::Map<const Eigen::ArrayXd>;
  const Eigen::Index m = static_cast<Eigen::Index>(fit.subset.size());
  b = (p.x() - Array(fit.px.data(), m)).square() + (p.y() - Array(fit.py.data(), m)).square() +
      Array(fit.r_sq.data(), m);
  if (fit.kernel_scale != 1) b *= fit.kernel_scale;
  rbf_basis_in_place(b, kernel);
  for (int c = 0; c < channels; ++c)
    out[c] += weight * (b * Array(&fit.alpha_by_channel[static_cast<size_t>(c) * static_cast<size_t>(m)], m)).sum();
}

}  // namespace radrecon
