#pragma once
// The one home of the radial basis functions (Hardy's multiquadric and the thin-plate spline),
// their optional linear polynomial, Eck's radii and the dense fit through a subset of samples,
// shared by the global interpolant (multiquadric.h) and its partition of unity of local patches
// (local_multiquadric.h).
//
// A fit through samples p_j (j in a subset) is
//   B(q) = sum_j alpha_j phi(s (d(q, p_j)^2 + r_j^2)) + sum_t c_t u_t(q),
// phi(v) = v^mu (the multiquadric, s a power of 4 near 1 / (size^2 + max r_j^2)) or
// phi(v) = v log(v) / 2 = d^2 log d (the thin-plate spline, r_j = 0, phi(0) = 0, s = 1 / size^2:
// distances in units of the subset's size); size: the subset's largest distance from its centroid. With a
// polynomial, u_0 = 1 and u_1, u_2 are the coordinates along the subset's principal axes about
// its centroid, each divided by the subset's spread along it, so that the polynomial block has
// entries of order 1 whatever the units; the interpolation system is the augmented
//   [A P; P^T 0] [alpha; c] = [f; 0]
// (the side conditions sum_j alpha_j u_t(p_j) = 0), exact at the samples and reproducing linear
// functions. The polynomial holds only the terms the subset determines: a subset on one line
// (spread across below tol::kRbfFlatSubsetRelative of its spread along) drops u_2 (linear along
// the line, constant across), a single sample keeps u_0 only. The values are centred (their mean
// goes to c_0), so that constant data give alpha = 0 and the constant to the bit.
//
// Scale: the thin-plate interpolant does not depend on the unit of length. phi(s d^2) =
// s d^2 log d + (s log s / 2) d^2, and under the side conditions sum_j alpha_j |q - p_j|^2 is a
// constant (its quadratic and linear parts in q vanish), absorbed by c_0: the kernel's scale only
// multiplies alpha. The multiquadric's scale is its radii r_j; its s only multiplies phi by s^mu
// (and alpha by s^-mu), so it changes nothing but the range of the numbers: samples 1e50 m apart
// with mu = 7.5 no longer overflow to a "singular" system.

#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/LU>

#include "core/vec.h"
#include "reconstruct/convex_hull.h"
#include "reconstruct/subset_cache.h"

namespace radrecon {

class KdTree2;

/// The basis and polynomial of an RBF interpolant.
struct RbfKernel {
  enum class Kind { multiquadric, thin_plate };
  Kind kind = Kind::multiquadric;
  double mu = 0.5;  ///< the multiquadric's exponent: nonzero, not (near) a positive integer (methods.h)
  int poly = 0;     ///< 0: no polynomial; 1: a linear polynomial with the side conditions

  static RbfKernel multiquadric(double mu, int poly = 0) { return {Kind::multiquadric, mu, poly}; }
  static RbfKernel thin_plate() { return {Kind::thin_plate, 0, 1}; }
  bool is_thin_plate() const { return kind == Kind::thin_plate; }
  /// "multiquadric" or "thin-plate", for messages.
  std::string name() const { return is_thin_plate() ? "thin-plate" : "multiquadric"; }
};

/// (d^2 + r^2)^mu from dist_sq_plus_r_sq = d^2 + r^2 (m^2), with mu = 1/2 (Hardy's choice and the
/// default) and -1/2 without pow().
inline double multiquadric_basis(double dist_sq_plus_r_sq, double mu) {
  if (mu == 0.5) return std::sqrt(dist_sq_plus_r_sq);
  if (mu == -0.5) return 1.0 / std::sqrt(dist_sq_plus_r_sq);
  return std::pow(dist_sq_plus_r_sq, mu);
}

/// phi(v) of the kernel for v = s (d^2 + r^2) (dimensionless for the thin-plate spline).
inline double rbf_basis(double v, const RbfKernel& kernel) {
  if (kernel.is_thin_plate()) return v > 0 ? 0.5 * v * std::log(v) : 0.0;
  return multiquadric_basis(v, kernel.mu);
}

/// The same basis over an array of v, in place, with Eigen's packet functions (SIMD): sqrt for
/// mu = 1/2, rsqrt for -1/2, pow otherwise, log for the thin-plate spline. Its last bits may
/// differ from the scalar form's (rsqrt is not 1 / sqrt in every lane, Eigen's log is not libm's);
/// fit_rbf() builds its matrix and evaluate_rbf_fit() evaluates with this form (sqrt, the
/// default, is exact in both).
inline void rbf_basis_in_place(Eigen::ArrayXd& v, const RbfKernel& kernel) {
  // The thin-plate spline's phi(0) = 0 as 0 times the log of the least normal double (not of 0,
  // -inf): no select(), which Eigen evaluates lane by lane with std::log.
  if (kernel.is_thin_plate()) v = 0.5 * v * v.max(std::numeric_limits<double>::min()).log();
  else if (kernel.mu == 0.5) v = v.sqrt();
  else if (kernel.mu == -0.5) v = v.rsqrt();
  else v = v.pow(kernel.mu);
}

/// Eck's radii, squared (m^2): r_i^2 = squared distance from points[i] to its nearest other
/// point, found with `tree` (built over `points`). Needs at least 2 points; throws
/// ReconstructionError naming the point when two coincide.
std::vector<double> eck_radii_sq(std::span<const Vec2> points, const KdTree2& tree);

/// The RBF through the samples `subset` of `points` (the header's B), solved by dense LU with
/// partial pivoting (Eigen; the augmented matrix is symmetric indefinite).
struct RbfFit {
  std::vector<unsigned> subset;  ///< sample indices
  /// The subset's convex hull, where a caller keeps it with the fit (the local patches, which
  /// do not extrapolate past it); empty otherwise.
  ConvexHull2 hull;
  double rcond = 1;              ///< reciprocal condition estimate of the system
  // For evaluation as arrays (SIMD): the subset's coordinates, r^2, and the coefficients alpha
  // channel by channel (subset.size() each).
  std::vector<double> px, py, r_sq, alpha_by_channel;
  double kernel_scale = 1;  ///< s: d^2 + r^2 is multiplied by it before phi
  // The polynomial: `terms` of u_0 = 1, u_1 = axis1 . (q - centre), u_2 = axis2 . (q - centre).
  int terms = 0;                 ///< 0 (none), 1, 2 or 3
  Vec2 centre = Vec2::Zero();
  Vec2 axis1 = Vec2::Zero(), axis2 = Vec2::Zero();
  std::vector<double> poly;  ///< terms * channels, channel by channel: c_t of channel c at [c * terms + t]
  /// Without a polynomial: the values' mean per channel, taken out before the fit when asked
  /// (fit_rbf's centre_values); empty otherwise.
  std::vector<double> offset;

  /// The polynomial of channel c at q (without one: the offset, or 0).
  double polynomial(const Vec2& q, int c) const {
    if (terms == 0) return offset.empty() ? 0 : offset[static_cast<size_t>(c)];
    const double* k = &poly[static_cast<size_t>(c) * static_cast<size_t>(terms)];
    double v = k[0];
    const Vec2 d = q - centre;
    if (terms > 1) v += k[1] * axis1.dot(d);
    if (terms > 2) v += k[2] * axis2.dot(d);
    return v;
  }
};

/// Fits the RBF through `subset` (values: channels per point, point-major; r_sq per point, zeros
/// for the thin-plate spline). centre_values, without a polynomial: fit the deviations from the
/// subset's mean and add the mean back (RbfFit::offset), so that constants are reproduced: a
/// multiquadric through a few samples of a large offset (terrain at 900 m) sags between them. Throws ReconstructionError when the system is singular or its
/// coefficients overflow.
RbfFit fit_rbf(std::span<const Vec2> points, std::span<const double> r_sq, std::span<const double> values,
               int channels, const RbfKernel& kernel, std::vector<unsigned> subset, bool centre_values = false);

/// A fit kept with the LU factorisation of its system, from which fits through subsets that
/// differ from its own by a few samples are derived (fit_rbf_near()). The fit's values are
/// centred by its subset's mean where it has a polynomial, else not (fit_rbf()'s default).
struct RbfRootFit {
  RbfFit fit;
  Eigen::MatrixXd system;  ///< its system's matrix, [phi P; P^T 0] (to check derived fits)
  Eigen::PartialPivLU<Eigen::MatrixXd> lu;
};
RbfRootFit fit_rbf_root(std::span<const Vec2> points, std::span<const double> r_sq, std::span<const double> values,
                        int channels, const RbfKernel& kernel, std::vector<unsigned> subset);

/// The fit through `subset` (sorted, as the root's) from the root's factorisation: the system
/// on the root's samples and the subset's added ones by blocks (a Schur complement of the added
/// samples' size), with the root's samples that the subset drops released from their equations
/// and held at 0 (a system of their number). Costs solves with the root's LU for each sample
/// added or dropped, instead of a factorisation. The same interpolant as fit_rbf() through the
/// subset, in the root's frame (polynomial axes, the kernel's scale s: the interpolant
/// does not depend on them), centred by the subset's own mean; the values of the dropped
/// samples never enter; each channel solved as a vector of its own, as if alone. Checked:
/// nullopt unless the backward error of the same update on the subset's own system, for a fixed
/// pseudo-random right-hand side (so that the outcome depends on neither the values nor their
/// channels), is within tol::kRbfNearFitBackwardError (then fit_rbf() it), or when the subset's
/// polynomial has fewer terms than the root's (a subset on one line).
std::optional<RbfFit> fit_rbf_near(const RbfRootFit& root, std::span<const Vec2> points, std::span<const double> r_sq,
                                   std::span<const double> values, int channels, const RbfKernel& kernel,
                                   std::vector<unsigned> subset);

/// The fit's value at p into out[0, channels): the basis over its samples as Eigen arrays (SIMD,
/// sums in a fixed packet order, so results do not depend on threads), plus the polynomial.
/// `b` is scratch.
void evaluate_rbf_fit(const RbfFit& fit, const RbfKernel& kernel, int channels, const Vec2& p, Eigen::ArrayXd& b,
                      double* out);
/// The basis part alone (no polynomial) at p, times `weight`, added to out[0, channels): what
/// evaluate_rbf_fit() sums, and the local methods blend.
void add_rbf_sum(const RbfFit& fit, const RbfKernel& kernel, int channels, const Vec2& p, double weight,
                 Eigen::ArrayXd& b, double* out);

/// Fits over subsets of the samples, each solved once and shared (subset_cache.h).
using RbfFitCache = SubsetCache<RbfFit>;

}  // namespace radrecon
