#pragma once
// Piecewise linear interpolation on the Delaunay triangulation of the samples (scipy's
// griddata(method="linear")): B(q) = b0 B_0 + b1 B_1 + b2 B_2 with (b0, b1, b2) the barycentric
// coordinates of q in the Delaunay triangle holding it. Exact at the samples, continuous (C0),
// reproduces linear functions inside the convex hull. Outside the hull: OutsideHull::nearest
// (the value at the nearest hull point, linear along the hull edge) or OutsideHull::none (NaN).
// Where the Delaunay triangulation is not unique (four or more co-circular samples, e.g. a
// lattice), the diagonal is CGAL's choice for the samples in their given order (delaunay.h).

#include "reconstruct/delaunay.h"
#include "reconstruct/interpolant.h"
#include "reconstruct/methods.h"
#include "reconstruct/samples.h"

namespace radrecon {

class DelaunayLinear final : public Interpolant {
 public:
  /// Needs 3 samples not all on one line; duplicate points are refused (ReconstructionError).
  DelaunayLinear(const ScatteredSamples& samples, OutsideHull outside);
  int channels() const override { return channels_; }
  void evaluate(std::span<const Vec2> points, std::span<double> out) const override;

 private:
  DelaunayMesh mesh_;
  std::vector<double> values_;  ///< point-major, channels_ per sample
  int channels_;
  OutsideHull outside_;
};

}  // namespace radrecon
