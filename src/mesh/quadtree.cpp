#include "mesh/quadtree.h"

#include <algorithm>

#include "core/check.h"

namespace radrecon {

Quadtree::Quadtree(const Surface& surface, bool back_side) : surface_(&surface), back_side_(back_side) {
  nodes_.push_back(node_for(surface.domain()));
}

QuadNode Quadtree::node_for(const ParamCell& cell) const {
  const MeshElement e = make_element(*surface_, back_side_, cell);
  QuadNode n;
  static_cast<ParamCell&>(n) = cell;
  n.corners = e.corners;
  n.center = e.center;
  n.area_m2 = e.area_m2;
  if (cell.is_triangle()) {
    for (int k = 0; k < 3; ++k) n.size_m = std::max(n.size_m, (e.corners[(k + 1) % 3] - e.corners[k]).norm());
  } else {
    n.size_m = std::max((cell.u1 - cell.u0) * surface_->length_u_m(), (cell.v1 - cell.v0) * surface_->length_v_m());
  }
  return n;
}

int Quadtree::split(int index) {
  RR_CHECK(index >= 0 && index < node_count(), "quadtree node index out of range");
  if (!nodes_[static_cast<size_t>(index)].is_leaf()) return nodes_[static_cast<size_t>(index)].first_child;
  const std::array<ParamCell, 4> quarters = nodes_[static_cast<size_t>(index)].quarters();
  const int first = node_count();
  for (const ParamCell& q : quarters) nodes_.push_back(node_for(q));
  nodes_[static_cast<size_t>(index)].first_child = first;
  leaves_ += 3;
  return first;
}

std::vector<int> Quadtree::leaves(int root) const {
  RR_CHECK(root >= 0 && root < node_count(), "quadtree node index out of range");
  std::vector<int> out;
  std::vector<int> stack{root};
  while (!stack.empty()) {
    const int k = stack.back();
    stack.pop_back();
    const QuadNode& n = node(k);
    if (n.is_leaf()) {
      out.push_back(k);
    } else {
      for (int c = 3; c >= 0; --c) stack.push_back(n.first_child + c);
    }
  }
  return out;
}

int Quadtree::locate(double u, double v) const {
  u = std::clamp(u, 0.0, 1.0);
  v = std::clamp(v, 0.0, 1.0);
  if (node(0).is_triangle() && u + v > 1) {
    const double sum = u + v;
    u /= sum;
    v /= sum;
  }
  int k = 0;
  while (!node(k).is_leaf()) {
    const QuadNode& n = node(k);
    k = n.first_child + n.quarter_of(u, v);
  }
  return k;
}

}  // namespace radrecon
