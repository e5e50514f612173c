#pragma once
// Sibson's natural-neighbour interpolation (the paper's sec. 2.2.3): B(q) = sum_i lambda_i(q) B_i
// with lambda_i the share of q's Voronoi cell stolen from p_i's. The coordinates come from a
// robust Delaunay triangulation (CGAL). Exact at the samples, C0, reproduces linear functions
// inside the convex hull. Outside the hull: OutsideHull::nearest (the value at the nearest hull
// point, interpolated linearly along the hull edge) or OutsideHull::none (NaN).

#include <memory>
#include <vector>

#include "reconstruct/interpolant.h"
#include "reconstruct/methods.h"
#include "reconstruct/samples.h"

namespace radrecon {

class NaturalNeighbour final : public Interpolant {
 public:
  /// Needs 3 samples not all on one line; duplicate points are refused.
  NaturalNeighbour(const ScatteredSamples& samples, OutsideHull outside);
  ~NaturalNeighbour() override;
  int channels() const override;
  void evaluate(std::span<const Vec2> points, std::span<double> out) const override;

  /// Sibson coordinates of q: pairs (sample index, lambda), lambda summing to one; empty outside
  /// the convex hull.
  std::vector<std::pair<unsigned, double>> coordinates(const Vec2& q) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace radrecon
