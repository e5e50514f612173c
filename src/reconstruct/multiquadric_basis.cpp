#include "reconstruct/multiquadric_basis.h"

#if defined(__AVX2__) && defined(__FMA__)
#include <immintrin.h>
#endif

#include <algorithm>
#include <cstdint>
#include <optional>
#include <string>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include "core/math.h"

#include "core/check.h"
#include "core/parallel.h"
#include "core/parse.h"
#include "core/tolerances.h"
#include "reconstruct/interpolant.h"
#include "reconstruct/kdtree.h"

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

namespace {

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

}  // namespace

namespace {

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
RbfFit frame_fit(std::span<const Vec2> points, const RbfKernel& kernel, std::vector<unsigned> subset) {
  RR_CHECK(!subset.empty(), "an RBF fit needs samples");
  RbfFit fit;
  if (kernel.poly) polynomial_frame(points, subset, fit);
  if (kernel.is_thin_plate()) {
    double size_sq = 0;
    for (unsigned s : subset) size_sq = std::max(size_sq, (points[s] - fit.centre).squaredNorm());
    if (size_sq > 0) fit.kernel_scale = 1 / size_sq;
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

}  // namespace

RbfFit fit_rbf(std::span<const Vec2> points, std::span<const double> r_sq, std::span<const double> values,
               int channels, const RbfKernel& kernel, std::vector<unsigned> subset, bool centre_values) {
  RbfFit fit = frame_fit(points, kernel, std::move(subset));
  const std::vector<double> mean = subset_mean(values, channels, fit.subset, fit.terms > 0 || centre_values);
  Eigen::MatrixXd A, B;
  fill_system(r_sq, values, channels, kernel, fit, mean, A, B);
  const Eigen::PartialPivLU<Eigen::Ref<Eigen::MatrixXd>> lu(A);  // in place: A becomes its LU
  fit.rcond = lu.rcond();
  check_factorisation(fit.rcond, kernel);
  set_coefficients(r_sq, channels, kernel, centre_values, mean, lu.solve(B), fit);
  return fit;
}

RbfRootFit fit_rbf_root(std::span<const Vec2> points, std::span<const double> r_sq, std::span<const double> values,
                        int channels, const RbfKernel& kernel, std::vector<unsigned> subset) {
  RbfRootFit root;
  root.fit = frame_fit(points, kernel, std::move(subset));
  const std::vector<double> mean = subset_mean(values, channels, root.fit.subset, root.fit.terms > 0);
  Eigen::MatrixXd A, B;
  fill_system(r_sq, values, channels, kernel, root.fit, mean, A, B);
  root.system = A;
  root.lu.compute(A);
  root.fit.rcond = root.lu.rcond();
  check_factorisation(root.fit.rcond, kernel);
  set_coefficients(r_sq, channels, kernel, false, mean, root.lu.solve(B), root.fit);
  return root;
}

namespace {

/// lu⁻¹ rhs, or rhs's own empty shape when it has no columns: Eigen's solve of an empty
/// right-hand side offsets a null pointer (undefined behaviour the sanitizers report).
Eigen::MatrixXd solve_columns(const Eigen::PartialPivLU<Eigen::MatrixXd>& lu, const Eigen::MatrixXd& rhs) {
  if (rhs.cols() == 0) return Eigen::MatrixXd(lu.rows(), 0);
  return lu.solve(rhs);
}

}  // namespace

std::optional<RbfFit> fit_rbf_near(const RbfRootFit& root, std::span<const Vec2> points, std::span<const double> r_sq,
                                   std::span<const double> values, int channels, const RbfKernel& kernel,
                                   std::vector<unsigned> subset) {
  RR_CHECK(!subset.empty(), "an RBF fit needs samples");
  using Eigen::Index, Eigen::MatrixXd, Eigen::VectorXd;
  const RbfFit& base = root.fit;
  const std::vector<unsigned>& from = base.subset;
  const Index mb = static_cast<Index>(from.size()), t = base.terms, n_root = mb + t;
  // The subset's own frame must have the root's terms (a subset on one line has fewer).
  if (kernel.poly) {
    RbfFit own;
    polynomial_frame(points, subset, own);
    if (own.terms != t) return std::nullopt;
  }
  // R: the root's samples the subset drops (their positions in the root); D: those it adds.
  std::vector<Index> dropped;
  std::vector<unsigned> added;
  {
    size_t a = 0, b = 0;
    while (a < from.size() || b < subset.size()) {
      if (b == subset.size() || (a < from.size() && from[a] < subset[b])) dropped.push_back(static_cast<Index>(a++));
      else if (a == from.size() || subset[b] < from[a]) added.push_back(subset[b++]);
      else ++a, ++b;
    }
  }
  const Index nd = static_cast<Index>(added.size()), nr = static_cast<Index>(dropped.size());
  const double s = base.kernel_scale;
  const auto phi = [&](double dx, double dy, double rr) { return rbf_basis(s * (dx * dx + dy * dy + rr), kernel); };
  const auto poly_terms = [&](const Vec2& p, double* u) {
    const Vec2 d = p - base.centre;
    u[0] = 1, u[1] = base.axis1.dot(d), u[2] = base.axis2.dot(d);
  };

  // The operator, whatever the values. With K the root's system, the system on root + added is
  // [K cols; rows corner] by blocks: W = K^-1 cols, and the Schur complement S = corner - rows W.
  // The dropped rows' equations then give way to their unknowns being 0, through the unit
  // columns e_r: their solutions U (and U_added) and the constraint matrix U at the dropped rows.
  MatrixXd cols = MatrixXd::Zero(n_root, nd + nr);
  double u[3];
  for (Index j = 0; j < nd; ++j) {
    const Vec2& p = points[added[static_cast<size_t>(j)]];
    const double rr = r_sq[added[static_cast<size_t>(j)]];
    for (Index a = 0; a < mb; ++a) cols(a, j) = phi(base.px[static_cast<size_t>(a)] - p.x(), base.py[static_cast<size_t>(a)] - p.y(), rr);
    poly_terms(p, u);
    for (Index k = 0; k < t; ++k) cols(mb + k, j) = u[k];
  }
  for (Index j = 0; j < nr; ++j) cols(dropped[static_cast<size_t>(j)], nd + j) = 1;
  const MatrixXd x = solve_columns(root.lu, cols);
  const auto W = x.leftCols(nd);
  MatrixXd rows(nd, n_root), corner(nd, nd);
  for (Index i = 0; i < nd; ++i) {
    const Vec2& p = points[added[static_cast<size_t>(i)]];
    for (Index a = 0; a < mb; ++a)
      rows(i, a) = phi(p.x() - base.px[static_cast<size_t>(a)], p.y() - base.py[static_cast<size_t>(a)], base.r_sq[static_cast<size_t>(a)]);
    poly_terms(p, u);
    for (Index k = 0; k < t; ++k) rows(i, mb + k) = u[k];
    for (Index j = 0; j < nd; ++j) {
      const Vec2& q = points[added[static_cast<size_t>(j)]];
      corner(i, j) = phi(p.x() - q.x(), p.y() - q.y(), r_sq[added[static_cast<size_t>(j)]]);
    }
  }
  Eigen::PartialPivLU<MatrixXd> schur;
  MatrixXd units = x.rightCols(nr), units_added(nd, nr);
  if (nd > 0) {
    schur.compute(corner - rows * W);
    if (!(schur.rcond() > 0)) return std::nullopt;  // singular: the direct fit says why
    units_added = solve_columns(schur, -rows * x.rightCols(nr));
    units -= W * units_added;
  }
  Eigen::PartialPivLU<MatrixXd> constraint;
  if (nr > 0) {
    MatrixXd at_dropped(nr, nr);
    for (Index i = 0; i < nr; ++i) at_dropped.row(i) = units.row(dropped[static_cast<size_t>(i)]);
    constraint.compute(at_dropped);
    if (!(constraint.rcond() > 0)) return std::nullopt;
  }

  // One right-hand side: the subset's values (centred) at the root's kept rows and the added
  // ones; the root's dropped samples get 0, so that their values never enter. Vector by vector,
  // so that a channel's arithmetic does not depend on how many there are.
  const Index m = static_cast<Index>(subset.size());
  RbfFit fit;
  fit.rcond = base.rcond;
  fit.kernel_scale = s;
  fit.terms = base.terms;
  fit.centre = base.centre, fit.axis1 = base.axis1, fit.axis2 = base.axis2;
  fit.px.resize(static_cast<size_t>(m));
  fit.py.resize(static_cast<size_t>(m));
  for (Index k = 0; k < m; ++k) {
    fit.px[static_cast<size_t>(k)] = points[subset[static_cast<size_t>(k)]].x();
    fit.py[static_cast<size_t>(k)] = points[subset[static_cast<size_t>(k)]].y();
  }
  fit.subset = std::move(subset);
  const std::vector<unsigned>& order = fit.subset;
  // The solution for one right-hand side in the root's order (y, zero at the dropped samples) and
  // the added samples' (y_added).
  const auto solve_parts = [&](const auto& value_of, VectorXd& y, VectorXd& y_added) {
    VectorXd v = VectorXd::Zero(n_root), v_added(nd);
    {
      size_t at = 0;  // the next dropped position
      for (Index a = 0; a < mb; ++a) {
        if (at < dropped.size() && dropped[at] == a) ++at;
        else v(a) = value_of(from[static_cast<size_t>(a)]);
      }
    }
    for (Index i = 0; i < nd; ++i) v_added(i) = value_of(added[static_cast<size_t>(i)]);
    y = root.lu.solve(v);
    y_added.resize(nd);
    if (nd > 0) {
      y_added = schur.solve(v_added - rows * y);
      y -= W * y_added;
    }
    if (nr > 0) {
      VectorXd at_dropped(nr);
      for (Index i = 0; i < nr; ++i) at_dropped(i) = y(dropped[static_cast<size_t>(i)]);
      const VectorXd l = constraint.solve(-at_dropped);
      y += units * l;
      if (nd > 0) y_added += units_added * l;
      for (Index i : dropped) y(i) = 0;  // to rounding already; the fit leaves them out
    }
  };
  // In the subset's order: the root's kept samples and the added, merged.
  const auto merge = [&](const VectorXd& y, const VectorXd& y_added) {
    VectorXd out(m + t);
    size_t a = 0, j = 0;
    for (Index k = 0; k < m; ++k) {
      if (j < added.size() && added[j] == order[static_cast<size_t>(k)]) {
        out(k) = y_added(static_cast<Index>(j++));
      } else {
        while (from[a] != order[static_cast<size_t>(k)]) ++a;  // past the dropped ones
        out(k) = y(static_cast<Index>(a++));
      }
    }
    out.tail(t) = y.tail(t);
    return out;
  };

  // The update is checked, not trusted: its backward error on the subset's own system (each
  // row's residual against the size of its terms) must be at round-off's. The system by blocks,
  // [K_kept cols_kept; rows corner] (the root's matrix, kept with its LU, for the root's rows and
  // columns; the rows of the dropped samples left out). Checked on a probe, fixed pseudo-random
  // values (not the data's), so that whether a fit is derived does not depend on the values or
  // on their channels.
  std::vector<double> probe(points.size());
  {
    std::uint64_t state = 0x9e3779b97f4a7c15ULL;  // splitmix64, for values in [-1, 1)
    for (double& p : probe) {
      std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
      z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
      z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
      p = static_cast<double>((z ^ (z >> 31)) >> 11) * 0x1p-52 - 1.0;
    }
  }
  {
    VectorXd y, y_added;
    solve_parts([&](unsigned sample) { return probe[sample]; }, y, y_added);
    if (!y.allFinite() || !y_added.allFinite()) return std::nullopt;
    const auto added_cols = cols.leftCols(nd);
    VectorXd residual = root.system * y, size = root.system.cwiseAbs() * y.cwiseAbs();
    VectorXd residual_added = rows * y, size_added = rows.cwiseAbs() * y.cwiseAbs();
    if (nd > 0) {
      residual += added_cols * y_added, size += added_cols.cwiseAbs() * y_added.cwiseAbs();
      residual_added += corner * y_added, size_added += corner.cwiseAbs() * y_added.cwiseAbs();
    }
    const auto within = [](double r, double of) { return std::abs(r) <= tol::kRbfNearFitBackwardError * of; };
    size_t at = 0;  // the next dropped position
    for (Index a = 0; a < n_root; ++a) {
      if (at < dropped.size() && dropped[at] == a) {
        ++at;
        continue;
      }
      const double f = a < mb ? probe[from[static_cast<size_t>(a)]] : 0.0;
      if (!within(residual(a) - f, size(a) + std::abs(f))) return std::nullopt;
    }
    for (Index i = 0; i < nd; ++i) {
      const double f = probe[added[static_cast<size_t>(i)]];
      if (!within(residual_added(i) - f, size_added(i) + std::abs(f))) return std::nullopt;
    }
  }

  const int C = channels;
  const std::vector<double> mean = subset_mean(values, C, fit.subset, t > 0);
  MatrixXd coefficients(m + t, C);
  for (int c = 0; c < C; ++c) {
    VectorXd y, y_added;
    const auto value_of = [&](unsigned sample) {
      return values[sample * static_cast<size_t>(C) + c] - mean[static_cast<size_t>(c)];
    };
    solve_parts(value_of, y, y_added);
    coefficients.col(c) = merge(y, y_added);
  }
  if (!coefficients.allFinite()) return std::nullopt;
  set_coefficients(r_sq, C, kernel, false, mean, coefficients, fit);
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
#if defined(__AVX2__) && defined(__FMA__)
  // The multiquadric (mu = 1/2) for up to three channels in one pass over the samples, the
  // basis and the sums in AVX2 registers (the general path below stores the basis first).
  if (!kernel.is_thin_plate() && kernel.mu == 0.5 && channels <= 3) {
    const size_t m = fit.subset.size();
    const double *xs = fit.px.data(), *ys = fit.py.data(), *rs = fit.r_sq.data();
    const double* a0 = fit.alpha_by_channel.data();
    const double* a1 = channels > 1 ? a0 + m : a0;
    const double* a2 = channels > 2 ? a0 + 2 * m : a0;
    const double scale = fit.kernel_scale;
    const __m256d x = _mm256_set1_pd(p.x()), y = _mm256_set1_pd(p.y()), s = _mm256_set1_pd(scale);
    __m256d sum0 = _mm256_setzero_pd(), sum1 = sum0, sum2 = sum0;
    size_t i = 0;
    for (; i + 4 <= m; i += 4) {
      const __m256d dx = _mm256_sub_pd(x, _mm256_loadu_pd(xs + i)), dy = _mm256_sub_pd(y, _mm256_loadu_pd(ys + i));
      __m256d v = _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy)), _mm256_loadu_pd(rs + i));
      if (scale != 1) v = _mm256_mul_pd(v, s);
      const __m256d phi = _mm256_sqrt_pd(v);
      sum0 = _mm256_fmadd_pd(phi, _mm256_loadu_pd(a0 + i), sum0);
      if (channels > 1) sum1 = _mm256_fmadd_pd(phi, _mm256_loadu_pd(a1 + i), sum1);
      if (channels > 2) sum2 = _mm256_fmadd_pd(phi, _mm256_loadu_pd(a2 + i), sum2);
    }
    double t0 = sum_lanes(sum0), t1 = sum_lanes(sum1), t2 = sum_lanes(sum2);
    for (; i < m; ++i) {
      const double dx = p.x() - xs[i], dy = p.y() - ys[i];
      double v = dx * dx + dy * dy + rs[i];
      if (scale != 1) v *= scale;
      const double phi = std::sqrt(v);
      t0 += phi * a0[i];
      t1 += phi * a1[i];
      t2 += phi * a2[i];
    }
    out[0] += weight * t0;
    if (channels > 1) out[1] += weight * t1;
    if (channels > 2) out[2] += weight * t2;
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
