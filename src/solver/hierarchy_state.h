#pragma once
// Hierarchical radiosity's state (solver/hierarchical.h), internal to the solver: one quadtree
// per surface side with the radiometry of every node, the links between nodes, and the
// gathering over them (Jacobi iterations with push-pull) that turns links into radiosity.

#include <string>
#include <vector>

#include "mesh/quadtree.h"
#include "scene/side.h"
#include "solver/covered.h"
#include "solver/enclosed.h"
#include "solver/solution.h"

namespace radrecon::hierarchy {

/// The radiometry of one quadtree node (the geometry is the Quadtree's, at the same index).
struct NodeState {
  Rgb radiosity = Rgb::Zero();
  Rgb gathered = Rgb::Zero();  ///< irradiance through this node's own links, W/m^2
  Rgb irradiance = Rgb::Zero();  ///< leaves: total irradiance including the ancestors', W/m^2
  double spread_w_m2 = 0;        ///< max - min of the children's radiosity (channel mean); 0 at leaves
  double exposed = 1;            ///< Tree::exposed_fraction_of() the node, set when it is made
  /// The fraction of the node outside the regions that surfaces standing on its side enclose
  /// (Tree::enclosed), set when it is made. No light reaches those regions, so the node's
  /// radiosity (its mean over its area) is nil there, and what it sends is seen from its
  /// unenclosed part alone, at seen_radiosity().
  double unenclosed = 1;
  /// The radiosity of the node's unenclosed part, W/m^2: what a receiver sees of it (its visible
  /// form factor leaves the enclosed part out). 0 for a node wholly enclosed.
  Rgb seen_radiosity() const {
    if (unenclosed >= 1) return radiosity;
    return unenclosed > 0 ? Rgb(radiosity / unenclosed) : Rgb::Zero();
  }
};

/// One side of one surface: its quadtree and the radiometry of every node.
struct Tree {
  Tree(const Surface& surface, size_t index, bool back)
      : name(side_name(surface, back)), scene_surface(index), back_side(back), normal(side_normal(surface, back)),
        reflectance(surface.reflectance), emission_w_m2(side_emission(surface, back)), quad(surface, back) {
    state.push_back({emission_w_m2});
  }
  std::string name;
  size_t scene_surface = 0;
  bool back_side = false;
  Vec3 normal;
  Rgb reflectance, emission_w_m2;
  Quadtree quad;
  std::vector<NodeState> state;  ///< by node index
  int leaf_cap = 0;              ///< 0: no cap
  /// The surfaces lying on this one (solver/covered.h): a node's exposed fraction scales what it
  /// emits, absorbs and reflects, so its radiosity is its mean over its area, the covered part dark.
  std::vector<ConvexPolygon> covers;
  /// The regions of this side that surfaces standing on it enclose (solver/enclosed.h: the floor
  /// under a block without a bottom): they neither receive nor send light.
  EnclosedRegions enclosed;
  /// The fraction of node k outside `enclosed`.
  double unenclosed_fraction_of(int k) const { return enclosed.exposed_fraction(node(k)); }
  /// The fraction of node k that `covers` leave exposed.
  double exposed_fraction_of(int k) const {
    const QuadNode& n = node(k);
    return exposed_fraction({n.corners.data(), static_cast<size_t>(n.vertex_count())}, normal, covers);
  }
  const QuadNode& node(int k) const { return quad.node(k); }
  NodeState& at(int k) { return state[static_cast<size_t>(k)]; }
  const NodeState& at(int k) const { return state[static_cast<size_t>(k)]; }
};

struct Link {
  int receiver_tree, receiver_node, source_tree, source_node;
  double f;         ///< area-to-area visible form factor, receiver -> source
  double f_spread;  ///< max - min of the point form factors over the receiver's samples
};

/// Jacobi gathering over all links, then push-pull, until no leaf's radiosity changes by more
/// than `tolerance` times the largest, or `max_iterations` have run. Returns whether the
/// tolerance stopped it (the last gather's state stays either way); `residual` gets the last
/// relative change.
bool gather_over_links(std::vector<Tree>& trees, const std::vector<Link>& links, int max_iterations, double tolerance,
                       double& residual);

/// Adds each tree to the solution as a surface side (its leaves as the elements, with their
/// radiosity, in leaf order), and to its stats the power emitted and absorbed, W per channel
/// (the covered parts' excluded), what escaped, and the element count.
void add_surfaces(const Scene& scene, const std::vector<Tree>& trees, Solution& sol);

}  // namespace radrecon::hierarchy
