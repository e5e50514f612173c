// The segment nearest to a point among many (reconstruct/nearest_segment.h).

#include "reconstruct/nearest_segment.h"

#include <algorithm>
#include <limits>
#include <optional>

#include "core/check.h"

namespace radrecon {

namespace {

/// Segments a leaf of the hierarchy holds.
constexpr int kLeafSegments = 4;

/// The squared distance from q to the box [lo, hi] in the plane (0 inside it).
double box_distance_sq(const BoxNode& n, const Vec2& q) {
  const double dx = std::max({n.lo.x() - q.x(), 0.0, q.x() - n.hi.x()});
  const double dy = std::max({n.lo.y() - q.y(), 0.0, q.y() - n.hi.y()});
  return dx * dx + dy * dy;
}

}  // namespace

NearestSegment::NearestSegment(std::span<const Vec2> points, std::vector<std::pair<unsigned, unsigned>> segments,
                               std::vector<std::pair<unsigned, unsigned>> keys)
    : points_(points), segments_(std::move(segments)), keys_(std::move(keys)) {
  RR_CHECK(keys_.size() == segments_.size(), "one key per segment");
  std::vector<BoxItem> items;
  items.reserve(segments_.size());
  for (const auto& [a, b] : segments_) {
    const Vec2 lo = points_[a].cwiseMin(points_[b]), hi = points_[a].cwiseMax(points_[b]);
    items.push_back({Vec3(lo.x(), lo.y(), 0), Vec3(hi.x(), hi.y(), 0), Vec3(0.5 * (lo.x() + hi.x()), 0.5 * (lo.y() + hi.y()), 0)});
  }
  build_box_hierarchy(items, kLeafSegments, nodes_, order_);
}

std::optional<NearestSegment::Found> NearestSegment::nearest(const Vec2& q) const {
  if (nodes_.empty()) return std::nullopt;
  std::optional<Found> best;
  double best_sq = std::numeric_limits<double>::infinity();
  std::pair<unsigned, unsigned> best_key;
  // Depth first, the nearer child first; a box farther than the best distance is passed over
  // (one as far is not: a tie there may have the smaller key).
  std::vector<int> stack = {0};
  while (!stack.empty()) {
    const BoxNode& n = nodes_[static_cast<size_t>(stack.back())];
    stack.pop_back();
    if (box_distance_sq(n, q) > best_sq) continue;
    if (n.count > 0) {
      for (int k = n.first; k < n.first + n.count; ++k) {
        const size_t s = static_cast<size_t>(order_[static_cast<size_t>(k)]);
        const Vec2 &a = points_[segments_[s].first], &b = points_[segments_[s].second];
        const double t = nearest_on_segment_t(q, a, b);
        const double d = (a + t * (b - a) - q).squaredNorm();
        if (d < best_sq || (best && d == best_sq && keys_[s] < best_key)) best = Found{s, t}, best_sq = d, best_key = keys_[s];
      }
      continue;
    }
    const int near = n.first, far = n.first + 1;
    const bool swap = box_distance_sq(nodes_[static_cast<size_t>(far)], q) < box_distance_sq(nodes_[static_cast<size_t>(near)], q);
    stack.push_back(swap ? near : far);
    stack.push_back(swap ? far : near);
  }
  return best;
}

}  // namespace radrecon
