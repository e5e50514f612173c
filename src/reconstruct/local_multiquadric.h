#pragma once
// A partition of unity of local RBF interpolants (multiquadric_basis.h: the multiquadric, with or
// without a linear polynomial, or the thin-plate spline), for large sample sets where the global
// system (n x n) cannot be solved. Patches are discs of radius h centred on a square grid of
// spacing h over the samples' bounding box. Each patch interpolates every sample within 1.5 h of
// its centre (at least kMinPatchSamples, with barriers at least k, topped up with the nearest
// others; with a polynomial and no barriers, samples on one line, such as a survey track, take
// the nearest sample off it too) by an RBF with the global radii r_j and its own polynomial; h is chosen so that about
// k samples lie within 1.5 h on average. Without a polynomial a patch fits the deviations from its samples' mean and adds
// the mean back, so that constants are reproduced (a multiquadric through 16 samples of terrain
// at 900 m otherwise sags between them by tens of metres). The patches are blended with
// Wendland's C2 weights (1 - d/h)^4 (4 d/h + 1), positive everywhere in the box (the discs cover
// it). Exact at the samples. With a polynomial each patch reproduces linear functions, and so
// does their blend (the weights sum to one); a patch whose samples (or, with barriers, those the
// query sees) span no plane, so that its polynomial lacks a term (multiquadric_basis.h), gives
// way: it has weight only where no patch with a full polynomial has any.
//
// No patch extrapolates: at a query p outside the convex hull of its samples (at the edges and
// corners of the data, or where a patch's few samples leave part of its disc uncovered) it takes
// its RBF's value at the hull's nearest point e to p, plus its polynomial's change from e to p
// (so linear functions are still reproduced everywhere; without a polynomial, its offset's
// change: none). An RBF extrapolated from a few samples overshoots without bound: on a real
// elevation model the largest error at the edges was 3.5 times natural neighbour's
// (bench/dem_edges.sh). Outside the samples' box the weights are those of the nearest point of
// the box.
//
// With barriers (barriers.h): each patch contributes the RBF through those of its samples the
// query sees (solved once per patch and subset, multiquadric_basis.h), and a patch that sees
// none of them no weight; a query no patch serves gets NaN.

#include <memory>
#include <optional>
#include <vector>

#include "reconstruct/barriers.h"
#include "reconstruct/interpolant.h"
#include "reconstruct/multiquadric_basis.h"
#include "reconstruct/samples.h"

namespace radrecon {

class KdTree2;

/// The local RBF interpolant of any RbfKernel (named after the paper's method).
class LocalMultiquadric final : public Interpolant {
 public:
  /// k >= kMinPatchSamples. The multiquadric: kernel.mu != 0; r > 0 if given, else Eck's rule.
  /// The thin-plate spline: no r. Needs 2 distinct samples.
  LocalMultiquadric(const ScatteredSamples& samples, const RbfKernel& kernel, std::optional<double> r_m, int k,
                    Barriers barriers = {});
  /// Hardy's multiquadric without a polynomial, as in the paper.
  LocalMultiquadric(const ScatteredSamples& samples, double mu, std::optional<double> r_m, int k,
                    Barriers barriers = {})
      : LocalMultiquadric(samples, RbfKernel::multiquadric(mu), r_m, k, std::move(barriers)) {}
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
    RbfFit fit;           ///< through its samples, with their hull (no extrapolation past it)
    double inside_sq = 0; ///< squared radius about the centre that lies in the hull
    double reach_m = 0;   ///< a bound on the distance from its support to its samples
  };
  /// Refuses oversized or singular patches, warns of poorly conditioned ones.
  void check_patches() const;
  std::vector<Vec2> points_;
  std::vector<double> r_sq_;
  int channels_;
  RbfKernel kernel_;
  double h_ = 1;
  double candidate_slack_ = 0;  ///< kCandidateSlack plus the patch centres' rounding, in units of h
  Vec2 origin_, box_max_;  ///< the samples' bounding box
  int nx_ = 1, ny_ = 1;
  std::vector<Patch> patches_;  ///< row by row over the grid
  Barriers barriers_;
  std::vector<double> values_;  ///< with barriers: the samples' values, for the subsets' fits
  RbfFitCache fits_;           ///< keyed by patch index
};

}  // namespace radrecon
