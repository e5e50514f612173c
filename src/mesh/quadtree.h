#pragma once
// A quadtree over one side of a scene surface: the adaptive subdivision of hierarchical
// radiosity (solver/hierarchical.h keeps the links and radiosities beside it, indexed by node).
// Node 0 is the whole side; a split gives a node four children, the quarters of its (u,v)
// rectangle, stored consecutively.

#include <array>
#include <vector>

#include "mesh/grid_mesh.h"
#include "scene/scene.h"

namespace radrecon {

/// One node: the image of the (u,v) rectangle [u0,u1] x [v0,v1] of its surface side.
struct QuadNode {
  double u0, v0, u1, v1;
  std::array<Vec3, 4> corners;  ///< counter-clockwise seen from the front of the side
  Vec3 center;                  ///< the surface point at the (u,v) centre
  double area_m2 = 0;
  double size_m = 0;            ///< the longer of its two edges, metres
  /// The first of four consecutive children, in the order (u low, v low), (u high, v low),
  /// (u low, v high), (u high, v high); -1 for a leaf.
  int first_child = -1;
  bool is_leaf() const { return first_child < 0; }
};

class Quadtree {
 public:
  /// The root alone, covering the whole side. `surface` must outlive the tree.
  Quadtree(const Surface& surface, bool back_side);

  const QuadNode& node(int index) const { return nodes_[static_cast<size_t>(index)]; }
  int node_count() const { return static_cast<int>(nodes_.size()); }
  int leaf_count() const { return leaves_; }

  /// Splits a leaf into its four quarters and returns the index of the first child; a node
  /// that has children already keeps them (their first index is returned).
  int split(int index);

  /// The leaves below `root` (the whole tree by default), depth first, children in order.
  std::vector<int> leaves(int root = 0) const;

  /// The leaf containing (u, v) in [0,1]^2 (clamped into it). Leaves are half-open,
  /// [u0, u1) x [v0, v1), closed on the side's far border, so every point has exactly one.
  int locate(double u, double v) const;

 private:
  QuadNode make_node(double u0, double v0, double u1, double v1) const;

  const Surface* surface_;
  bool back_side_;
  std::vector<QuadNode> nodes_;
  int leaves_ = 1;
};

}  // namespace radrecon
