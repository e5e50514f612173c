#pragma once
// Natural bicubic spline interpolation of nodal values on a regular grid (the paper's sec.
// 2.1.2, after Numerical Recipes' splie2/splin2): cubic splines with zero second derivative at
// the ends, first along x through every row, then along y. Evaluated as the equivalent tensor
// product: per cell, values and the second derivatives f_xx, f_yy, f_xxyy at its four corners.
// Outside the grid the point is clamped onto it.

#include "reconstruct/interpolant.h"
#include "reconstruct/samples.h"

namespace radrecon {

class Bicubic final : public Interpolant {
 public:
  /// Needs at least 2 x 2 nodes (with 2 nodes along an axis the spline is linear along it).
  explicit Bicubic(GridNodes nodes);
  int channels() const override { return nodes_.channels; }
  void evaluate(std::span<const Vec2> points, std::span<double> out) const override;

 private:
  GridNodes nodes_;
  std::vector<double> fxx_, fyy_, fxxyy_;  ///< same layout as nodes_.values
};

/// Second derivatives M of the natural cubic spline through y[0..n) at equally spaced abscissae
/// h apart: M[0] = M[n-1] = 0 and M[i-1] + 4 M[i] + M[i+1] = 6 (y[i-1] - 2 y[i] + y[i+1]) / h^2.
/// `stride` steps through y and m (to run along rows or columns of a grid).
void natural_spline_second_derivatives(const double* y, double* m, int n, double h, size_t stride);

}  // namespace radrecon
