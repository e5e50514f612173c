// The box hierarchy's defining properties on random boxes: every item in exactly one leaf, no
// leaf over its size, every item inside its leaf's box and every child inside its parent's, and
// each split at the median (children's counts differ by at most one).

#include <gtest/gtest.h>

#include <array>
#include <random>

#include "core/box_hierarchy.h"

namespace radrecon {
namespace box_hierarchy_test {

bool inside(const Vec3& lo, const Vec3& hi, const Vec3& outer_lo, const Vec3& outer_hi) {
  return (lo.array() >= outer_lo.array()).all() && (hi.array() <= outer_hi.array()).all();
}

TEST(BoxHierarchy, EveryItemInOneLeafInsideItsBoxChildrenInsideParentsSplitAtTheMedian) {
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> at(-10, 10), size(0, 1);
  for (const int n : {1, 2, 5, 37, 1000}) {
    std::vector<BoxItem> items;
    for (int k = 0; k < n; ++k) {
      const Vec3 lo(at(rng), at(rng), at(rng)), hi = lo + Vec3(size(rng), size(rng), size(rng));
      items.push_back({lo, hi, 0.5 * (lo + hi)});
    }
    std::vector<BoxNode> nodes;
    std::vector<int> order;
    build_box_hierarchy(items, 4, nodes, order);
    ASSERT_EQ(order.size(), items.size());
    std::vector<int> seen(items.size(), 0);
    // Walk from the root: each node's items are a range of `order`, split in halves.
    std::vector<std::array<int, 3>> stack{{0, 0, n}};  // node, first position, end position
    while (!stack.empty()) {
      const auto [index, begin, end] = stack.back();
      stack.pop_back();
      const BoxNode& node = nodes[static_cast<size_t>(index)];
      for (int p = begin; p < end; ++p) {
        const BoxItem& item = items[static_cast<size_t>(order[static_cast<size_t>(p)])];
        ASSERT_TRUE(inside(item.lo, item.hi, node.lo, node.hi));
      }
      if (node.count > 0) {
        ASSERT_EQ(node.first, begin);
        ASSERT_EQ(node.count, end - begin);
        ASSERT_LE(node.count, 4);
        for (int p = begin; p < end; ++p) ++seen[static_cast<size_t>(order[static_cast<size_t>(p)])];
        continue;
      }
      const int mid = begin + (end - begin) / 2;
      for (int c = 0; c < 2; ++c) {
        const BoxNode& child = nodes[static_cast<size_t>(node.first + c)];
        ASSERT_TRUE(inside(child.lo, child.hi, node.lo, node.hi));
      }
      stack.push_back({node.first, begin, mid});
      stack.push_back({node.first + 1, mid, end});
    }
    for (const int s : seen) EXPECT_EQ(s, 1);
  }
}

TEST(BoxHierarchy, NoItemsMakeNoNodes) {
  std::vector<BoxNode> nodes(3);
  std::vector<int> order(2);
  build_box_hierarchy({}, 4, nodes, order);
  EXPECT_TRUE(nodes.empty());
  EXPECT_TRUE(order.empty());
}

}  // namespace box_hierarchy_test
}  // namespace radrecon
