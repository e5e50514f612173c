#pragma once
// A quadtree over one side of a scene surface: the adaptive subdivision of hierarchical
// radiosity (solver/hierarchical.h keeps the links and radiosities beside it, indexed by node).
// Node 0 is the whole side; a split gives a node four children, the quarters of its parameter
// cell (ParamCell::quarters(): a box's four quarters, or a triangle's 4-way midpoint split),
// stored consecutively.

#include <array>
#include <vector>

#include "mesh/grid_mesh.h"
#include "scene/scene.h"

namespace radrecon {

/// One node: the image of a cell of its surface side's parameter domain.
struct QuadNode : ParamCell {
  /// Counter-clockwise seen from the front of the side; a triangle repeats its last corner.
  std::array<Vec3, 4> corners;
  Vec3 center;                  ///< the surface point at the (u,v) centre
  double area_m2 = 0;
  double size_m = 0;            ///< its longest edge, metres (a quad's: the longer parametric one)
  /// The first of four consecutive children, in the order of ParamCell::quarters(); -1 for a leaf.
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

  /// Splits a leaf into its four quarters (ParamCell::quarters()) and returns the index of the first child; a node
  /// that has children already keeps them (their first index is returned).
  int split(int index);

  /// The leaves below `root` (the whole tree by default), depth first, children in order.
  std::vector<int> leaves(int root = 0) const;

  /// The leaf containing (u, v) (clamped into the parameter domain). Leaves are half-open
  /// (ParamCell::quarter_of()), so every point has exactly one.
  int locate(double u, double v) const;

  /// The node a split would make for `cell` (a cell of this side's parameter domain), without
  /// storing it: its corners, centre, area and size as split() computes them.
  QuadNode node_for(const ParamCell& cell) const;

 private:

  const Surface* surface_;
  bool back_side_;
  std::vector<QuadNode> nodes_;
  int leaves_ = 1;
};

}  // namespace radrecon
