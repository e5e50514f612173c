#include "mesh/quadtree.h"

#include <algorithm>

#include "core/check.h"

namespace radrecon {

Quadtree::Quadtree(const Surface& surface, bool back_side) : surface_(&surface), back_side_(back_side) {
  nodes_.push_back(make_node(0, 0, 1, 1));
}

QuadNode Quadtree::make_node(double u0, double v0, double u1, double v1) const {
  const MeshElement e = make_element(*surface_, back_side_, u0, v0, u1, v1);
  QuadNode n;
  n.u0 = u0;
  n.v0 = v0;
  n.u1 = u1;
  n.v1 = v1;
  n.corners = e.corners;
  n.center = e.center;
  n.area_m2 = e.area_m2;
  n.size_m = std::max((u1 - u0) * surface_->length_u_m(), (v1 - v0) * surface_->length_v_m());
  return n;
}

int Quadtree::split(int index) {
  RR_CHECK(index >= 0 && index < node_count(), "quadtree node index out of range");
  if (!nodes_[static_cast<size_t>(index)].is_leaf()) return nodes_[static_cast<size_t>(index)].first_child;
  const QuadNode parent = nodes_[static_cast<size_t>(index)];
  const double um = 0.5 * (parent.u0 + parent.u1), vm = 0.5 * (parent.v0 + parent.v1);
  const int first = node_count();
  nodes_.push_back(make_node(parent.u0, parent.v0, um, vm));
  nodes_.push_back(make_node(um, parent.v0, parent.u1, vm));
  nodes_.push_back(make_node(parent.u0, vm, um, parent.v1));
  nodes_.push_back(make_node(um, vm, parent.u1, parent.v1));
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
  int k = 0;
  while (!node(k).is_leaf()) {
    const QuadNode& n = node(k);
    const double um = 0.5 * (n.u0 + n.u1), vm = 0.5 * (n.v0 + n.v1);
    k = n.first_child + (u >= um ? 1 : 0) + (v >= vm ? 2 : 0);
  }
  return k;
}

}  // namespace radrecon
