#include "core/box_hierarchy.h"

#include <algorithm>
#include <cmath>

#include "core/check.h"

namespace radrecon {

namespace {

void build_node(std::span<const BoxItem> items, int leaf_size, size_t index, int begin, int end,
                std::vector<BoxNode>& nodes, std::vector<int>& order) {
  const BoxItem& first = items[static_cast<size_t>(order[static_cast<size_t>(begin)])];
  Vec3 lo = first.lo, hi = first.hi, clo = first.centre, chi = first.centre;
  for (int k = begin + 1; k < end; ++k) {
    const BoxItem& item = items[static_cast<size_t>(order[static_cast<size_t>(k)])];
    lo = lo.cwiseMin(item.lo), hi = hi.cwiseMax(item.hi);
    clo = clo.cwiseMin(item.centre), chi = chi.cwiseMax(item.centre);
  }
  nodes[index].lo = lo;
  nodes[index].hi = hi;
  if (end - begin <= leaf_size) {
    nodes[index].first = begin;
    nodes[index].count = end - begin;
    return;
  }
  int axis = 0;
  (chi - clo).maxCoeff(&axis);
  const int mid = begin + (end - begin) / 2;
  std::nth_element(order.begin() + begin, order.begin() + mid, order.begin() + end, [&](int x, int y) {
    return items[static_cast<size_t>(x)].centre[axis] < items[static_cast<size_t>(y)].centre[axis];
  });
  const size_t left = nodes.size();
  nodes.emplace_back();
  nodes.emplace_back();
  nodes[index].first = static_cast<int>(left);
  nodes[index].count = 0;
  build_node(items, leaf_size, left, begin, mid, nodes, order);
  build_node(items, leaf_size, left + 1, mid, end, nodes, order);
}

}  // namespace

double ray_box_entry(const Vec3& lo, const Vec3& hi, const Vec3& o, const Vec3& inverse, double t_max) {
  double t0 = 0, t1 = t_max;
  for (int a = 0; a < 3; ++a) {
    // An axis the ray runs parallel to: inside the slab or not (an infinite inverse would give
    // 0 x infinity = NaN at the slab's face).
    if (!std::isfinite(inverse[a])) {
      if (o[a] < lo[a] || o[a] > hi[a]) return -1;
      continue;
    }
    double ta = (lo[a] - o[a]) * inverse[a], tb = (hi[a] - o[a]) * inverse[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (!(t0 <= t1)) return -1;
  }
  return t0;
}

void build_box_hierarchy(std::span<const BoxItem> items, int leaf_size, std::vector<BoxNode>& nodes,
                         std::vector<int>& order) {
  RR_CHECK(leaf_size >= 1, "a hierarchy's leaves hold at least one item");
  nodes.clear();
  order.resize(items.size());
  for (size_t k = 0; k < items.size(); ++k) order[k] = static_cast<int>(k);
  if (items.empty()) return;
  nodes.reserve(2 * items.size() / static_cast<size_t>(leaf_size) + 2);
  nodes.emplace_back();
  build_node(items, leaf_size, 0, 0, static_cast<int>(items.size()), nodes, order);
}

}  // namespace radrecon
