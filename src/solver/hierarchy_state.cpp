#include "solver/hierarchy_state.h"

#include <algorithm>
#include <limits>

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
    b = n.exposed * (t.emission_w_m2 + t.reflectance * irradiance);
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
      lo = std::min(lo, bc.mean());
      hi = std::max(hi, bc.mean());
    }
    b /= area;
    t.at(index).spread_w_m2 = hi - lo;
  }
  t.at(index).radiosity = b;
  return b;
}

}  // namespace

bool gather_over_links(std::vector<Tree>& trees, const std::vector<Link>& links, int max_iterations, double tolerance,
                       double& residual) {
  for (int iteration = 0; iteration < max_iterations; ++iteration) {
    for (Tree& t : trees)
      for (NodeState& n : t.state) n.gathered = Rgb::Zero();
    for (const Link& l : links) {
      const NodeState& s = trees[static_cast<size_t>(l.source_tree)].at(l.source_node);
      trees[static_cast<size_t>(l.receiver_tree)].at(l.receiver_node).gathered += l.f * s.radiosity;
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
    st.emitted_w += t.at(0).exposed * t.node(0).area_m2 * t.emission_w_m2;
    st.elements += out.elements.size();
    sol.surfaces.push_back(std::move(out));
  }
  for (const Tree& t : trees)
    for (const int k : t.quad.leaves())
      st.absorbed_w += t.at(k).exposed * t.node(k).area_m2 * (1.0 - t.reflectance) * t.at(k).irradiance;
  st.escaped_w = st.emitted_w - st.absorbed_w;  // what is not absorbed has left the scene
}

}  // namespace radrecon::hierarchy
