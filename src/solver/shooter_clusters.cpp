#include "solver/shooter_clusters.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "core/box_hierarchy.h"
#include "core/check.h"
#include "core/tolerances.h"
#include "solver/visibility.h"

namespace radrecon {

namespace {

/// Copies the box hierarchy's node `k` (and its subtree) into `out` at `index`, its members from
/// position `begin` of the hierarchy's order; returns the position after its last member.
int copy_node(const std::vector<BoxNode>& boxes, int k, const Mesh& mesh, std::span<const size_t> sides,
              const std::vector<int>& order, ShooterClusters& out, size_t index, int begin) {
  const BoxNode& box = boxes[static_cast<size_t>(k)];
  int end = begin;
  if (box.count > 0) {
    RR_CHECK_EQ(box.first, begin, "the hierarchy's leaves are in order");
    end = begin + box.count;
  } else {
    const size_t left = out.nodes.size();
    out.nodes.emplace_back();
    out.nodes.emplace_back();
    out.nodes[index].first_child = static_cast<int>(left);
    const int mid = copy_node(boxes, box.first, mesh, sides, order, out, left, begin);
    end = copy_node(boxes, box.first + 1, mesh, sides, order, out, left + 1, mid);
  }
  ShooterClusters::Node& node = out.nodes[index];
  node.begin = begin;
  node.end = end;
  double area_m2 = 0;
  Vec3 weighted = Vec3::Zero();
  for (int m = begin; m < end; ++m) {
    const MeshElement& e = mesh.surfaces[sides[static_cast<size_t>(order[static_cast<size_t>(m)])]].elements[0];
    weighted += e.area_m2 * e.center;
    area_m2 += e.area_m2;
  }
  node.center = area_m2 > 0 ? Vec3(weighted / area_m2)
                            : mesh.surfaces[sides[static_cast<size_t>(order[static_cast<size_t>(begin)])]].elements[0].center;
  for (int m = begin; m < end; ++m) {
    const MeshElement& e = mesh.surfaces[sides[static_cast<size_t>(order[static_cast<size_t>(m)])]].elements[0];
    for (int c = 0; c < e.corner_count(); ++c)
      node.radius_m = std::max(node.radius_m, (e.corners[static_cast<size_t>(c)] - node.center).norm());
  }
  return end;
}

/// The clusters: the top-most nodes of the subtree at `k` with at most kClusterMembers members.
void find_roots(ShooterClusters& out, int k) {
  const ShooterClusters::Node& node = out.nodes[static_cast<size_t>(k)];
  if (node.end - node.begin <= kClusterMembers) {
    out.roots.push_back(k);
    return;
  }
  find_roots(out, node.first_child);
  find_roots(out, node.first_child + 1);
}

}  // namespace

ShooterClusters make_shooter_clusters(const Mesh& mesh) {
  ShooterClusters out;
  out.cluster_of_side.assign(mesh.surfaces.size(), -1);
  std::vector<size_t> single;  // the sides of one element
  for (size_t s = 0; s < mesh.surfaces.size(); ++s)
    if (mesh.surfaces[s].elements.size() == 1) single.push_back(s);
  if (single.size() < tol::kLeastClusteredSides) return out;
  std::vector<BoxItem> items;
  items.reserve(single.size());
  for (const size_t s : single) {
    const Vec3& c = mesh.surfaces[s].elements[0].center;
    items.push_back({c, c, c});
  }
  std::vector<BoxNode> boxes;
  std::vector<int> order;
  build_box_hierarchy(items, 1, boxes, order);
  out.nodes.emplace_back();
  copy_node(boxes, 0, mesh, single, order, out, 0, 0);
  for (const int k : order) out.sides.push_back(single[static_cast<size_t>(k)]);
  find_roots(out, 0);
  for (size_t c = 0; c < out.roots.size(); ++c) {
    const ShooterClusters::Node& root = out.nodes[static_cast<size_t>(out.roots[c])];
    for (int m = root.begin; m < root.end; ++m) out.cluster_of_side[out.sides[static_cast<size_t>(m)]] = static_cast<int>(c);
  }
  return out;
}

ClusterShot::ClusterShot(const Scene& scene, const Mesh& mesh, const ShooterClusters& clusters, size_t cluster,
                         const OccluderBvh& bvh,
                         std::span<const std::vector<Rgb>* const> unshot)
    : mesh_(mesh), clusters_(clusters), bvh_(bvh), root_(clusters.roots[cluster]) {
  const ShooterClusters::Node& root = clusters.nodes[static_cast<size_t>(root_)];
  trees_.reserve(static_cast<size_t>(root.end - root.begin));
  for (int m = root.begin; m < root.end; ++m) {
    const size_t s = clusters.sides[static_cast<size_t>(m)];
    const MeshSurface& side = mesh.surfaces[s];
    const MeshElement& e = side.elements[0];
    const Rgb& b = (*unshot[s])[0];
    trees_.emplace_back(scene.surfaces[side.scene_surface], side, *unshot[s], 0, 0, side.nu, side.nv);
    at_.push_back(e.center);
    normal_.push_back(side.normal);
    radiosity_.push_back(b);
    intensity_.push_back(e.area_m2 * b / std::numbers::pi);
    corners_.push_back({e.corners, e.corner_count()});
    double radius_m = 0;
    for (int c = 0; c < e.corner_count(); ++c) radius_m = std::max(radius_m, (e.corners[static_cast<size_t>(c)] - e.center).norm());
    point_kernel_m2_.push_back(tol::kClusterPointKernelRadii * tol::kClusterPointKernelRadii * radius_m * radius_m);
    power_w_ += e.area_m2 * b;
  }
}

Rgb ClusterShot::far_irradiance(int begin, int end, const Vec3& p, const Vec3& n) const {
  Rgb sum = Rgb::Zero();
  for (size_t m = static_cast<size_t>(begin); m < static_cast<size_t>(end); ++m) {
    const Vec3 d = p - at_[m];  // from the member to p
    const double r2 = d.squaredNorm();
    const double cos_m = normal_[m].dot(d), cos_p = -n.dot(d);  // each times |d|
    if (!(cos_m > 0)) continue;  // p is behind the member
    if (r2 >= point_kernel_m2_[m]) {
      if (cos_p > 0) sum += (cos_m * cos_p / (r2 * r2)) * intensity_[m];
      continue;
    }
    // Near: the member's form factor, exact (its part in front of p's plane; no shadows).
    ConvexPolygon polygon;
    for (int c = 0; c < corners_[m].second; ++c) polygon.push(corners_[m].first[static_cast<size_t>(c)]);
    sum += visible_form_factor_past(p, n, polygon, normal_[m], {}) * radiosity_[m];
  }
  return sum;
}

Rgb ClusterShot::seen_irradiance(const ShooterClusters::Node& node, const Vec3& p, const Vec3& n,
                                 size_t receiver_surface) const {
  const int first = clusters_.nodes[static_cast<size_t>(root_)].begin;
  const Rgb e = far_irradiance(node.begin - first, node.end - first, p, n);
  if ((e == 0).all()) return e;
  // The node's own members lie within its radius of its centre, where crossings are passed over;
  // the cluster's other members, and every other surface, may hide it.
  return bvh_.blocks_segment(p, node.center, node.radius_m, receiver_surface, {}) ? Rgb(Rgb::Zero()) : e;
}

Gathered ClusterShot::gather(const Receiver& r, size_t receiver_side) const {
  Gathered out;
  const size_t receiver_surface = mesh_.surfaces[receiver_side].scene_surface;
  const int first = clusters_.nodes[static_cast<size_t>(root_)].begin;
  double reach_m = 0;  // the Gauss points' farthest distance from the centre (progressive.cpp)
  for (int k = 0; k < r.gauss_count; ++k) reach_m = std::max(reach_m, (r.gauss[static_cast<size_t>(k)] - r.center).norm());
  thread_local std::vector<const Occluder*> near;
  std::array<int, 64> stack;  // depth <= log2(members) + 1 for a median split
  int top = 0;
  stack[top++] = root_;
  while (top > 0) {
    const ShooterClusters::Node& node = clusters_.nodes[static_cast<size_t>(stack[--top])];
    const double distance_m = (r.center - node.center).norm();
    const double far_radii = node.first_child >= 0 ? tol::kClusterFarRadii : tol::kClusterMemberFarRadii;
    if (distance_m >= far_radii * node.radius_m) {
      // Far: the members' point kernels, past the shadow rays to the node's centre.
      const Rgb at_center = seen_irradiance(node, r.center, r.normal, receiver_surface);
      out.at_center += at_center;
      if (r.size_m <= tol::kMidpointReceiverRatio * (distance_m - node.radius_m)) {
        out.mean += at_center;
      } else {
        Rgb mean = Rgb::Zero();
        for (int k = 0; k < r.gauss_count; ++k)
          mean += seen_irradiance(node, r.gauss[static_cast<size_t>(k)], r.normal, receiver_surface);
        out.mean += mean / r.gauss_count;
      }
    } else if (node.first_child >= 0) {
      stack[top++] = node.first_child + 1;
      stack[top++] = node.first_child;
    } else {
      // Near a single member: as a patch of one element shoots, with exact shadows.
      const size_t m = static_cast<size_t>(node.begin - first);
      const MeshSurface& side = mesh_.surfaces[clusters_.sides[static_cast<size_t>(node.begin)]];
      const Block& block = trees_[m].root();
      if (side.scene_surface == receiver_surface || (block.highest_w_m2 == 0).all()) continue;
      near.clear();
      bvh_.collect(Shaft({&r.center, 1}, {block.corners.data(), static_cast<size_t>(block.corner_count)}, reach_m),
                   receiver_surface, side.scene_surface, near);
      const ReceiverShadows shadows(r, near);
      out += radrecon::gather(trees_[m], block, r, side.normal, shadows, 0);
    }
  }
  return out;
}

}  // namespace radrecon
