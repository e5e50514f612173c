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
#include "core/limits.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "core/tolerances.h"
#include "mesh/grid_mesh.h"
#include "mesh/quadtree.h"
#include "scene/side.h"
#include "solver/bvh.h"
#include "solver/form_factor.h"
#include "solver/hierarchy_state.h"
#include "solver/visibility.h"

namespace radrecon {

namespace {

using hierarchy::Link;
using hierarchy::NodeState;
using hierarchy::Tree;
using hierarchy::add_surfaces;
using hierarchy::gather_over_links;

/// Thrown when a hierarchy would exceed HierarchicalOptions::max_links.
struct TooManyLinks {};

/// The links' canonical order, by receiver then source: the gather's, for determinism.
bool canonical(const Link& a, const Link& b) {
  return std::tie(a.receiver_tree, a.receiver_node, a.source_tree, a.source_node) <
         std::tie(b.receiver_tree, b.receiver_node, b.source_tree, b.source_node);
}

class Hierarchy {
 public:
  Hierarchy(const Scene& scene, const HierarchicalOptions& options, LinkFormFactorCache* cache)
      : scene_(scene), covers_(covers_by_surface(scene)), contacts_(scene), options_(options),
        cache_(cache != nullptr ? cache : &own_cache_) {
    min_size_m_ = min_element_size_m(scene, options);
    occluders_ = make_occluders(scene);
    bvh_ = OccluderBvh(occluders_);
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
    std::vector<LinkRequest> roots;
    for (size_t r = 0; r < trees_.size(); ++r)
      for (size_t s = 0; s < trees_.size(); ++s) {
        const Tree& R = trees_[r];
        const Tree& S = trees_[s];
        if (R.scene_surface == S.scene_surface || !quads_face(R.node(0).corners, R.normal, S.node(0).corners, S.normal))
          continue;
        pair_occluders_[r * trees_.size() + s] =
            bvh_.between(R.node(0).corners, S.node(0).corners, R.scene_surface, S.scene_surface);
        roots.push_back({static_cast<int>(r), &R.node(0), static_cast<int>(s), &S.node(0)});
      }
    measure_into_cache(roots);
    for (const LinkRequest& q : roots) links_.push_back(make_link(q.receiver_tree, 0, q.source_tree, 0));
  }

  void solve() {
    const auto start = std::chrono::steady_clock::now();
    int passes = 0;
    Progress progress(options_.progress_label, options_.progress_label.empty());
    progress_ = &progress;
    gather_until_converged();
    while (true) {
      progress.note("refinement pass " + std::to_string(passes + 1) + " of the " + std::to_string(links_.size()) +
                    " links, " + std::to_string(total_leaves()) + " leaves");
      if (!refine_pass()) break;
      ++passes;
      progress.note("gathering over " + std::to_string(links_.size()) + " links after refinement pass " +
                    std::to_string(passes) + ", " + std::to_string(total_leaves()) + " leaves");
      gather_until_converged();
    }
    hierarchy_links_ = links_.size();
    if (options_.leaf_gather) {
      progress.note("the final gather: every link pushed to its receiver's leaves");
      push_links_to_leaves();
      progress.note("the final gather over " + std::to_string(links_.size()) + " links");
      gather_until_converged();
    }
    progress.done();
    progress_ = nullptr;
    seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!options_.progress_label.empty())
      std::fprintf(stderr, "%s: %d leaves on %zu surface sides, %zu links, %d refinement passes, %.2f s%s\n",
                   options_.progress_label.c_str(), total_leaves(), trees_.size(), hierarchy_links_, passes, seconds_,
                   converged_ ? "" : " (gathering stopped before converging)");
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
    add_surfaces(scene_, trees_, sol);
    return sol;
  }

 private:
  void add_tree(size_t k, bool back) {
    Tree& t = trees_.emplace_back(scene_.surfaces[k], k, back);
    t.covers = covers_[k];
    t.enclosed = EnclosedRegions(contacts_.at(SideRef{k, back}), scene_.surfaces[k].frame());
    t.at(0).exposed = t.exposed_fraction_of(0);
    t.at(0).unenclosed = t.unenclosed_fraction_of(0);
  }

  const std::vector<const Occluder*>& occluders(int r, int s) const {
    return pair_occluders_[static_cast<size_t>(r) * trees_.size() + static_cast<size_t>(s)];
  }

  /// A link's end: node `node` of tree `tree`.
  LinkEnd end(int tree, const QuadNode& node) const {
    const Tree& t = trees_[static_cast<size_t>(tree)];
    return {&scene_.surfaces[t.scene_surface], t.scene_surface, t.normal, node};
  }

  /// A link with its form factor (link_form_factor.h), from the cache when known.
  Link make_link(int rt, int rn, int st, int sn) const {
    const QuadNode& r = trees_[static_cast<size_t>(rt)].node(rn);
    const QuadNode& s = trees_[static_cast<size_t>(st)].node(sn);
    const LinkFormFactorCache::End cr{rt, r}, cs{st, s};
    const LinkFormFactorCache::Value* known = cache_->find(cr, cs);
    if (known == nullptr)
      known = cache_->insert(cr, cs, measure_link(end(rt, r), end(st, s), bvh_, !occluders(rt, st).empty()));
    return {rt, rn, st, sn, known->f, known->f_spread};
  }

  /// Measures the requests not in the cache (measure_into_cache(), link_form_factor.h).
  std::vector<const LinkFormFactor*> measure_into_cache(const std::vector<LinkRequest>& requests) const {
    return radrecon::measure_into_cache(*cache_, requests, progress_, [&](const LinkRequest& q) {
      return measure_link(end(q.receiver_tree, *q.receiver), end(q.source_tree, *q.source), bvh_,
                          !occluders(q.receiver_tree, q.source_tree).empty());
    });
  }

  /// The refinement oracle: the power error (W, channel mean) of the link, from the variation
  /// of the transport across the receiver, rho_r * B_s * spread(F) * A_r, and from the
  /// variation of the source's radiosity, rho_r * spread(B_s) * F * A_r.
  struct Estimate {
    double receiver_w, source_w;
    double total() const { return std::max(receiver_w, source_w); }
  };
  Estimate estimate(int receiver_tree, const QuadNode& receiver, double source_radiosity_w_m2, double source_spread_w_m2,
                    double f, double f_spread) const {
    const double scale = trees_[static_cast<size_t>(receiver_tree)].reflectance.mean() * receiver.area_m2;
    return {scale * source_radiosity_w_m2 * f_spread, scale * source_spread_w_m2 * f};
  }
  Estimate error_estimate(const Link& l) const {
    const NodeState& s = trees_[static_cast<size_t>(l.source_tree)].at(l.source_node);
    return estimate(l.receiver_tree, trees_[static_cast<size_t>(l.receiver_tree)].node(l.receiver_node),
                    s.seen_radiosity().mean(), s.spread_w_m2, l.f, l.f_spread);
  }

  bool splittable(int tree, const QuadNode& n) const {
    const Tree& t = trees_[static_cast<size_t>(tree)];
    if (!n.is_leaf()) return true;
    if (n.size_m < 2 * min_size_m_) return false;
    return t.leaf_cap == 0 || t.quad.leaf_count() + 3 <= t.leaf_cap;
  }

  /// What the refinement does with a link of estimate `e`: keep it, or split its receiver or its
  /// source (the end responsible for the larger error that can be split).
  enum class Refine { keep, receiver, source };
  Refine decide(const Estimate& e, int receiver_tree, const QuadNode& receiver, int source_tree,
                const QuadNode& source) const {
    const bool can_r = splittable(receiver_tree, receiver);
    // A black source radiates its uniform emission only: splitting it changes nothing.
    const bool black_source = (trees_[static_cast<size_t>(source_tree)].reflectance == 0).all();
    const bool can_s = !black_source && splittable(source_tree, source);
    if (e.total() <= options_.epsilon_w || (!can_r && !can_s)) return Refine::keep;
    return can_r && (!can_s || e.receiver_w >= e.source_w) ? Refine::receiver : Refine::source;
  }

  /// Splits a leaf; its children are seen at its radiosity until the next solve (their own is
  /// nil over their enclosed part).
  void split(int tree, int node) {
    Tree& t = trees_[static_cast<size_t>(tree)];
    if (!t.node(node).is_leaf()) return;
    t.quad.split(node);
    const Rgb radiosity = t.at(node).seen_radiosity();
    for (int c = 0; c < 4; ++c) {
      const int k = static_cast<int>(t.state.size());
      NodeState child{radiosity};
      child.exposed = t.exposed_fraction_of(k);
      child.unenclosed = t.unenclosed_fraction_of(k);
      child.radiosity *= child.unenclosed;
      t.state.push_back(child);
    }
  }

  /// Warms the cache with the links the next refinement pass will make, measured in parallel
  /// wave by wave: the children of every link that decide() refines, then those of the children
  /// it refines, and so on, with the sources' radiosities as split() leaves them. What the pass
  /// then does is unchanged: only a leaf cap, which the waves do not count down, makes it ask
  /// for a link not prefetched (measured then) or leave one unused.
  void prefetch_pass() {
    struct End {
      int tree, index;  ///< index -1: a node the pass would create
      QuadNode node;
      double radiosity_w_m2, spread_w_m2;  ///< the node's state as the pass sees it (channel mean)
    };
    struct Pending {
      End r, s;
      LinkFormFactor f;
    };
    const auto stored = [&](int tree, int index) {
      const Tree& t = trees_[static_cast<size_t>(tree)];
      return End{tree, index, t.node(index), t.at(index).seen_radiosity().mean(), t.at(index).spread_w_m2};
    };
    // The four children of an end: stored ones for a node split already, else the quarters,
    // which start with the parent's radiosity and no spread.
    const auto children = [&](const End& e) {
      std::array<End, 4> out;
      const std::array<ParamCell, 4> quarters = e.node.quarters();
      for (int c = 0; c < 4; ++c)
        out[static_cast<size_t>(c)] =
            e.index >= 0 && !e.node.is_leaf()
                ? stored(e.tree, e.node.first_child + c)
                : End{e.tree, -1, trees_[static_cast<size_t>(e.tree)].quad.node_for(quarters[static_cast<size_t>(c)]),
                      e.radiosity_w_m2, 0.0};
      return out;
    };
    std::vector<Pending> wave;
    for (const Link& l : links_)  // a link within epsilon is kept (decide()): nothing to prefetch
      if (error_estimate(l).total() > options_.epsilon_w)
        wave.push_back({stored(l.receiver_tree, l.receiver_node), stored(l.source_tree, l.source_node), {l.f, l.f_spread}});
    size_t made = 0;
    while (!wave.empty() && made <= options_.max_links) {
      std::vector<Pending> next;
      for (const Pending& p : wave) {
        const Estimate e = estimate(p.r.tree, p.r.node, p.s.radiosity_w_m2, p.s.spread_w_m2, p.f.f, p.f.f_spread);
        const Refine refine = decide(e, p.r.tree, p.r.node, p.s.tree, p.s.node);
        if (refine == Refine::keep) continue;
        for (const End& c : children(refine == Refine::receiver ? p.r : p.s))
          next.push_back(refine == Refine::receiver ? Pending{c, p.s, {}} : Pending{p.r, c, {}});
      }
      std::vector<LinkRequest> requests;
      requests.reserve(next.size());
      for (const Pending& p : next) requests.push_back({p.r.tree, &p.r.node, p.s.tree, &p.s.node});
      const std::vector<const LinkFormFactor*> measured = measure_into_cache(requests);
      for (size_t k = 0; k < next.size(); ++k) next[k].f = *measured[k];
      made += next.size();
      wave.swap(next);
    }
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
    prefetch_pass();
    // A link within epsilon is kept whatever the order: its estimate depends on its own form
    // factor and its source's state, which a pass does not change (split() gives new nodes only).
    // Only the others need the queue's order.
    std::priority_queue<Entry> queue;
    size_t sequence = 0;
    std::vector<Link> kept;
    kept.reserve(links_.size());
    const auto enqueue = [&](const Link& l) {
      const double error = error_estimate(l).total();
      if (error <= options_.epsilon_w) kept.push_back(l);
      else queue.push({error, sequence++, l});
    };
    for (const Link& l : links_) enqueue(l);
    const size_t in_order = kept.size();  // a subsequence of links_: in canonical order already
    bool changed = false;
    while (!queue.empty()) {
      const Entry top = queue.top();
      queue.pop();
      const Link& l = top.link;
      const Refine refine = decide(error_estimate(l), l.receiver_tree, trees_[static_cast<size_t>(l.receiver_tree)].node(l.receiver_node),
                                   l.source_tree, trees_[static_cast<size_t>(l.source_tree)].node(l.source_node));
      if (refine == Refine::keep) {
        kept.push_back(l);
        continue;
      }
      changed = true;
      const bool split_receiver = refine == Refine::receiver;
      const int tree = split_receiver ? l.receiver_tree : l.source_tree;
      const int node = split_receiver ? l.receiver_node : l.source_node;
      split(tree, node);
      const int first = trees_[static_cast<size_t>(tree)].node(node).first_child;
      for (int c = 0; c < 4; ++c) {
        const Link child = split_receiver ? make_link(l.receiver_tree, first + c, l.source_tree, l.source_node)
                                          : make_link(l.receiver_tree, l.receiver_node, l.source_tree, first + c);
        enqueue(child);
      }
      if (kept.size() + queue.size() > options_.max_links) throw TooManyLinks{};
    }
    // Keep the links in a canonical order (by receiver, then source) for a deterministic gather:
    // those kept at once are in it, the rest are sorted and merged in (no two links join the
    // same pair of nodes, so there are no ties to order).
    std::sort(kept.begin() + static_cast<std::ptrdiff_t>(in_order), kept.end(), canonical);
    std::inplace_merge(kept.begin(), kept.begin() + static_cast<std::ptrdiff_t>(in_order), kept.end(), canonical);
    links_.swap(kept);
    return changed;
  }

  /// Final gather: every link whose receiver has children is replaced by links from each of the
  /// receiver's leaves to the same source, each with its own area-to-area form factor. Sources
  /// keep the hierarchy's resolution; receivers get the leaves' resolution, so no leaf inherits
  /// an ancestor's average irradiance (e.g. light from the front of a wall that the leaf is
  /// behind).
  void push_links_to_leaves() {
    std::vector<LinkRequest> requests;
    size_t count = 0;
    for (const Link& l : links_) {
      const Tree& R = trees_[static_cast<size_t>(l.receiver_tree)];
      if (R.node(l.receiver_node).is_leaf()) {
        ++count;
        continue;
      }
      for (const int k : R.quad.leaves(l.receiver_node))
        requests.push_back({l.receiver_tree, &R.node(k), l.source_tree, &trees_[static_cast<size_t>(l.source_tree)].node(l.source_node)});
      if (count + requests.size() > options_.max_links) throw TooManyLinks{};
    }
    const std::vector<const LinkFormFactor*> measured = measure_into_cache(requests);
    std::vector<Link> leaf_links;
    leaf_links.reserve(count + requests.size());
    size_t next = 0;  // the requests in the order they were made
    for (const Link& l : links_) {
      const Tree& R = trees_[static_cast<size_t>(l.receiver_tree)];
      if (R.node(l.receiver_node).is_leaf()) {
        leaf_links.push_back(l);
        continue;
      }
      for (const int k : R.quad.leaves(l.receiver_node)) {
        const LinkFormFactor& f = *measured[next++];
        leaf_links.push_back({l.receiver_tree, k, l.source_tree, l.source_node, f.f, f.f_spread});
      }
    }
    std::sort(leaf_links.begin(), leaf_links.end(), canonical);
    links_.swap(leaf_links);
  }

  void gather_until_converged() {
    converged_ = gather_over_links(trees_, links_, options_.max_gather_iterations, options_.tolerance, residual_);
  }

  int total_leaves() const {
    int n = 0;
    for (const Tree& t : trees_) n += t.quad.leaf_count();
    return n;
  }

  const Scene& scene_;
  std::vector<std::vector<ConvexPolygon>> covers_;  ///< by scene surface (solver/covered.h)
  ContactFinder contacts_;  ///< for each side's enclosed regions (solver/enclosed.h)
  HierarchicalOptions options_;
  LinkFormFactorCache own_cache_;
  LinkFormFactorCache* cache_;  ///< the caller's, or own_cache_
  double min_size_m_ = 0;
  std::vector<Occluder> occluders_;
  OccluderBvh bvh_;  ///< over occluders_
  std::vector<Tree> trees_;
  std::vector<std::vector<const Occluder*>> pair_occluders_;
  std::vector<Link> links_;
  Progress* progress_ = nullptr;  ///< solve()'s, while it runs
  size_t hierarchy_links_ = 0;
  double residual_ = 0;
  bool converged_ = true;
  double seconds_ = 0;
};

}  // namespace

std::optional<Solution> try_solve_hierarchical(const Scene& scene, const HierarchicalOptions& options,
                                               const std::string& mesh_spec, LinkFormFactorCache* cache) {
  RR_CHECK(options.epsilon_w > 0 && options.tolerance > 0, "hierarchical options out of range");
  Hierarchy h(scene, options, cache);
  try {
    h.solve();
  } catch (const TooManyLinks&) {
    return std::nullopt;
  }
  return h.solution(mesh_spec);
}

Solution solve_hierarchical(const Scene& scene, const HierarchicalOptions& options, const std::string& mesh_spec,
                            LinkFormFactorCache* cache, const std::string& where) {
  std::optional<Solution> sol = try_solve_hierarchical(scene, options, mesh_spec, cache);
  if (!sol) {
    char eps[32];
    std::snprintf(eps, sizeof eps, "%g", options.epsilon_w);
    throw UserError(where.empty() ? mesh_spec : where, std::string("epsilon ") + eps + " W would need more than " +
                                   std::to_string(options.max_links) + " links; use a larger epsilon, or " +
                                   limit_spec(Limit::links).option + " raises the limit (nothing was written)");
  }
  return std::move(*sol);
}

}  // namespace radrecon
