#include "solver/hierarchy_state.h"

#include <algorithm>
#include <limits>

#include "solver/polygon.h"

namespace radrecon::hierarchy {

namespace {

/// Pushes irradiance down to the leaves and pulls area-weighted radiosity up; returns the
/// node's new radiosity.
Rgb push_pull(Tree& t, int index, const Rgb& irradiance_above, double& change, double& largest) {
  const QuadNode& node = t.node(index);
  NodeState& n = t.at(index);
  const Rgb irradiance = irradiance_above + n.gathered;
  Rgb b;
  if (node.is_leaf()) {
    // The irradiance is the node's mean, nil over its enclosed part (no light reaches it).
    b = n.exposed * (n.unenclosed * t.emission_w_m2 + t.reflectance * irradiance);
    n.irradiance = irradiance;
    change = std::max(change, (b - n.radiosity).abs().maxCoeff());
    largest = std::max(largest, b.abs().maxCoeff());
  } else {
    const int first = node.first_child;
    b = Rgb::Zero();
    double area = 0, lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (int c = 0; c < 4; ++c) {
      const Rgb bc = push_pull(t, first + c, irradiance, change, largest);
      const double a = t.node(first + c).area_m2;
      b += a * bc;
      area += a;
      // The spread of what the children are seen at: a wholly enclosed child is never seen.
      const NodeState& child = t.at(first + c);
      if (child.unenclosed <= 0) continue;
      const double seen = child.seen_radiosity().mean();
      lo = std::min(lo, seen);
      hi = std::max(hi, seen);
    }
    b /= area;
    t.at(index).spread_w_m2 = hi >= lo ? hi - lo : 0;
  }
  t.at(index).radiosity = b;
  return b;
}

/// The plane of a tree's side, its front the half-space {dot(normal, x) >= dot(normal, corner)}.
HalfSpace front_of(const Tree& t) {
  return HalfSpace{t.normal, t.normal.dot(t.node(0).corners[0])}.with_tolerance();
}

ConvexPolygon polygon_of(const QuadNode& n) {
  ConvexPolygon p;
  for (int k = 0; k < n.vertex_count(); ++k) p.push(n.corners[static_cast<size_t>(k)]);
  return p;
}

/// Adds the unenclosed area of node k's part in the half-space `front` to `area_m2_sum`, and the
/// power that part sends to `power_w`: whole nodes as they are, a leaf across the plane by the
/// share of its area on the front side (its radiosity is uniform; its enclosed part is taken as
/// spread over it alike).
void add_front_part(const Tree& t, int k, const HalfSpace& front, double& area_m2_sum, Rgb& power_w) {
  const QuadNode& node = t.node(k);
  const ConvexPolygon p = polygon_of(node);
  std::array<double, ConvexPolygon::kCapacity> d;
  const Side side = distances(p, front, d);
  if (side == Side::outside) return;
  if (side == Side::inside || node.is_leaf()) {
    double a_m2 = node.area_m2;
    if (side == Side::across) {
      ConvexPolygon part;
      cut(p, d, 1.0, part);
      const double whole_m2 = area_m2(p);
      a_m2 = whole_m2 > 0 ? a_m2 * area_m2(part) / whole_m2 : 0;  // a node has area; no 0 / 0 if not
    }
    area_m2_sum += a_m2 * t.at(k).unenclosed;
    power_w += a_m2 * t.at(k).radiosity;
    return;
  }
  for (int c = 0; c < 4; ++c) add_front_part(t, node.first_child + c, front, area_m2_sum, power_w);
}

/// The links whose source node the receiver's plane cuts (a ground node across a wall's foot,
/// linked to the wall): the receiver sees only the source's part in front of its plane, so it
/// takes that part's mean radiosity, not the node's (which mixes in the lit or shadowed ground on
/// the wall's other side): the power it sends over the area it sends it from (its unenclosed part).
/// Each distinct (receiver side, source node) is listed once.
struct SourcesSeenInPart {
  struct Part {
    int receiver_tree, source_tree, source_node;
    auto operator<=>(const Part&) const = default;
  };
  std::vector<Part> parts;
  std::vector<int> of_link;  ///< by link: its index in `parts`, or -1 when it sees the whole source
  std::vector<Rgb> radiosity_w_m2;  ///< by part: the mean radiosity of the source's front part

  SourcesSeenInPart(const std::vector<Tree>& trees, const std::vector<Link>& links) : of_link(links.size(), -1) {
    std::vector<HalfSpace> fronts;
    for (const Tree& t : trees) fronts.push_back(front_of(t));
    std::array<double, ConvexPolygon::kCapacity> d;
    for (size_t i = 0; i < links.size(); ++i) {
      const Link& l = links[i];
      const ConvexPolygon source = polygon_of(trees[static_cast<size_t>(l.source_tree)].node(l.source_node));
      if (distances(source, fronts[static_cast<size_t>(l.receiver_tree)], d) != Side::across) continue;
      of_link[i] = static_cast<int>(parts.size());
      parts.push_back({l.receiver_tree, l.source_tree, l.source_node});
    }
    // One entry per distinct part: many receivers on one wall link to the same ground node.
    std::vector<Part> unique = parts;
    std::sort(unique.begin(), unique.end());
    unique.erase(std::unique(unique.begin(), unique.end()), unique.end());
    for (int& k : of_link)
      if (k >= 0)
        k = static_cast<int>(std::lower_bound(unique.begin(), unique.end(), parts[static_cast<size_t>(k)]) -
                             unique.begin());
    parts = std::move(unique);
    radiosity_w_m2.assign(parts.size(), Rgb::Zero());
    fronts_ = std::move(fronts);
  }

  /// Recomputes every part's radiosity from the trees' current node radiosities.
  void update(const std::vector<Tree>& trees) {
    for (size_t k = 0; k < parts.size(); ++k) {
      const Part& q = parts[k];
      const Tree& t = trees[static_cast<size_t>(q.source_tree)];
      double area_m2_sum = 0;
      Rgb power_w = Rgb::Zero();
      add_front_part(t, q.source_node, fronts_[static_cast<size_t>(q.receiver_tree)], area_m2_sum, power_w);
      radiosity_w_m2[k] = area_m2_sum > 0 ? Rgb(power_w / area_m2_sum) : t.at(q.source_node).seen_radiosity();
    }
  }

 private:
  std::vector<HalfSpace> fronts_;
};

}  // namespace

bool gather_over_links(std::vector<Tree>& trees, const std::vector<Link>& links, int max_iterations, double tolerance,
                       double& residual) {
  SourcesSeenInPart seen_in_part(trees, links);
  for (int iteration = 0; iteration < max_iterations; ++iteration) {
    for (Tree& t : trees)
      for (NodeState& n : t.state) n.gathered = Rgb::Zero();
    seen_in_part.update(trees);
    for (size_t i = 0; i < links.size(); ++i) {
      const Link& l = links[i];
      const int part = seen_in_part.of_link[i];
      const Rgb& b = part >= 0 ? seen_in_part.radiosity_w_m2[static_cast<size_t>(part)]
                               : trees[static_cast<size_t>(l.source_tree)].at(l.source_node).seen_radiosity();
      trees[static_cast<size_t>(l.receiver_tree)].at(l.receiver_node).gathered += l.f * b;
    }
    double change = 0, largest = 0;
    for (Tree& t : trees) push_pull(t, 0, Rgb::Zero(), change, largest);
    residual = largest > 0 ? change / largest : 0;
    if (change <= tolerance * largest) return true;
  }
  return false;
}

void add_surfaces(const Scene& scene, const std::vector<Tree>& trees, Solution& sol) {
  SolveStats& st = sol.stats;
  for (const Tree& t : trees) {
    const Surface& surface = scene.surfaces[t.scene_surface];
    SurfaceSolution out;
    out.name = t.name;
    out.scene_surface = surface.name;
    out.back_side = t.back_side;
    out.length_u_m = surface.length_u_m();
    out.length_v_m = surface.length_v_m();
    out.shear_m = surface.shear_m();
    out.triangle = surface.is_triangle();
    for (const int k : t.quad.leaves()) {
      const QuadNode& n = t.node(k);
      out.elements.push_back({n, n.center, n.area_m2, t.at(k).radiosity});
    }
    st.emitted_w += t.at(0).exposed * t.at(0).unenclosed * t.node(0).area_m2 * t.emission_w_m2;
    st.elements += out.elements.size();
    sol.surfaces.push_back(std::move(out));
  }
  for (const Tree& t : trees)
    for (const int k : t.quad.leaves())
      st.absorbed_w += t.at(k).exposed * t.node(k).area_m2 * (1.0 - t.reflectance) * t.at(k).irradiance;
  st.escaped_w = st.emitted_w - st.absorbed_w;  // what is not absorbed has left the scene
}

}  // namespace radrecon::hierarchy
