#pragma once
// A bounding volume hierarchy over a scene's surfaces for the renderer's primary rays: a ray
// looks at the surfaces whose boxes it passes through, nearest boxes first, instead of at every
// surface (a model of 11,000 triangles rendered at 640 x 480 took 14 minutes).

#include <array>
#include <vector>

#include "core/box_hierarchy.h"
#include "scene/scene.h"

namespace radrecon {

class SurfaceBvh {
 public:
  static constexpr int kLeafSize = 4;

  /// The scene must outlive the hierarchy and not change.
  explicit SurfaceBvh(const Scene& scene);

  /// Appends to `out` every surface whose box the ray o + t d meets at some t in [0, t_max()]
  /// (boxes widened by tol::kRayBoxSlackRelative of the scene's size: a hit that
  /// Surface::parameters() accepts on an edge is never missed), and possibly some beyond it.
  /// `t_max` is called again before each node is entered, so a caller may lower it as hits are
  /// found. `inverse`: 1 / d per axis.
  template <class TMax>
  void collect(const Vec3& o, const Vec3& inverse, TMax&& t_max, std::vector<size_t>& out) const;

  size_t node_count() const { return nodes_.size(); }

 private:
  std::vector<int> order_;       ///< surfaces, leaf by leaf
  std::vector<BoxNode> nodes_;  ///< core/box_hierarchy.h
};

template <class TMax>
void SurfaceBvh::collect(const Vec3& o, const Vec3& inverse, TMax&& t_max, std::vector<size_t>& out) const {
  if (nodes_.empty()) return;
  // Nodes with the ray's entry into their box; depth <= log2(surfaces) + 1 for a median split,
  // and the stack holds at most one node more than that.
  struct Entry {
    int node;
    double t;
  };
  std::array<Entry, 64> stack;
  int top = 0;
  // The ray's entry into a node's box, or a negative value if it misses it.
  const auto enter = [&](int k) {
    const BoxNode& node = nodes_[static_cast<size_t>(k)];
    return ray_box_entry(node.lo, node.hi, o, inverse, t_max());
  };
  if (const double t = enter(0); t >= 0) stack[top++] = {0, t};
  while (top > 0) {
    const Entry entry = stack[--top];
    if (entry.t > t_max()) continue;  // hits found since it was pushed lie nearer
    const BoxNode& node = nodes_[static_cast<size_t>(entry.node)];
    if (node.count > 0) {
      for (int k = 0; k < node.count; ++k) out.push_back(static_cast<size_t>(order_[static_cast<size_t>(node.first + k)]));
      continue;
    }
    // The nearer child on top, so that its hits lower t_max before the farther one is entered.
    const int a = node.first, b = node.first + 1;
    const double ta = enter(a), tb = enter(b);
    if (ta >= 0 && tb >= 0) {
      stack[top++] = ta <= tb ? Entry{b, tb} : Entry{a, ta};
      stack[top++] = ta <= tb ? Entry{a, ta} : Entry{b, tb};
    } else if (ta >= 0) {
      stack[top++] = {a, ta};
    } else if (tb >= 0) {
      stack[top++] = {b, tb};
    }
  }
}

}  // namespace radrecon
