#pragma once
// Bilinear interpolation of nodal values on a regular grid (the paper's sec. 2.1.1):
//   B(x, y) = (1-u)(1-v) B00 + u(1-v) B10 + u v B11 + (1-u) v B01
// with (u, v) the point's position inside its grid cell. Outside the grid the point is clamped
// onto it (constant extension of the border values).

#include "reconstruct/interpolant.h"
#include "reconstruct/samples.h"

namespace radrecon {

class Bilinear final : public Interpolant {
 public:
  /// Needs at least 2 x 2 nodes.
  explicit Bilinear(GridNodes nodes);
  int channels() const override { return nodes_.channels; }
  void evaluate(std::span<const Vec2> points, std::span<double> out) const override;

 private:
  GridNodes nodes_;
};

}  // namespace radrecon
