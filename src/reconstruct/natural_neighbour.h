#pragma once
// Sibson's natural-neighbour interpolation (the paper's sec. 2.2.3): B(q) = sum_i lambda_i(q) B_i
// with lambda_i the share of q's Voronoi cell stolen from p_i's. The coordinates come from a
// robust Delaunay triangulation (CGAL). Exact at the samples, C0, reproduces linear functions
// inside the convex hull. Outside the hull: OutsideHull::nearest (the value at the nearest hull
// point, interpolated linearly along the hull edge) or OutsideHull::none (NaN).
//
// With barriers (barriers.h): Sibson's coordinates of q over the samples VISIBLE from q, exactly
// (not an approximation):
//   - Where every natural neighbour of q among all samples is visible, those coordinates are
//     already the ones over the visible samples (q's Voronoi cell, and the part of it each
//     neighbour loses, depend on the natural neighbours alone), so they are used as they are.
//   - Otherwise, with few samples and segments (kMaxWholeVisibleSamples,
//     kMaxWholeVisiblePairs), the coordinates of q in the
//     Delaunay triangulation of every sample it sees: neighbouring queries mostly see the same
//     set, whose triangulation is built once and shared (kMaxCachedTriangulationSamples).
//   - Otherwise the Delaunay triangulation of q's k nearest visible samples is built, and its
//     coordinates are taken when they are certified: no farther visible sample can cut q's cell
//     nor be nearer than its sample to any point of it (the next visible sample farther than
//     rho + max(rho, r), rho the farthest vertex of q's cell, r the largest circumradius of the
//     triangles q's insertion destroys); else k doubles.
//   - A query outside the hull of the samples it sees: the outside rule over those samples (the
//     nearest point of their hull, or NaN). A query that sees no sample: NaN.
//   - Limits, for queries walled into pockets or far from what they see: the samples tried are
//     the nearest kMaxVisibleCandidates (barriers.h), the triangulation holds at most kMaxVisibleNeighbours;
//     past them the coordinates (or the hull) are those of the visible samples found. With the
//     factory's barrier samples (methods.h) queries next to a barrier have natural neighbours
//     right there, and no query of a sampled region comes near these limits.
// So the interpolant is exact at the samples, continuous away from barriers and from the sight
// lines that graze a barrier's free end (where a sample comes into view), jumps across barriers,
// and reproduces linear functions wherever q is inside the hull of what it sees.

//
// The same machinery serves two more interpolants (NeighbourRule), with the same hull and
// barrier rules:
//   - laplace: Laplace's non-Sibsonian coordinates (Belikov & Semenov 1997, Sugihara 1999):
//     lambda_i proportional to |e_i| / |q - p_i|, e_i the edge of q's Voronoi cell facing p_i.
//     Exact at the samples, C0, reproduces linear functions inside the hull; cheaper than
//     Sibson's (lengths, not areas) and not C1 at the samples' circles either.
//   - sibson-c1: Farin's C1 form over Sibson's coordinates (sibson_c1.h), with gradients fitted
//     at the samples from their natural neighbours. Exact at the samples, C1 away from them,
//     reproduces quadratics given exact gradients.

#include <functional>
#include <memory>
#include <vector>

#include "reconstruct/barriers.h"
#include "reconstruct/interpolant.h"
#include "reconstruct/methods.h"
#include "reconstruct/samples.h"

namespace radrecon {

/// Which natural-neighbour interpolant: Sibson's coordinates times the values
/// (natural-neighbour), Laplace's (laplace), or Farin's C1 form over Sibson's (sibson-c1).
enum class NeighbourRule { sibson, laplace, sibson_c1 };

class NaturalNeighbour final : public Interpolant {
 public:
  /// Needs 3 samples not all on one line; duplicate points are refused.
  NaturalNeighbour(const ScatteredSamples& samples, OutsideHull outside, Barriers barriers = {},
                   NeighbourRule rule = NeighbourRule::sibson);
  ~NaturalNeighbour() override;
  int channels() const override;
  void evaluate(std::span<const Vec2> points, std::span<double> out) const override;
  /// Sibson's rule without barriers: face by face over the raster's rows (sibson_raster.h), the
  /// points it leaves (by the hull, next to a sample) query by query; else as Interpolant's.
  void evaluate_raster(const Raster& raster, size_t first, size_t count, std::span<double> out) const override;

  /// Visible samples a query's local triangulation may hold (with barriers).
  static constexpr size_t kMaxVisibleNeighbours = 512;
  /// With barriers, up to this many samples, and at most kMaxWholeVisiblePairs samples times
  /// barrier segments: a query's coordinates in the triangulation of every sample it sees, built
  /// once per set of visible samples and shared (see the header). The sets change where a query
  /// crosses a line through a sample and a segment's end, so their number grows with that
  /// product; past it the k-nearest path, whose cost does not, is taken.
  static constexpr size_t kMaxWholeVisibleSamples = 1024;
  static constexpr size_t kMaxWholeVisiblePairs = size_t{1} << 14;
  /// The most samples the shared triangulations of the visible sets hold in all (some 200 bytes
  /// each); past it they are built per thread and not kept.
  static constexpr size_t kMaxCachedTriangulationSamples = size_t{1} << 18;

  /// The coordinates of q (Sibson's, or Laplace's for NeighbourRule::laplace): pairs (sample
  /// index, lambda), lambda summing to one; empty outside the convex hull (of the samples visible
  /// from q, with barriers).
  std::vector<std::pair<unsigned, double>> coordinates(const Vec2& q) const;
  /// coordinates() of every query point at once, as evaluate() finds them (coherent queries
  /// share their walks and conflict zones): visit(i, coordinates of points[i]), called from
  /// several threads at once for distinct i. A query on a Delaunay edge may have other last bits
  /// than coordinates() gives it alone; they do not depend on the number of threads.
  void visit_coordinates(std::span<const Vec2> points,
                         const std::function<void(size_t, std::span<const std::pair<unsigned, double>>)>& visit) const;

  /// The edges of the samples' convex hull as pairs of sample indices (consecutive samples along
  /// the hull, collinear ones included: the finite edges of the Delaunay triangulation's
  /// infinite faces), without regard to barriers.
  const std::vector<std::pair<unsigned, unsigned>>& hull_edges() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace radrecon
