#pragma once
// Hierarchical radiosity (Hanrahan, Salzman and Aupperle 1991) on one quadtree per surface side.
//
// Links join a receiver node and a source node with the area-to-area form factor: the mean over
// 4 x 4 points of the receiver (16 x 16 where the point value jumps) of the exact visible
// point-to-quad form factor (visibility.h, shared with the progressive solver), so leaves hold
// area averages. A link is refined while its error estimate, in watts,
//     max( rho_r * B_s * (F_max - F_min) * A_r ,  rho_r * (B_max - B_min)_s * F * A_r ),
// (the spread of the form factor over the receiver's samples, shadows included, and the spread
// of the source's children's radiosity) exceeds epsilon: the end responsible for the larger term
// is split into four, if it is at least twice the minimum element size (a black source, whose
// radiosity is its uniform emission, never), and its children are linked instead. Passes of
// best-first refinement alternate with solves (gathering over the links, push-pull) until no
// link is refined; then each leaf gets its own links to its ancestors' sources (final gather).
// The parts of a side that surfaces standing on it enclose (solver/enclosed.h) neither receive
// nor send light: a node across one is seen at the radiosity of its part outside them.

#include <optional>
#include <string>

#include "scene/scene.h"
#include "solver/link_form_factor.h"
#include "solver/solution.h"

namespace radrecon {

struct HierarchicalOptions {
  /// Refine links that carry more than this power, W (> 0).
  double epsilon_w = 1e-3;
  /// Leaves are never smaller than this (metres): a node is split only if its longer edge is at
  /// least twice it. 0: tol::kMinElementFraction of the scene's longest edge.
  double min_size_m = 0;
  /// Gathering stops when no radiosity changes by more than this fraction of the largest.
  double tolerance = 1e-6;
  /// ... or after this many Jacobi iterations (each removes a factor of about the largest
  /// reflectance; 1e-6 needs a few dozen). Reaching it is reported as stats.converged = false.
  int max_gather_iterations = 10000;
  /// If set: the surface side with this name (e.g. "ground") is split at most so often that
  /// it has at most this many leaves; the splits with the largest error estimates go first.
  std::optional<std::pair<std::string, int>> leaf_cap;
  /// After refinement, give every leaf its own links to the sources of its ancestors' links
  /// (a final gather at the leaves' resolution; the sources keep theirs).
  bool leaf_gather = true;
  /// Refinement that needs more links than this is given up (try_solve_hierarchical() returns
  /// nullopt, solve_hierarchical() refuses it): a guard against an epsilon so small that the
  /// links (which grow as the square of the elements) exhaust memory.
  size_t max_links = 4'000'000;  ///< the solve calls set it to Limit::links (core/limits.h)
  /// Name printed in progress messages on stderr; empty: quiet.
  std::string progress_label;
};

/// Solves the scene by hierarchical radiosity; the elements of the solution are the leaves.
/// nullopt when the refinement would need more than options.max_links links. `cache`, if given,
/// must have been used only with this scene.
std::optional<Solution> try_solve_hierarchical(const Scene& scene, const HierarchicalOptions& options,
                                               const std::string& mesh_spec, LinkFormFactorCache* cache = nullptr);

/// try_solve_hierarchical(), with too many links refused (UserError naming `where`, e.g.
/// "--mesh quadtree-eps:1e-9"; empty: `mesh_spec`).
Solution solve_hierarchical(const Scene& scene, const HierarchicalOptions& options, const std::string& mesh_spec,
                            LinkFormFactorCache* cache = nullptr, const std::string& where = "");

/// The smallest element of `options` (metres): its min_size_m, or by default
/// tol::kMinElementFraction of the scene's longest edge.
double min_element_size_m(const Scene& scene, const HierarchicalOptions& options);

/// Number of leaves of the named surface side in a solution.
size_t leaf_count(const Solution& solution, const std::string& side);

/// quadtree:LEAVES: an epsilon whose quadtree gives the side `side` exactly `leaves` leaves, or
/// the largest within 0.1% that gives at least that many (the Illinois method on log count
/// against log epsilon), then solved with a cap of exactly `leaves`. Throws
/// UserError (naming `field`) if `leaves` is not 1 + 3k or cannot be reached above the
/// minimum element size.
Solution solve_hierarchical_leaves(const Scene& scene, const std::string& side, int leaves,
                                   HierarchicalOptions options, const std::string& field);

}  // namespace radrecon
