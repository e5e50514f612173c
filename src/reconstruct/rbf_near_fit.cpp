// RBF fits derived from a nearby root's factorisation (reconstruct/multiquadric_basis.h,
// fit_rbf_root() and fit_rbf_near()): a bordered Schur complement for the samples a subset adds,
// a constraint system for those it drops, checked by its backward error.

#include <algorithm>
#include <optional>

#include <Eigen/LU>

#include "core/check.h"
#include "core/tolerances.h"
#include "reconstruct/multiquadric_basis.h"
#include "reconstruct/rbf_system.h"

namespace radrecon {

using rbf_system::check_factorisation, rbf_system::fill_system, rbf_system::frame_fit, rbf_system::polynomial_frame,
    rbf_system::set_coefficients, rbf_system::subset_mean;

RbfRootFit fit_rbf_root(std::span<const Vec2> points, std::span<const double> r_sq, std::span<const double> values,
                        int channels, const RbfKernel& kernel, std::vector<unsigned> subset) {
  RbfRootFit root;
  root.fit = frame_fit(points, r_sq, kernel, std::move(subset));
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

}  // namespace radrecon
