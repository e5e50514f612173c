#include "render/surface_bvh.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/check.h"
#include "core/tolerances.h"

namespace radrecon {

SurfaceBvh::SurfaceBvh(const Scene& scene) {
  const size_t n = scene.surfaces.size();
  if (n == 0) return;
  // Per surface: its box, widened, and its centroid.
  std::vector<std::array<Vec3, 3>> boxes(n);
  Vec3 scene_lo = scene.surfaces[0].corners[0], scene_hi = scene_lo;
  for (size_t k = 0; k < n; ++k) {
    const Surface& s = scene.surfaces[k];
    Vec3 lo = s.corners[0], hi = s.corners[0];
    for (const Vec3& c : s.corners) lo = lo.cwiseMin(c), hi = hi.cwiseMax(c);
    boxes[k] = {lo, hi, 0.5 * (lo + hi)};
    scene_lo = scene_lo.cwiseMin(lo), scene_hi = scene_hi.cwiseMax(hi);
  }
  const double slack_m = tol::kRayBoxSlackRelative * (1.0 + (scene_hi - scene_lo).norm() + scene_lo.norm() + scene_hi.norm());
  for (auto& b : boxes) b[0].array() -= slack_m, b[1].array() += slack_m;
  order_.resize(n);
  for (size_t k = 0; k < n; ++k) order_[k] = k;
  nodes_.reserve(2 * n);
  nodes_.emplace_back();
  build(0, 0, static_cast<int>(n), boxes);
}

void SurfaceBvh::build(size_t index, int begin, int end, const std::vector<std::array<Vec3, 3>>& boxes) {
  Vec3 lo = boxes[order_[static_cast<size_t>(begin)]][0], hi = boxes[order_[static_cast<size_t>(begin)]][1];
  Vec3 clo = boxes[order_[static_cast<size_t>(begin)]][2], chi = clo;
  for (int k = begin; k < end; ++k) {
    const auto& b = boxes[order_[static_cast<size_t>(k)]];
    lo = lo.cwiseMin(b[0]), hi = hi.cwiseMax(b[1]);
    clo = clo.cwiseMin(b[2]), chi = chi.cwiseMax(b[2]);
  }
  nodes_[index].lo = lo;
  nodes_[index].hi = hi;
  if (end - begin <= kLeafSize) {
    nodes_[index].first = begin;
    nodes_[index].count = end - begin;
    return;
  }
  // Median split along the longest axis of the centroids' box (ties by surface index: the same
  // tree on every machine).
  int axis = 0;
  (chi - clo).maxCoeff(&axis);
  const int mid = begin + (end - begin) / 2;
  std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end, [&](size_t x, size_t y) {
    const double cx = boxes[x][2][axis], cy = boxes[y][2][axis];
    return cx < cy || (cx == cy && x < y);
  });
  const int first = static_cast<int>(nodes_.size());
  nodes_[index].first = first;
  nodes_[index].count = 0;
  nodes_.emplace_back();
  nodes_.emplace_back();
  build(static_cast<size_t>(first), begin, mid, boxes);
  build(static_cast<size_t>(first + 1), mid, end, boxes);
  RR_CHECK(nodes_.size() <= 2 * order_.size(), "surface hierarchy larger than expected");
}

double SurfaceBvh::enter(const Node& node, const Vec3& o, const Vec3& inverse, double t_max) {
  double t0 = 0, t1 = t_max;
  for (int a = 0; a < 3; ++a) {
    // An axis the ray runs parallel to: inside the slab or not (an infinite inverse would give
    // 0 x infinity = NaN at the slab's face).
    if (!std::isfinite(inverse[a])) {
      if (o[a] < node.lo[a] || o[a] > node.hi[a]) return -1;
      continue;
    }
    double ta = (node.lo[a] - o[a]) * inverse[a], tb = (node.hi[a] - o[a]) * inverse[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (!(t0 <= t1)) return -1;
  }
  return t0;
}

}  // namespace radrecon
