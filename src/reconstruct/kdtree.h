#pragma once
// k-nearest-neighbour queries over 2-D points (nanoflann underneath).

#include <memory>
#include <span>
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

  /// The k nearest points to q (k <= size()), nearest first: indices and squared distances
  /// (m^2). Among the points found, equal distances are ordered by index (which of several
  /// equidistant points beyond the k-th is found is up to the tree, but deterministic).
  void nearest(const Vec2& q, int k, std::vector<unsigned>& indices, std::vector<double>& dist_sq) const;
  size_t size() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace radrecon
