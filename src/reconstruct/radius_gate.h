#pragma once
// gdal_grid's radius and min_points for a method that has no search radius of its own (the
// multiquadric, the thin-plate spline): the method's value where at least `min_points` samples lie
// within `radius_m` of the query, no value (NaN) elsewhere. The method itself is not cut at the
// radius (its patches, or its global system, use the samples they use). Shepard's radius is its
// own (shepard.h): there only the samples within it count.

#include <memory>

#include "reconstruct/interpolant.h"
#include "reconstruct/samples.h"

namespace radrecon {

class KdTree2;

class RadiusGate final : public Interpolant {
 public:
  /// radius_m > 0, min_points >= 1.
  RadiusGate(std::unique_ptr<Interpolant> inner, const ScatteredSamples& samples, double radius_m, int min_points);
  ~RadiusGate() override;
  int channels() const override { return inner_->channels(); }
  void evaluate(std::span<const Vec2> points, std::span<double> out) const override;

 private:
  std::unique_ptr<Interpolant> inner_;
  std::unique_ptr<KdTree2> tree_;
  double radius_sq_;
  int min_points_;
};

}  // namespace radrecon
