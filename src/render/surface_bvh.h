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
  /// Surface::parameters() accepts on an edge is never missed), where `t_max` is re-read
  /// after each leaf, so a caller may lower it as hits are found. `inverse`: 1 / d per axis.
  template <class TMax>
  void collect(const Vec3& o, const Vec3& inverse, TMax&& t_max, std::vector<size_t>& out) const;

  size_t node_count() const { return nodes_.size(); }

 private:
  /// The entry of the ray into the node's box, or a negative value if it misses it.
  static double enter(const BoxNode& node, const Vec3& o, const Vec3& inverse, double t_max);

  std::vector<int> order_;       ///< surfaces, leaf by leaf
  std::vector<BoxNode> nodes_;  ///< core/box_hierarchy.h
};

template <class TMax>
void SurfaceBvh::collect(const Vec3& o, const Vec3& inverse, TMax&& t_max, std::vector<size_t>& out) const {
  if (nodes_.empty()) return;
  std::array<int, 64> stack;
  int top = 0;
  if (enter(nodes_[0], o, inverse, t_max()) >= 0) stack[top++] = 0;
  while (top > 0) {
    const BoxNode& node = nodes_[static_cast<size_t>(stack[--top])];
    if (node.count > 0) {
      for (int k = 0; k < node.count; ++k) out.push_back(static_cast<size_t>(order_[static_cast<size_t>(node.first + k)]));
      continue;
    }
    // The nearer child on top, so that its hits lower t_max before the farther one is entered.
    const int a = node.first, b = node.first + 1;
    const double ta = enter(nodes_[static_cast<size_t>(a)], o, inverse, t_max());
    const double tb = enter(nodes_[static_cast<size_t>(b)], o, inverse, t_max());
    if (ta >= 0 && tb >= 0) {
      stack[top++] = ta <= tb ? b : a;
      stack[top++] = ta <= tb ? a : b;
    } else if (ta >= 0) {
      stack[top++] = a;
    } else if (tb >= 0) {
      stack[top++] = b;
    }
  }
}

}  // namespace radrecon
