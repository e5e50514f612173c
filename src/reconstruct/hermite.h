#pragma once
// Bicubic Hermite interpolation of nodal values on a regular grid, with the derivatives estimated
// from the samples (the approach [BdSF93] takes, as cited by the paper's sec. 2.1):
//   f_x, f_y: central differences (f[i+1] - f[i-1]) / 2h inside the grid, second-order one-sided
//             differences (-3 f[0] + 4 f[1] - f[2]) / 2h (and mirrored) on its border; with only
//             2 nodes along an axis, the first-order difference (f[1] - f[0]) / h at both.
//   f_xy:     the same differences along y applied to the estimated f_x.
// Per cell, the bicubic patch that matches f, f_x, f_y and f_xy at its four corners (the tensor
// product of the cubic Hermite basis h00 = 2t^3 - 3t^2 + 1, h01 = 3t^2 - 2t^3,
// h10 = t^3 - 2t^2 + t, h11 = t^3 - t^2): patches share values and first derivatives along their
// common edges, so the interpolant is C1 across cells, and exact at the nodes.
//
// Polynomials: the differences above are exact for quadratics (in each variable), and a bicubic
// Hermite patch reproduces every polynomial of degree <= 3 in each variable given exact
// derivatives, so every quadratic a + bx + cy + dx^2 + exy + fy^2 is reproduced exactly on a grid
// of at least 3 x 3 nodes; with 2 nodes along x, those linear in x (a + bx + cy + exy + fy^2).
// The same interpolant as the tensor product of Keys' cubic convolution (keys_cubic.h: a = -1/2,
// the Catmull-Rom spline, whose slopes are these central differences; Keys' end rule
// f(-1) = 3 f(0) - 3 f(1) + f(2) gives the one-sided slope above, and with 2 nodes the linear
// extrapolation gives f(1) - f(0)): hermite_test.cpp checks the two against each other. Unlike
// bicubic's natural spline it is local: a value depends on the 4 x 4 nodes around its cell.
//
// Outside the grid the point is clamped onto it (constant extension of the border values, as
// bilinear and bicubic do). A non-finite query gives NaN.

#include "reconstruct/interpolant.h"
#include "reconstruct/samples.h"

namespace radrecon {

class Hermite final : public Interpolant {
 public:
  /// Needs at least 2 x 2 nodes, a positive finite spacing and finite values
  /// (ReconstructionError otherwise).
  explicit Hermite(GridNodes nodes);
  int channels() const override { return nodes_.channels; }
  void evaluate(std::span<const Vec2> points, std::span<double> out) const override;

  /// The estimated derivatives at node (i, j), channel c (for tests and tools): f_x, f_y, f_xy.
  double fx(int i, int j, int c) const { return fx_[index(i, j, c)]; }
  double fy(int i, int j, int c) const { return fy_[index(i, j, c)]; }
  double fxy(int i, int j, int c) const { return fxy_[index(i, j, c)]; }

 private:
  size_t index(int i, int j, int c) const {
    return (static_cast<size_t>(j) * nodes_.nx + i) * nodes_.channels + c;
  }
  GridNodes nodes_;
  std::vector<double> fx_, fy_, fxy_;  ///< same layout as nodes_.values, per metre
};

/// The derivative estimates of Hermite along one line of n >= 2 samples h apart: d[k] from
/// y[0..n) (both stepped by `stride`), central inside, second-order one-sided at the ends
/// (first-order when n = 2). Exact for quadratics when n >= 3.
void estimate_derivatives(const double* y, double* d, int n, double h, size_t stride);

}  // namespace radrecon
