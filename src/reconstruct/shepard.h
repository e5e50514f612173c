#pragma once
// Shepard's inverse distance weighting (the paper's sec. 2.2.1):
//   B(q) = sum_i d(q, p_i)^-mu B_i / sum_i d(q, p_i)^-mu,
// over all samples (global) or over the k nearest (local, from a k-d tree). Exact at the
// samples; the weights are positive and sum to one, so B stays within the samples' range.

#include <limits>
#include <memory>

#include "reconstruct/barriers.h"
#include "reconstruct/interpolant.h"
#include "reconstruct/samples.h"

namespace radrecon {

class KdTree2;
class CoherentNearest;

class Shepard final : public Interpolant {
 public:
  /// mu > 0; k = 0 uses every sample, k > 0 the k nearest (at most all).
  Shepard(ScatteredSamples samples, double mu, int k);
  /// With barriers (barriers.h): only the samples visible from a query contribute (with k > 0,
  /// the k nearest visible ones among the nearest max(kMaxVisibleCandidates, 2k)); a query that
  /// sees none gets NaN (no value).
  Shepard(ScatteredSamples samples, double mu, int k, Barriers barriers);
  /// With a search radius, as gdal_grid's invdist(nn) radius and min_points: only the samples
  /// (of those above) within `radius_m` of a query contribute, and a query with fewer than
  /// `min_points` (>= 1) of them gets NaN (no value). radius_m = infinity: no radius.
  Shepard(ScatteredSamples samples, double mu, int k, Barriers barriers, double radius_m, int min_points);
  ~Shepard() override;
  int channels() const override { return samples_.channels; }
  void evaluate(std::span<const Vec2> points, std::span<double> out) const override;

 private:
  ScatteredSamples samples_;
  std::vector<double> px_, py_;          ///< sample coordinates, structure of arrays for the inner loop
  std::vector<double> values_by_channel_;  ///< channels * samples, channel by channel
  double mu_;
  int k_;
  double radius_sq_ = std::numeric_limits<double>::infinity();  ///< m^2
  size_t min_points_ = 1;
  std::unique_ptr<KdTree2> tree_;
  std::unique_ptr<CoherentNearest> nearest_;  ///< k > 0: the k nearest of coherent queries, over tree_
  Barriers barriers_;
  std::unique_ptr<PointVisibility> visibility_;  ///< with barriers: over samples_.points
  /// Per-thread buffers of evaluate().
  struct Scratch;
  /// Whether global_value_one_pass() applies but for the radius: a SIMD build, mu 2 or 4, at most
  /// three channels, and every value 0 or of a magnitude in [kLeastValue, kMostValue] (shepard.cpp).
  bool one_pass_ = false;
  /// The global weighted mean at p (finite) in one pass over the samples, in SIMD packets, with
  /// weights d^-mu themselves; `hidden` (with barriers, else null): a flag per sample, nonzero
  /// where p does not see it (it weighs 0; NaN where p sees none). False (nothing written) where
  /// the weights could overflow or underflow, i.e. where p is within sqrt(kLeastDistSq) of a
  /// visible sample or beyond sqrt(kMostDistSq) of one; always false in a build without SIMD.
  bool global_value_one_pass(const Vec2& p, const char* hidden, double* o) const;
  /// The local path's value at p (o: a value per channel) from its k nearest samples, in any
  /// order, `nearest` the position of the nearest among them.
  void local_value(const Vec2& p, std::span<const unsigned> nearest_idx, std::span<const double> nearest_d2,
                   size_t nearest, Scratch& s, double* o) const;
};

}  // namespace radrecon
