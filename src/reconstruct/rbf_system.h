#pragma once
// The pieces of an RBF fit's interpolation system (reconstruct/multiquadric_basis.h), shared by
// the direct fit and the fits derived from a nearby root's factorisation. Internal to
// reconstruct/multiquadric_basis.cpp and reconstruct/rbf_near_fit.cpp.

#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "reconstruct/multiquadric_basis.h"

namespace radrecon::rbf_system {

/// The polynomial's frame for `subset`: centroid, principal axes scaled by the spreads along
/// them, and how many terms the subset determines (header: tol::kRbfFlatSubsetRelative).
void polynomial_frame(std::span<const Vec2> points, const std::vector<unsigned>& subset, RbfFit& fit);

/// The interpolation system of `fit` (its frame and kernel scale set) through its subset, centred
/// by `mean` (per channel): A = [phi P; P^T 0] and the right-hand sides B = [f - mean; 0].
void fill_system(std::span<const double> r_sq, std::span<const double> values, int channels,
                 const RbfKernel& kernel, const RbfFit& fit, const std::vector<double>& mean, Eigen::MatrixXd& A,
                 Eigen::MatrixXd& B);

/// The subset's frame (polynomial and kernel scale, from its extent and, for the multiquadric,
/// its largest r_j^2 in `r_sq`, m^2 per point) and coordinates into a new fit.
RbfFit frame_fit(std::span<const Vec2> points, std::span<const double> r_sq, const RbfKernel& kernel,
                 std::vector<unsigned> subset);

/// The values' mean per channel over the subset, taken out of the system into c_0 (with a
/// polynomial) or into the offset; zeros otherwise.
std::vector<double> subset_mean(std::span<const double> values, int channels, const std::vector<unsigned>& subset,
                                bool centre);

/// The coefficients x (alpha of the subset's samples, then the polynomial's) into the fit.
void set_coefficients(std::span<const double> r_sq, int channels, const RbfKernel& kernel, bool centre_values,
                      const std::vector<double>& mean, const Eigen::MatrixXd& x, RbfFit& fit);

/// Refuses a factorisation whose reciprocal condition number is 0 or not finite.
void check_factorisation(double rcond, const RbfKernel& kernel);

/// Warns (warn(), core/error.h) "SYSTEM is poorly conditioned (reciprocal condition R)SUFFIX"
/// when rcond is below tol::kPoorConditioning.
void warn_if_poorly_conditioned(double rcond, const std::string& system, const std::string& suffix = "");

}  // namespace radrecon::rbf_system
