#include "reconstruct/multiquadric_basis.h"

#include <string>

#include <Eigen/LU>

#include "core/check.h"
#include "core/parse.h"
#include "reconstruct/interpolant.h"
#include "reconstruct/kdtree.h"

namespace radrecon {

std::vector<double> eck_radii_sq(std::span<const Vec2> points, const KdTree2& tree) {
  RR_CHECK_EQ(tree.size(), points.size(), "the tree must be built over the points");
  RR_CHECK_GE(points.size(), size_t{2}, "Eck's radii need at least 2 points");
  std::vector<double> r_sq(points.size());
  unsigned idx[2];
  double d2[2];
  for (size_t i = 0; i < points.size(); ++i) {
    tree.nearest(points[i], 2, idx, d2);  // the point itself (or a duplicate of it) and the next
    if (d2[1] == 0)
      throw ReconstructionError("two samples at the same point (" + format_number(points[i].x()) + ", " +
                                format_number(points[i].y()) + ")");
    r_sq[i] = d2[1];
  }
  return r_sq;
}

MultiquadricFit fit_multiquadric(std::span<const Vec2> points, std::span<const double> r_sq,
                                 std::span<const double> values, int channels, double mu,
                                 std::vector<unsigned> subset) {
  const Eigen::Index m = static_cast<Eigen::Index>(subset.size());
  Eigen::MatrixXd A(m, m), B(m, channels);
  for (Eigen::Index a = 0; a < m; ++a) {
    const unsigned sa = subset[static_cast<size_t>(a)];
    for (Eigen::Index b = 0; b < m; ++b) {
      const unsigned sb = subset[static_cast<size_t>(b)];
      A(a, b) = multiquadric_basis((points[sa] - points[sb]).squaredNorm() + r_sq[sb], mu);
    }
    for (int c = 0; c < channels; ++c) B(a, c) = values[sa * static_cast<size_t>(channels) + c];
  }
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(A);
  MultiquadricFit fit;
  fit.rcond = lu.rcond();
  if (!(fit.rcond > 0) || !std::isfinite(fit.rcond))
    throw ReconstructionError("the multiquadric system is singular (duplicate samples?)");
  const Eigen::MatrixXd alpha = lu.solve(B);
  if (!alpha.allFinite())
    throw ReconstructionError("the multiquadric coefficients overflow: the sample values are too large for the "
                              "system (scale them down)");
  fit.alpha.resize(subset.size() * static_cast<size_t>(channels));
  for (Eigen::Index a = 0; a < m; ++a)
    for (int c = 0; c < channels; ++c) fit.alpha[static_cast<size_t>(a) * channels + c] = alpha(a, c);
  const size_t count = subset.size();
  fit.px.resize(count);
  fit.py.resize(count);
  fit.r_sq.resize(count);
  fit.alpha_by_channel.resize(count * static_cast<size_t>(channels));
  for (size_t a = 0; a < count; ++a) {
    fit.px[a] = points[subset[a]].x();
    fit.py[a] = points[subset[a]].y();
    fit.r_sq[a] = r_sq[subset[a]];
    for (int c = 0; c < channels; ++c) fit.alpha_by_channel[static_cast<size_t>(c) * count + a] = fit.alpha[a * channels + c];
  }
  fit.subset = std::move(subset);
  return fit;
}

}  // namespace radrecon
