#pragma once
// The one builder of the bounding volume hierarchies radrecon keeps (the solver's occluders,
// solver/bvh.h; the renderer's surfaces, render/surface_bvh.h): nodes over items given by their
// axis-aligned boxes, split at the median of their centres along the longest axis of the
// centres' box, at most a given number of items a leaf.

#include <span>
#include <vector>

#include "core/vec.h"

namespace radrecon {

/// A node: its box, and either a leaf's items or its two children.
struct BoxNode {
  Vec3 lo, hi;
  int first = 0;  ///< leaf: first position in the item order; inner: index of the first child
  int count = 0;  ///< leaf: number of items; inner: 0 (children at first, first + 1)
};

/// An item to build over: its box and its centre.
struct BoxItem {
  Vec3 lo, hi, centre;
};

/// Where the ray o + t d enters the box [lo, hi] for t in [0, t_max]: the least such t, or a
/// negative value if it misses the box. `inverse`: 1 / d per axis (infinite along an axis the
/// ray runs parallel to). The slab test of both hierarchies' ray queries.
double ray_box_entry(const Vec3& lo, const Vec3& hi, const Vec3& o, const Vec3& inverse, double t_max);

/// Builds the hierarchy of `items` into `nodes` (node 0 the root; empty for no items) and
/// `order` (the items' indices, leaf by leaf). Deterministic: the same input gives the same tree.
void build_box_hierarchy(std::span<const BoxItem> items, int leaf_size, std::vector<BoxNode>& nodes,
                         std::vector<int>& order);

}  // namespace radrecon
