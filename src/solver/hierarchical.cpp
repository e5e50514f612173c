#include "solver/hierarchical.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <queue>
#include <tuple>

#include "core/check.h"
#include "core/error.h"
#include "core/tolerances.h"
#include "mesh/quadtree.h"
#include "scene/side.h"
#include "solver/form_factor.h"
#include "solver/visibility.h"

namespace radrecon {

namespace {

/// The radiometry of one quadtree node (the geometry is the Quadtree's, at the same index).
struct NodeState {
  Rgb radiosity = Rgb::Zero();
  Rgb gathered = Rgb::Zero();  ///< irradiance through this node's own links, W/m^2
  Rgb irradiance = Rgb::Zero();  ///< leaves: total irradiance including the ancestors', W/m^2
  double spread_w_m2 = 0;        ///< max - min of the children's radiosity (channel mean); 0 at leaves
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
  const QuadNode& node(int k) const { return quad.node(k); }
  NodeState& at(int k) { return state[static_cast<size_t>(k)]; }
  const NodeState& at(int k) const { return state[static_cast<size_t>(k)]; }
};

struct Link {
  int receiver_tree, receiver_node, source_tree, source_node;
  double f;         ///< area-to-area visible form factor, receiver -> source
  double f_spread;  ///< max - min of the point form factors over the receiver's samples
};

/// Midpoint samples per receiver edge for a link's area-to-area form factor, and the finer rule
/// used where the point form factor jumps across the receiver (its spread exceeds this
/// fraction of its maximum).
constexpr int kLinkQuadrature = 4;
constexpr int kLinkQuadratureFine = 16;
constexpr double kDiscontinuousSpread = 0.5;

/// Thrown when a hierarchy would exceed HierarchicalOptions::max_links.
struct TooManyLinks {};


class Hierarchy {
 public:
  Hierarchy(const Scene& scene, const HierarchicalOptions& options) : scene_(scene), options_(options) {
    min_size_m_ = min_element_size_m(scene, options);
    occluders_ = make_occluders(scene);
    for (size_t k = 0; k < scene.surfaces.size(); ++k) {
      add_tree(k, false);
      if (scene.surfaces[k].two_sided) add_tree(k, true);
    }
    if (options.leaf_cap) {
      bool found = false;
      for (Tree& t : trees_)
        if (t.name == options.leaf_cap->first) {
          t.leaf_cap = options.leaf_cap->second;
          found = true;
        }
      RR_CHECK(found, "leaf cap names no surface side");
    }
    pair_occluders_.resize(trees_.size() * trees_.size());
    for (size_t r = 0; r < trees_.size(); ++r)
      for (size_t s = 0; s < trees_.size(); ++s) {
        const Tree& R = trees_[r];
        const Tree& S = trees_[s];
        if (R.scene_surface == S.scene_surface || !quads_face(R.node(0).corners, R.normal, S.node(0).corners, S.normal))
          continue;
        pair_occluders_[r * trees_.size() + s] =
            occluders_between(occluders_, R.node(0).corners, S.node(0).corners, R.scene_surface, S.scene_surface);
        links_.push_back(make_link(static_cast<int>(r), 0, static_cast<int>(s), 0));
      }
  }

  void solve() {
    const auto start = std::chrono::steady_clock::now();
    int passes = 0;
    gather_until_converged();
    while (refine_pass()) {
      ++passes;
      gather_until_converged();
      if (!options_.progress_label.empty())
        std::fprintf(stderr, "%s: refinement pass %d, %zu links, %d leaves\n", options_.progress_label.c_str(),
                     passes, links_.size(), total_leaves());
    }
    hierarchy_links_ = links_.size();
    if (options_.leaf_gather) {
      push_links_to_leaves();
      gather_until_converged();
    }
    seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }

  Solution solution(const std::string& mesh_spec) const {
    Solution sol;
    sol.scene = scene_.name;
    sol.mesh = mesh_spec;
    SolveStats& st = sol.stats;
    st.method = "hierarchical";
    st.links = hierarchy_links_;
    st.epsilon_w = options_.epsilon_w;
    st.residual = residual_;
    st.converged = converged_;
    st.seconds = seconds_;
    for (const Tree& t : trees_) {
      const Surface& surface = scene_.surfaces[t.scene_surface];
      SurfaceSolution out;
      out.name = t.name;
      out.scene_surface = surface.name;
      out.back_side = t.back_side;
      out.length_u_m = surface.length_u_m();
      out.length_v_m = surface.length_v_m();
      out.shear_m = surface.shear_m();
      out.triangle = surface.is_triangle();
      collect_leaves(t, out);
      st.emitted_w += t.node(0).area_m2 * t.emission_w_m2;
      st.elements += out.elements.size();
      sol.surfaces.push_back(std::move(out));
    }
    for (const Tree& t : trees_) add_absorbed(t, st.absorbed_w);
    st.escaped_w = st.emitted_w - st.absorbed_w;  // what is not absorbed has left the scene
    return sol;
  }

 private:
  void add_tree(size_t k, bool back) { trees_.emplace_back(scene_.surfaces[k], k, back); }

  const std::vector<const Occluder*>& occluders(int r, int s) const {
    return pair_occluders_[static_cast<size_t>(r) * trees_.size() + static_cast<size_t>(s)];
  }

  /// A link's form factor is the area-to-area form factor F(receiver -> source): the mean over
  /// kLinkQuadrature^2 midpoint samples of the receiver of the exact visible point-to-quad form
  /// factor. Its spread over the samples measures how much the transport varies across the
  /// receiver, shadow boundaries included.
  Link make_link(int rt, int rn, int st, int sn) const {
    Link link = sample_link(rt, rn, st, sn, kLinkQuadrature);
    // A discontinuity (a shadow boundary, or the foot of a wall standing on the receiver) makes
    // the coarse rule's error of order 1 / kLinkQuadrature of the jump: sample finely there.
    if (link.f_spread > kDiscontinuousSpread * (link.f + link.f_spread))
      link = sample_link(rt, rn, st, sn, kLinkQuadratureFine);
    return link;
  }

  Link sample_link(int rt, int rn, int st, int sn, int n) const {
    const Tree& R = trees_[static_cast<size_t>(rt)];
    const Tree& S = trees_[static_cast<size_t>(st)];
    const QuadNode& r = R.node(rn);
    const QuadNode& s = S.node(sn);
    const Surface& surface = scene_.surfaces[R.scene_surface];
    ConvexPolygon source;
    for (int k = 0; k < s.vertex_count(); ++k) source.push(s.corners[k]);
    const auto& occ = occluders(rt, st);
    Link link{rt, rn, st, sn, 0.0, 0.0};
    double lo = std::numeric_limits<double>::infinity(), hi = 0;
    r.for_each_midpoint(n, [&](const Vec2& uv) {
      const Vec3 p = surface.point(uv.x(), uv.y());
      const double f = visible_form_factor(p, R.normal, source, S.normal, occ);
      link.f += f;
      lo = std::min(lo, f);
      hi = std::max(hi, f);
    });
    link.f /= n * n;
    link.f_spread = hi - lo;
    return link;
  }

  /// The refinement oracle: the power error (W, channel mean) of the link, from the variation
  /// of the transport across the receiver, rho_r * B_s * spread(F) * A_r, and from the
  /// variation of the source's radiosity, rho_r * spread(B_s) * F * A_r.
  struct Estimate {
    double receiver_w, source_w;
    double total() const { return std::max(receiver_w, source_w); }
  };
  Estimate error_estimate(const Link& l) const {
    const Tree& R = trees_[static_cast<size_t>(l.receiver_tree)];
    const QuadNode& r = R.node(l.receiver_node);
    const NodeState& s = trees_[static_cast<size_t>(l.source_tree)].at(l.source_node);
    const double scale = R.reflectance.mean() * r.area_m2;
    return {scale * s.radiosity.mean() * l.f_spread, scale * s.spread_w_m2 * l.f};
  }

  bool splittable(int tree, int node) const {
    const Tree& t = trees_[static_cast<size_t>(tree)];
    const QuadNode& n = t.node(node);
    if (!n.is_leaf()) return true;
    if (n.size_m < 2 * min_size_m_) return false;
    return t.leaf_cap == 0 || t.quad.leaf_count() + 3 <= t.leaf_cap;
  }

  /// Splits a leaf; its children start with its radiosity until the next solve.
  void split(int tree, int node) {
    Tree& t = trees_[static_cast<size_t>(tree)];
    if (!t.node(node).is_leaf()) return;
    t.quad.split(node);
    const Rgb radiosity = t.at(node).radiosity;
    for (int c = 0; c < 4; ++c) t.state.push_back({radiosity});
  }

  /// One refinement pass, best first: the link with the largest error estimate is refined one
  /// level (its larger-error end split, the children linked in its place), and its new links go
  /// back into the queue, until no link exceeds epsilon or can be refined. Without a leaf cap
  /// the result does not depend on the order; with one, the cap keeps the splits that matter
  /// most. Returns whether anything was refined.
  bool refine_pass() {
    struct Entry {
      double error;
      size_t sequence;  // ties: first come first served, for determinism
      Link link;
      bool operator<(const Entry& o) const { return error < o.error || (error == o.error && sequence > o.sequence); }
    };
    std::priority_queue<Entry> queue;
    size_t sequence = 0;
    for (const Link& l : links_) queue.push({error_estimate(l).total(), sequence++, l});
    std::vector<Link> kept;
    kept.reserve(links_.size());
    bool changed = false;
    while (!queue.empty()) {
      const Entry top = queue.top();
      queue.pop();
      const Link& l = top.link;
      const Estimate e = error_estimate(l);
      const bool can_r = splittable(l.receiver_tree, l.receiver_node);
      // A black source radiates its uniform emission only: splitting it changes nothing.
      const bool black_source = (trees_[static_cast<size_t>(l.source_tree)].reflectance == 0).all();
      const bool can_s = !black_source && splittable(l.source_tree, l.source_node);
      if (e.total() <= options_.epsilon_w || (!can_r && !can_s)) {
        kept.push_back(l);
        continue;
      }
      changed = true;
      const bool split_receiver = can_r && (!can_s || e.receiver_w >= e.source_w);
      const int tree = split_receiver ? l.receiver_tree : l.source_tree;
      const int node = split_receiver ? l.receiver_node : l.source_node;
      split(tree, node);
      const int first = trees_[static_cast<size_t>(tree)].node(node).first_child;
      for (int c = 0; c < 4; ++c) {
        const Link child = split_receiver ? make_link(l.receiver_tree, first + c, l.source_tree, l.source_node)
                                          : make_link(l.receiver_tree, l.receiver_node, l.source_tree, first + c);
        queue.push({error_estimate(child).total(), sequence++, child});
      }
      if (kept.size() + queue.size() > options_.max_links) throw TooManyLinks{};
    }
    // Keep the links in a canonical order (by receiver, then source) for a deterministic gather.
    std::sort(kept.begin(), kept.end(), [](const Link& a, const Link& b) {
      return std::tie(a.receiver_tree, a.receiver_node, a.source_tree, a.source_node) <
             std::tie(b.receiver_tree, b.receiver_node, b.source_tree, b.source_node);
    });
    links_.swap(kept);
    return changed;
  }

  /// Final gather: every link whose receiver has children is replaced by links from each of the
  /// receiver's leaves to the same source, each with its own area-to-area form factor. Sources
  /// keep the hierarchy's resolution; receivers get the leaves' resolution, so no leaf inherits
  /// an ancestor's average irradiance (e.g. light from the front of a wall that the leaf is
  /// behind).
  void push_links_to_leaves() {
    std::vector<Link> leaf_links;
    leaf_links.reserve(links_.size());
    for (const Link& l : links_) {
      const Tree& R = trees_[static_cast<size_t>(l.receiver_tree)];
      if (R.node(l.receiver_node).is_leaf()) {
        leaf_links.push_back(l);
        continue;
      }
      for (const int k : R.quad.leaves(l.receiver_node)) {
        leaf_links.push_back(make_link(l.receiver_tree, k, l.source_tree, l.source_node));
        if (leaf_links.size() > options_.max_links) throw TooManyLinks{};
      }
    }
    std::sort(leaf_links.begin(), leaf_links.end(), [](const Link& a, const Link& b) {
      return std::tie(a.receiver_tree, a.receiver_node, a.source_tree, a.source_node) <
             std::tie(b.receiver_tree, b.receiver_node, b.source_tree, b.source_node);
    });
    links_.swap(leaf_links);
  }

  /// Jacobi gathering over all links, then push-pull, until the radiosity settles.
  void gather_until_converged() {
    converged_ = true;
    for (int iteration = 0; iteration < options_.max_gather_iterations; ++iteration) {
      for (Tree& t : trees_)
        for (NodeState& n : t.state) n.gathered = Rgb::Zero();
      for (const Link& l : links_) {
        const NodeState& s = trees_[static_cast<size_t>(l.source_tree)].at(l.source_node);
        trees_[static_cast<size_t>(l.receiver_tree)].at(l.receiver_node).gathered += l.f * s.radiosity;
      }
      double change = 0, largest = 0;
      for (Tree& t : trees_) push_pull(t, 0, Rgb::Zero(), change, largest);
      residual_ = largest > 0 ? change / largest : 0;
      if (change <= options_.tolerance * largest) return;
    }
    converged_ = false;  // the iteration limit, not the tolerance, stopped it (the last gather's
                         // state is what the solution reports)
  }

  /// Pushes irradiance down to the leaves and pulls area-weighted radiosity up; returns the
  /// node's new radiosity.
  Rgb push_pull(Tree& t, int index, const Rgb& irradiance_above, double& change, double& largest) {
    const QuadNode& node = t.node(index);
    NodeState& n = t.at(index);
    const Rgb irradiance = irradiance_above + n.gathered;
    Rgb b;
    if (node.is_leaf()) {
      b = t.emission_w_m2 + t.reflectance * irradiance;
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

  void collect_leaves(const Tree& t, SurfaceSolution& out) const {
    for (const int k : t.quad.leaves()) {
      const QuadNode& n = t.node(k);
      out.elements.push_back({n, n.center, n.area_m2, t.at(k).radiosity});
    }
  }

  void add_absorbed(const Tree& t, Rgb& absorbed) const {
    for (const int k : t.quad.leaves()) absorbed += t.node(k).area_m2 * (1.0 - t.reflectance) * t.at(k).irradiance;
  }

  int total_leaves() const {
    int n = 0;
    for (const Tree& t : trees_) n += t.quad.leaf_count();
    return n;
  }

  const Scene& scene_;
  HierarchicalOptions options_;
  double min_size_m_ = 0;
  std::vector<Occluder> occluders_;
  std::vector<Tree> trees_;
  std::vector<std::vector<const Occluder*>> pair_occluders_;
  std::vector<Link> links_;
  size_t hierarchy_links_ = 0;
  double residual_ = 0;
  bool converged_ = true;
  double seconds_ = 0;
};

}  // namespace

std::optional<Solution> try_solve_hierarchical(const Scene& scene, const HierarchicalOptions& options,
                                               const std::string& mesh_spec) {
  RR_CHECK(options.epsilon_w > 0 && options.tolerance > 0, "hierarchical options out of range");
  Hierarchy h(scene, options);
  try {
    h.solve();
  } catch (const TooManyLinks&) {
    return std::nullopt;
  }
  return h.solution(mesh_spec);
}

Solution solve_hierarchical(const Scene& scene, const HierarchicalOptions& options, const std::string& mesh_spec) {
  std::optional<Solution> sol = try_solve_hierarchical(scene, options, mesh_spec);
  if (!sol) {
    char eps[32];
    std::snprintf(eps, sizeof eps, "%g", options.epsilon_w);
    throw UserError(mesh_spec, std::string("epsilon ") + eps + " W would need more than " +
                                   std::to_string(options.max_links) + " links; use a larger epsilon or fewer leaves");
  }
  return std::move(*sol);
}

/// The minimum element size of `options`, or its default: a fraction of the longest edge.
double min_element_size_m(const Scene& scene, const HierarchicalOptions& options) {
  if (options.min_size_m > 0) return options.min_size_m;
  double longest = 0;
  for (const Surface& s : scene.surfaces) longest = std::max({longest, s.length_u_m(), s.length_v_m()});
  return longest * tol::kMinElementFraction;
}

}  // namespace radrecon
