#pragma once
// k-nearest-neighbour queries over 2-D points (nanoflann underneath).

#include <memory>
#include <span>

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
  size_t size() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace radrecon
