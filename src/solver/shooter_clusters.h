#pragma once
// Clusters of small shooters for progressive refinement (solver/progressive.h): a model's
// triangles, each a side of a single element, grouped by position so that a group shoots its
// unshot power in one shot rather than one shot each.
//
// A scene of N such sides shot one by one costs N shots of N receivers each, every one with
// exact shadows: the 10,000-triangle scene of issue 11 spent 40-50 ms a triangle. The members of
// a cluster (up to kClusterMembers) lie in a hierarchy, and a receiving element gathers from it
// top down (as Barnes and Hut sum gravity):
// - a subtree at least tol::kClusterFarRadii of its radius away (tol::kClusterMemberFarRadii for
//   a single member) shoots as the sum of its members' sources, past one shadow ray from the
//   element to the subtree's centre (OccluderBvh::blocks_segment()); the receiver's surface, and
//   whatever lies within the subtree's radius of its centre (its own members among it), aside:
//   the shadow of a point light where the subtree is small against its distance. Each member's
//   source is its exact (Lambert) form factor times its unshot radiosity, or beyond
//   tol::kClusterPointKernelRadii of its own radii its point kernel B A cos_m cos_x / (pi d^2);
// - a member nearer than that shoots as any patch does (gather()): exact shadows, the Gauss rule
//   where the element is large against its distance.
// A penumbra narrower than a subtree's size is drawn as a hard edge; the unshot power of every
// member goes in the shot and the power delivered is counted as for a patch, so what misses is
// counted as escaped.

#include <cstdint>
#include <span>
#include <vector>

#include "mesh/grid_mesh.h"
#include "scene/scene.h"
#include "solver/bvh.h"
#include "solver/gather.h"
#include "solver/shooter_tree.h"

namespace radrecon {

/// The most members of a cluster: the largest subtrees of ShooterClusters' hierarchy with at most
/// this many members shoot as one.
inline constexpr int kClusterMembers = 256;

/// A mesh's sides of a single element as a hierarchy over their centroids (a median split down to
/// single members, core/box_hierarchy.h), every node's members contiguous; and the clusters that
/// shoot, each a subtree.
struct ShooterClusters {
  struct Node {
    Vec3 center;          ///< the members' area-weighted centroid: where shadow rays end
    double radius_m = 0;  ///< the largest distance from `center` to a member's corner
    int begin = 0, end = 0;  ///< its members: sides[begin, end)
    int first_child = -1;    ///< children first_child and first_child + 1; -1: a single member
  };
  std::vector<Node> nodes;
  std::vector<size_t> sides;  ///< the members, mesh sides of one element each, node by node
  std::vector<int> roots;     ///< by cluster: its subtree's root node
  std::vector<int> cluster_of_side;  ///< by mesh side: its cluster, or -1
  bool empty() const { return roots.empty(); }
};

/// The clusters over the mesh's sides of a single element; none when there are fewer than
/// tol::kLeastClusteredSides of them. Deterministic.
ShooterClusters make_shooter_clusters(const Mesh& mesh);

/// One shot of a cluster: its members' unshot radiosities, taken when it is made (the members'
/// unshot radiosity may then be cleared), and what an element gathers from them.
class ClusterShot {
 public:
  /// `unshot`: by mesh side, each element's unshot radiosity, W/m^2. Everything given must
  /// outlive the shot.
  ClusterShot(const Scene& scene, const Mesh& mesh, const ShooterClusters& clusters, size_t cluster,
              const OccluderBvh& bvh,
              std::span<const std::vector<Rgb>* const> unshot);

  /// What the element `r` of the side `receiver_side` gathers from the cluster's members: from
  /// each subtree at least tol::kClusterFarRadii of its radii away (kClusterMemberFarRadii for one
  /// member) as from its members' sources past one shadow ray to its centre, from each nearer
  /// member with exact shadows (gather()).
  /// Thread-safe (one call at a time per thread: ReceiverShadows' buffers).
  Gathered gather(const Receiver& r, size_t receiver_side) const;

  /// The power the members shoot, W per channel.
  const Rgb& power_w() const { return power_w_; }

 private:
  /// The unoccluded irradiance at p (unit normal n) from the members [begin, end), W/m^2: their
  /// form factors times their radiosity, or their point kernels far from them.
  Rgb far_irradiance(int begin, int end, const Vec3& p, const Vec3& n) const;
  /// far_irradiance() of the node's members at p, or zero if an occluder hides the node's centre
  /// from p (past its radius).
  Rgb seen_irradiance(const ShooterClusters::Node& node, const Vec3& p, const Vec3& n, size_t receiver_surface) const;

  const Mesh& mesh_;
  const ShooterClusters& clusters_;
  const OccluderBvh& bvh_;
  int root_;
  std::vector<ShooterTree> trees_;       ///< by member from the root's begin: its one block
  // By member (ShooterClusters::sides, from the root's begin): centroid, unit normal, unshot
  // radiosity B and A B / pi, corners, and the squared distance beyond which its point kernel
  // stands for its form factor.
  std::vector<Vec3> at_, normal_;
  std::vector<Rgb> radiosity_, intensity_;
  std::vector<std::pair<std::array<Vec3, 4>, int>> corners_;
  std::vector<double> point_kernel_m2_;
  Rgb power_w_ = Rgb::Zero();
};

}  // namespace radrecon
