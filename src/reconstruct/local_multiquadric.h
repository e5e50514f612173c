#pragma once
// A partition of unity of local multiquadrics, for large sample sets where the global system
// (n x n) cannot be solved. Patches are discs of radius h centred on a square grid of spacing h
// over the samples' bounding box. Each patch interpolates every sample within 1.5 h of its
// centre (at least kMinPatchSamples, topped up with the nearest others), so it never
// extrapolates inside its disc, by a multiquadric with the global radii r_j; h is chosen so
// that about k samples lie within 1.5 h on average. The patches are blended with Wendland's C2
// weights (1 - d/h)^4 (4 d/h + 1), positive everywhere in the box (the discs cover it). Exact at
// the samples; outside the box, the value at the nearest point of the box.
//
// With barriers (barriers.h): each patch contributes the multiquadric through those of its
// samples the query sees (solved once per patch and subset, multiquadric_basis.h), and a patch
// that sees none of them no weight; a query no patch serves gets NaN.

#include <memory>
#include <optional>
#include <vector>

#include "reconstruct/barriers.h"
#include "reconstruct/interpolant.h"
#include "reconstruct/multiquadric_basis.h"
#include "reconstruct/samples.h"

namespace radrecon {

class KdTree2;

class LocalMultiquadric final : public Interpolant {
 public:
  /// mu != 0; k >= kMinPatchSamples; r > 0 if given, else Eck's rule. Needs 2 distinct samples.
  LocalMultiquadric(const ScatteredSamples& samples, double mu, std::optional<double> r_m, int k,
                    Barriers barriers = {});
  ~LocalMultiquadric() override;
  int channels() const override { return channels_; }
  void evaluate(std::span<const Vec2> points, std::span<double> out) const override;

  static constexpr int kMinPatchSamples = 3;
  /// A patch holding more samples than this (clustered data) is refused: its dense solve would
  /// take too long.
  static constexpr size_t kMaxPatchSamples = 2000;
  /// Patch radius = spacing of the patch grid, metres.
  double patch_radius() const { return h_; }
  /// The smallest reciprocal condition estimate of the patches' systems (LU's rcond()).
  double reciprocal_condition() const;

 private:
  struct Patch {
    Vec2 center;
    std::vector<unsigned> samples;
    std::vector<double> alpha;  ///< samples.size() * channels
    double rcond = 1;           ///< reciprocal condition estimate of its system
    double reach_m = 0;         ///< a bound on the distance from its support to its samples
  };
  /// Refuses oversized or singular patches, warns of poorly conditioned ones.
  void check_patches() const;
  std::vector<Vec2> points_;
  std::vector<double> r_sq_;
  int channels_;
  double mu_;
  double h_ = 1;
  Vec2 origin_, box_max_;  ///< the samples' bounding box
  int nx_ = 1, ny_ = 1;
  std::vector<Patch> patches_;  ///< row by row over the grid
  Barriers barriers_;
  std::vector<double> values_;  ///< with barriers: the samples' values, for the subsets' fits
  MultiquadricFitCache fits_;   ///< keyed by patch index
};

}  // namespace radrecon
