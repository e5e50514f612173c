#pragma once
// Piecewise-constant reconstruction of scattered samples: the value of the nearest sample (its
// Voronoi cell). Ties (equidistant samples) go to the k-d tree's first found: the same for any
// threads, but not by the samples' order (docs/interpolate.md).

#include <memory>

#include "reconstruct/barriers.h"
#include "reconstruct/interpolant.h"
#include "reconstruct/samples.h"

namespace radrecon {

class KdTree2;

class NearestSample final : public Interpolant {
 public:
  explicit NearestSample(ScatteredSamples samples);
  /// With barriers (barriers.h): the nearest sample visible from the query (ties as above); a
  /// query that sees none of its kMaxVisibleCandidates nearest gets NaN (no value).
  NearestSample(ScatteredSamples samples, Barriers barriers);
  ~NearestSample() override;
  int channels() const override { return samples_.channels; }
  void evaluate(std::span<const Vec2> points, std::span<double> out) const override;

 private:
  ScatteredSamples samples_;
  std::unique_ptr<KdTree2> tree_;
  Barriers barriers_;
};

}  // namespace radrecon
