#pragma once
// Piecewise-constant reconstruction: the value of the cell that contains the point (the radiosity
// solution as computed, without interpolation).

#include <memory>

#include "reconstruct/interpolant.h"
#include "reconstruct/samples.h"

namespace radrecon {

/// Cells must not overlap and must have a positive extent (ReconstructionError otherwise). A point on a shared edge takes the cell with the larger lower bound
/// (cells are half-open [x0, x1) x [y0, y1), closed on the far border of the domain). A point
/// outside the cells' bounding box is first clamped into it; a point in a gap between cells gets
/// NaN.
class PiecewiseConstant final : public Interpolant {
 public:
  explicit PiecewiseConstant(CellSamples samples);
  int channels() const override { return samples_.channels; }
  void evaluate(std::span<const Vec2> points, std::span<double> out) const override;

  /// Index of the cell containing `p` (after clamping), or -1.
  long locate(const Vec2& p) const;
  long locate_triangle(const Vec2& p, const std::vector<unsigned>& bucket) const;

 private:
  CellSamples samples_;
  Rect bounds_;
  int buckets_x_ = 1, buckets_y_ = 1;
  std::vector<std::vector<unsigned>> buckets_;  ///< cells overlapping each bucket
};

}  // namespace radrecon
