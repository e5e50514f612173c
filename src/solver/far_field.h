#pragma once
// A far block of a shooting patch (solver/shooter_tree.h) as one source: the radiosity it shoots
// with to a receiving point, exact to second order in its size over the distance, and the error
// of doing so.

#include <array>
#include <optional>
#include <span>

#include "solver/shooter_tree.h"

namespace radrecon {

/// The kernel's second-order term at a receiving point over a block, M = H + g g^T (H the
/// Hessian of ln k over the source point at the block's centroid, g its gradient), 1/m^2:
/// symmetric, its upper triangle row by row (00 01 02 11 12 22).
using KernelSecondOrder = std::array<double, 6>;

/// The radiosity a far block shoots with to the receiver point p (unit normal n), second order:
/// with k(y) = k(c) exp(g . t + t^T H t / 2 + ...) the point-to-point kernel (k = cos_y cos_x /
/// (pi r^2)) for y = c + t, g and H the gradient and Hessian of ln k over the source point at
/// the centroid c, M = H + g g^T, the block's form factor is F = k(c) A (1 + tr(M S) / 2) and
/// the sum over its elements sum_k F_k B_k = k(c) A (B_mean (1 + tr(M S) / 2) + g . dipole +
/// tr(M Q) / 2) (S: area_moment, Q: quadrupole), so the block shoots with
/// B_mean + (g . dipole + tr(M Q) / 2) / (1 + tr(M S) / 2), with an error of third order in
/// radius / distance whatever the radiosity over the block (first order only, B_mean +
/// g . dipole, where |tr(M S)| / 2 exceeds tol::kFarFieldCurvatureLimit). The mean alone errs to first order
/// wherever the radiosity varies (a wall lit at its top and dark at its foot), and that error
/// does not cancel over the receivers: it gains or loses power. Clamped to the block's range of
/// unshot radiosity.
Rgb far_field_radiosity(const Block& b, const Vec3& p, const Vec3& n, const Vec3& shooter_normal);
/// The same with the kernel's log-gradient at p already known: kernel_log_gradient()'s g, or
/// nullptr where it returned false (grazing: the block's mean).
/// `second_order`, if given, is the kernel's second-order term there as far_field_error() found it.
Rgb far_field_radiosity(const Block& b, const Vec3& p, const Vec3& n, const Vec3& shooter_normal, const Vec3* gradient,
                        const KernelSecondOrder* second_order = nullptr);

/// far_field_radiosity(b, p, n, shooter_normal) at each of `points` (an element's Gauss points)
/// into `out` (as many), the same values bit for bit, the points in SIMD packets.
void far_field_radiosities(const Block& b, std::span<const Vec3> points, const Vec3& n, const Vec3& shooter_normal,
                           std::span<Rgb> out);

/// The gradient g over the source point y, at the block's centroid, of ln k(p, y) (see
/// far_field_radiosity()), 1/m; false at grazing angles (tol::kKernelCosine), where the far
/// field is the block's mean alone.
bool kernel_log_gradient(const Block& b, const Vec3& p, const Vec3& n, const Vec3& shooter_normal, Vec3& g);

/// The far field's error at p (unit normal n) per unit spread of the block's radiosity,
/// relative to its form factor, given g = kernel_log_gradient(): half the largest remainder of
/// the kernel's expansion over the block (relative to the kernel at its centroid), read off the
/// kernel at a box's corners and edge midpoints (other blocks: each edge's quarters) and scaled
/// by tol::kFarFieldRemainderSamplingBox (Other) for the points between them. Infinite where the
/// kernel is not positive at all of them (the block is cut by the receiver's plane), or where
/// its logarithm varies too much over the block for that (tol::kFarFieldCurvatureLimit). A block's
/// far field errs by about its spread times its form factor times this, or less.
/// `second_order`, if given, gets the kernel's second-order term where the estimate computed it
/// (for far_field_radiosity() at the same point, which then need not compute it again).
double far_field_error(const Block& b, const Vec3& p, const Vec3& n, const Vec3& shooter_normal, const Vec3& g,
                       std::optional<KernelSecondOrder>* second_order = nullptr);

}  // namespace radrecon
