#pragma once
// Barriers: lines in the sample domain that no sample's influence crosses (discontinuities of
// the function: the foot of a wall on the ground, a fault, a breakline). A sample is visible from
// a query when the straight segment between them crosses no barrier.
//
// The rule, exact (orientation tests with exact predicates):
//   - the open segment (p, q) is blocked when it meets a closed barrier segment [a, b]: a proper
//     crossing, a barrier end point lying on it, or a collinear overlap;
//   - p and q themselves never block: a sample or query lying on a barrier sees both sides;
//   - light passes around a barrier's free end (a segment that misses the end point by any
//     amount is not blocked).

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "core/result.h"
#include "core/vec.h"

namespace radrecon {

/// One barrier segment, metres.
struct BarrierSegment {
  Vec2 a, b;
};

class Barriers {
 public:
  /// No barrier: every sample sees every query.
  Barriers() = default;

  /// The segments of `polylines`, or a Failure naming the polyline and point when a coordinate
  /// is not finite, a polyline has fewer than 2 points, or a segment has zero length.
  static Result<Barriers> from_polylines(std::span<const Polyline> polylines);

  bool empty() const { return segments_.empty(); }
  const std::vector<BarrierSegment>& segments() const { return segments_; }

  /// Whether the open segment (p, q) meets a barrier (the rule above). Thread-safe, allocation
  /// free: the segments are bucketed on a uniform grid, and only the segments of the cells the
  /// segment passes through are tested.
  bool blocks(const Vec2& p, const Vec2& q) const;

  /// Whether no barrier comes within reach_m of q (with a margin above the distance's round-off,
  /// relative and absolute): then no segment from q to a point within reach_m is blocked, and
  /// the visibility tests of a query whose samples all lie that near can be skipped.
  bool none_within(const Vec2& q, double reach_m) const;

  /// The distance from q to the nearest barrier segment (closed) when it is below max_distance,
  /// else max_distance (also with no barrier, and for a q not finite). Only the segments bucketed in the grid cells that
  /// the box of half-side max_distance around q overlaps are measured, so a small max_distance
  /// keeps it cheap; an infinite one measures every segment. Thread-safe, allocation free.
  double distance_to(const Vec2& q, double max_distance) const;

 private:
  explicit Barriers(std::vector<BarrierSegment> segments);

  std::vector<BarrierSegment> segments_;
  Vec2 origin_ = Vec2::Zero();   ///< lower corner of the grid (the segments' bounding box)
  double cell_m_ = 1;            ///< cell side, metres
  int nx_ = 0, ny_ = 0;
  std::vector<unsigned> cell_start_;  ///< nx * ny + 1 offsets into cell_segments_
  std::vector<unsigned> cell_segments_;
};

/// Which of a fixed set of points a query sees, for the methods that weigh every sample (global
/// Shepard and multiquadric): each point's side of every barrier's line is found once, so that a
/// query tests only the points across a segment's line from it (two orientations each). Exactly
/// Barriers::blocks() point by point. With many segments (more than kMaxSidedSegments) it asks
/// blocks(), whose grid then wins.
///
/// Queries come in runs of neighbours (a raster, a view's hits on a surface): a square grid of
/// kVerdictCells x kVerdictCells cells over the points and segments holds, per cell, the
/// verdicts that hold for the whole cell, for each pair of a segment and a point (the cell's
/// corners all certainly on one side of each line that decides it; the lines' orientations are
/// linear in the query), and the pairs left open; a query in a cell tests those alone. Each
/// thread keeps the verdicts of its last cells, made when a second query asks for the same cell
/// (scattered queries keep the direct tests). The same answers, bit for bit.
class PointVisibility {
 public:
  /// Both must outlive this.
  PointVisibility(std::span<const Vec2> points, const Barriers& barriers);
  /// hidden[i] = whether q does not see point i (resized to the points).
  void hidden_from(const Vec2& q, std::vector<char>& hidden) const;
  /// The indices of the points visible from q, ascending, into out; `hidden` is a buffer.
  void visible_from(const Vec2& q, std::vector<unsigned>& out, std::vector<char>& hidden) const;

  static constexpr size_t kMaxSidedSegments = 64;
  /// Cells of the verdicts' grid along each axis (see the class).
  static constexpr int kVerdictCells = 64;
  /// The most pairs of a segment and a point for the verdicts' grid: a thread keeps, for each of
  /// its 2 kVerdictCells cells, a byte per point and at most kMaxOpenShare of the pairs, 4 bytes
  /// each (a cell that leaves more open is not used): 96 KiB a cell, 12 MiB at most.
  static constexpr size_t kMaxVerdictPairs = 1 << 16;
  static constexpr double kMaxOpenShare = 1.0 / 8;

 private:
  struct Verdicts;
  /// The corners of the grid cell `cell` (row-major), counter-clockwise from the lower left.
  std::array<Vec2, 4> cell_corners(int cell) const;
  /// The verdicts of the grid cell `cell`, into v.
  void classify(int cell, Verdicts& v) const;
  /// Whether segment k hides point i from q (the rule of hidden_from()).
  bool pair_hides(const Vec2& q, size_t k, size_t i) const;

  std::span<const Vec2> points_;
  const Barriers* barriers_;
  std::vector<signed char> side_;  ///< segment-major: side_[s * n + i], the sign of orient(a_s, b_s, p_i)
  std::vector<double> px_, py_;    ///< the points' coordinates, m, as arrays (vectorised tests)
  std::uint64_t id_ = 0;           ///< tells this object's cells in the threads' caches from others'
  Vec2 grid_lo_ = Vec2::Zero();    ///< the verdicts' grid: its lower corner and cell size, m
  double cell_m_ = 0;              ///< 0: no grid (no segments, or a degenerate box)
};

class KdTree2;

/// Buffers of nearest_visible(), reused from query to query (per-thread scratch).
struct VisibleNeighbours {
  std::vector<unsigned> idx;         ///< the visible neighbours found, nearest first
  std::vector<double> dist_sq;       ///< their squared distances, m^2
  std::vector<unsigned> candidates;  ///< the k-d tree's candidates of the current round
  std::vector<double> candidates_dist_sq;
};

/// The k nearest of `points` (indexed by `tree`) visible from q past `barriers`, in (squared
/// distance, index) order, into found.idx and found.dist_sq; returns how many (fewer than k only
/// when fewer are visible). Searches the nearest 2k (at least 8), then twice as many, until k of
/// them are visible or every point was tried; each round tests its candidates from the first,
/// since equidistant points at the last place may come back in another order. Only the nearest
/// max(kMaxVisibleCandidates, 2k) points are tried: a query walled into a pocket would otherwise
/// try every point (and a k-d tree's k-nearest search costs ~k^2).
size_t nearest_visible(const KdTree2& tree, std::span<const Vec2> points, const Barriers& barriers, const Vec2& q,
                       size_t k, VisibleNeighbours& found);

/// The most points nearest_visible() tries for k <= kMaxVisibleCandidates / 2.
inline constexpr size_t kMaxVisibleCandidates = 512;

/// Whether all points lie on one line (or coincide), by exact orientation tests.
bool all_on_one_line(std::span<const Vec2> points);

/// Whether the open segment (p, q) meets the closed segment [a, b] (the rule of barriers.h),
/// by exact orientation tests: the brute-force definition that Barriers::blocks() accelerates.
bool segment_blocked(const Vec2& p, const Vec2& q, const BarrierSegment& s);

}  // namespace radrecon
