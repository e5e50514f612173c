#pragma once
// k-nearest-neighbour queries over 2-D points: one at a time (KdTree2, nanoflann underneath), or
// many coherent ones at once (CoherentNearest).

#include <cstdint>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "core/vec.h"

namespace radrecon {

class KdTree2 {
 public:
  /// The points must outlive the tree.
  explicit KdTree2(std::span<const Vec2> points);
  ~KdTree2();
  KdTree2(const KdTree2&) = delete;
  KdTree2& operator=(const KdTree2&) = delete;

  /// The k nearest points to q (1 <= k <= size()), written to the caller's buffers (each of size
  /// >= k; entries past the count returned are unspecified): indices and squared distances (m^2).
  /// Returns the number found (k, since k <= size()). No allocation.
  ///
  /// Order: by (dist_sq, index), nearest first, equal distances by increasing index.
  /// Which points: every point strictly closer than the k-th distance is found. When several
  /// points are equidistant at the k-th distance and not all fit, which of them are found is
  /// up to the tree (deterministic for a given tree and query, but not necessarily the lowest
  /// indices).
  size_t nearest(const Vec2& q, int k, std::span<unsigned> indices, std::span<double> dist_sq) const;
  /// Every point whose squared distance to q (computed as nearest() computes it) is below
  /// radius_sq (m^2), into `found` as (index, squared distance) by (dist_sq, index), nearest
  /// first: the first k - 1 points, in the same order, of a nearest() call whose k-th distance
  /// is the first to reach radius_sq. `found` is cleared first; its capacity is reused.
  void within(const Vec2& q, double radius_sq, std::vector<std::pair<unsigned, double>>& found) const;
  size_t size() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// The k nearest points of many query points that come in coherent runs (a raster's pixels),
/// with the same answers as KdTree2::nearest() at a fraction of a tree search each. The queries
/// are grouped into square tiles (tile()). A tile finds once the points that can be among any
/// of its queries' k nearest: those within r + 2h of its centre c, with r the distance of c's
/// k-th nearest and h the tile's half-diagonal (a query q within h of c has k points within
/// |q - c| + r, so its k-th nearest is no farther, and that disc lies within r + 2h of c). Each
/// query then ranks only the candidates within the previous query's k-th distance, a little
/// widened, when they are at least k (they then hold the k nearest), else within that distance
/// plus the step between the two queries (a bound, by the same argument): usually k and a few.
///
/// Answers: the k smallest by (squared distance, index), so the points of nearest() except that
/// ties at the k-th distance go to the lowest indices (but for a tile far from the points, whose
/// queries search the tree: there the tree's choice among such ties stands); squared distances
/// computed as nearest() computes them, bit for bit. They come in an order fixed by the points alone (the order of
/// their buckets), not by distance: sorting is most of a tree search's cost, and a sum over them
/// in this order still does not depend on which tile, batch or thread a query was in.
class CoherentNearest {
 public:
  /// `tree` indexes `points`; both must outlive this. 1 <= k <= points.size().
  CoherentNearest(const KdTree2& tree, std::span<const Vec2> points, int k);

  /// Queries grouped into tiles: every finite query in exactly one, the non-finite in none.
  struct Tiles {
    std::vector<std::uint32_t> order;  ///< query indices tile by tile, increasing within a tile
    std::vector<std::uint32_t> first;  ///< tile t holds order[first[t], first[t + 1])
    std::vector<Vec2> centre;          ///< of the tile's queries' bounding box
    std::vector<double> half_diagonal_m;
    size_t count() const { return first.empty() ? 0 : first.size() - 1; }
  };
  Tiles tile(std::span<const Vec2> queries) const;

  /// Buffers of one thread (visit_tile()).
  struct Scratch {
    std::vector<double> cx, cy, d2;  ///< the tile's candidates, and their squared distances to a query
    std::vector<unsigned> ci;        ///< their indices
    std::vector<std::uint32_t> pos;  ///< positions among a query's candidates, or bucket slots
    std::vector<unsigned> indices;   ///< a query's answer; while ranking, its candidates' indices
    std::vector<double> dist_sq;     ///< ... and squared distances
    double centre_kth_m = 0;  ///< the tile centre's k-th distance
  };

  /// Calls visit(q, indices, dist_sq, nearest) for each query of tile t (`tiles` = tile(queries))
  /// in increasing q: its k nearest points' indices and squared distances (in the order above),
  /// and the position among them of the nearest (the lowest index among equally near).
  template <typename Visit>
  void visit_tile(const Tiles& tiles, std::span<const Vec2> queries, size_t t, Scratch& s, Visit&& visit) const {
    const bool candidates = gather_candidates(tiles.centre[t], tiles.half_diagonal_m[t], s);
    Vec2 last(0, 0);
    double last_kth_m = -1;  // the previous query's k-th distance; < 0: none yet
    for (std::uint32_t e = tiles.first[t]; e < tiles.first[t + 1]; ++e) {
      const size_t q = tiles.order[e];
      size_t nearest = 0;
      if (candidates) {
        last_kth_m = select(queries[q], tiles.centre[t], last, last_kth_m, s, nearest);
        last = queries[q];
      } else {
        tree_.nearest(queries[q], k_, s.indices, s.dist_sq);
        nearest = in_bucket_order(queries[q], s);
      }
      visit(q, std::span<const unsigned>(s.indices.data(), static_cast<size_t>(k_)),
            std::span<const double>(s.dist_sq.data(), static_cast<size_t>(k_)), nearest);
    }
  }

 private:
  /// The candidates of the tile (centre c, half-diagonal h) into s; false when they would be
  /// too many (queries far from the points): its queries then search the tree one at a time.
  bool gather_candidates(const Vec2& c, double h, Scratch& s) const;
  /// Puts a tree search's answer (nearest first) in the points' bucket order, as select() gives
  /// it, so that a sum over them does not depend on which way they were found; returns the
  /// position of the nearest.
  size_t in_bucket_order(const Vec2& q, Scratch& s) const;
  /// q's k nearest among the candidates into s.indices and s.dist_sq, the position of the
  /// nearest into `nearest`; returns q's k-th distance.
  double select(const Vec2& q, const Vec2& centre, const Vec2& last, double last_kth_m, Scratch& s,
                size_t& nearest) const;

  const KdTree2& tree_;
  int k_;
  double tile_m_ = 1;  ///< a tile's side, metres: its square holds about k / 8 points on average
  /// The points bucketed on a grid of `bucket_m_` from bucket_origin_: bucket (a, b) holds
  /// entries [bucket_first_[b * buckets_x_ + a], bucket_first_[... + 1]) of the arrays below.
  Vec2 bucket_origin_;
  double bucket_m_ = 1;
  int buckets_x_ = 1, buckets_y_ = 1;
  std::vector<std::uint32_t> bucket_first_;
  std::vector<double> bucket_x_, bucket_y_;
  std::vector<unsigned> bucket_index_;
  std::vector<std::uint32_t> bucket_slot_;  ///< point i is entry bucket_slot_[i] of the arrays above
};

}  // namespace radrecon
