// quadtree:LEAVES: hierarchical radiosity with exactly a given number of leaves on one side, by
// a search over the refinement threshold epsilon.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

#include "core/error.h"
#include "core/limits.h"
#include "core/parse.h"
#include "core/progress.h"
#include "core/tolerances.h"
#include "mesh/grid_mesh.h"
#include "scene/side.h"
#include "solver/hierarchical.h"

namespace radrecon {

size_t leaf_count(const Solution& solution, const std::string& side) {
  const SurfaceSolution* s = solution.find(side);
  return s ? s->elements.size() : 0;
}

Solution solve_hierarchical_leaves(const Scene& scene, const std::string& side, int leaves,
                                   HierarchicalOptions options, const std::string& field) {
  if (leaves < 1 || (leaves - 1) % 3 != 0)
    throw UserError(field, "a quadtree has 1 + 3k leaves; " + std::to_string(leaves) + " is not of that form");
  const std::string spec = "quadtree:" + std::to_string(leaves);
  const std::string label = options.progress_label;
  const bool leaf_gather = options.leaf_gather;
  options.progress_label.clear();
  options.leaf_cap.reset();
  options.leaf_gather = false;  // the final gather does not change the count
  constexpr int kTooFine = std::numeric_limits<int>::max();
  LinkFormFactorCache cache;  // the solves below share most of their links
  // Leaves of `side` at epsilon `eps` (W); kTooFine when the links would not fit.
  const auto start = std::chrono::steady_clock::now();
  Progress progress(label, label.empty());
  auto count = [&](double eps) {
    options.epsilon_w = eps;
    const std::optional<Solution> sol = try_solve_hierarchical(scene, options, spec, &cache);
    const int n = sol ? static_cast<int>(leaf_count(*sol, side)) : kTooFine;
    char what[160];
    std::snprintf(what, sizeof what, "searching epsilon for %d leaves on %s: %.4g W gives %s", leaves, side.c_str(), eps,
                  sol ? std::to_string(n).c_str() : "too many links");
    progress.note(what);
    return n;
  };
  // The most leaves the side can have: split down to the minimum element size everywhere.
  {
    const double min_size = min_element_size_m(scene, options);
    const std::optional<SideRef> ref = find_side(scene, side);
    if (!ref) throw UserError(field, "the scene has no surface side named '" + side + "' (its sides: " + side_names(scene) + ")");
    const Surface& surface = scene.surfaces[ref->surface];
    // Refinement never splits a black side: its radiosity is its uniform emission, so no link's
    // error involves it (hierarchical.h). Refused at once rather than after a search to the
    // link limit.
    if (leaves > 1 && (surface.reflectance == 0).all())
      throw UserError(field, std::to_string(leaves) + " leaves on '" + side + "' cannot be reached: a black side (reflectance 0) "
                                 "is never split, its radiosity being its uniform emission; count another side with --leaves-on");
    const double side_size = surface.extent_m();  // as the quadtree sizes its root (a triangle's longest edge)
    double most = 1;
    for (double size = side_size; size >= 2 * min_size && most <= leaves; size /= 2) most *= 4;
    if (leaves > most)
      throw UserError(field, std::to_string(leaves) + " leaves on '" + side + "' cannot be reached above the minimum element size (" +
                                 std::to_string(min_size) + " m allows at most " + std::to_string(static_cast<long long>(most)) + ")");
    // The last few of those leaves need every node split, which refinement reaches only as epsilon
    // goes to 0, the links growing without end: the paper's ground at quadtree:65536 (all of its
    // 256 x 256) crept from 61,180 leaves to 65,443 over 90 s of searching, then hit the link
    // limit. Refused at once, with the counts that are within reach, on a side that can have
    // kManyLeaves or more (below, a search to the very last split is short).
    constexpr double kMostLeavesShare = 0.99, kManyLeaves = 1024;
    if (most >= kManyLeaves && leaves > kMostLeavesShare * most) {
      const long long within = 1 + 3 * static_cast<long long>((kMostLeavesShare * most - 1) / 3);
      throw UserError(field, std::to_string(leaves) + " leaves on '" + side + "' are (nearly) every node at the minimum element size (" +
                                 format_number(min_size) + " m allows at most " + std::to_string(static_cast<long long>(most)) +
                                 "), which refinement reaches only as epsilon goes to 0; ask for at most " +
                                 std::to_string(within) + ", or for a uniform grid use grid:N");
    }
  }
  // Bracket count(lo) >= leaves > count(hi), stepping down by kStep at most, then narrow it in
  // log epsilon until it is kBracket wide or lo gives exactly `leaves`. An epsilon far too
  // small costs far more than the rest of the search (the links grow as the square of the
  // leaves), so a step goes no lower than kUndershoot times where the last two counts,
  // extrapolated as a power of epsilon, reach `leaves`.
  constexpr double kStep = 10, kBracket = 1.001, kStart = 1e-3, kLargest = 1e12, kUndershoot = 0.9;
  constexpr int kMaxSteps = 24, kMaxNarrowings = 60;
  constexpr double kLeast = 0.05;
  double hi = 1.0, lo = kStart;
  int c_hi = count(hi);
  while (c_hi >= leaves && hi < kLargest) c_hi = count(hi *= kStep);
  // A count that stays put over kStalledSteps steps in a row (kStep each) has stopped: a side's
  // refinement can rest for a step and then go on (a small triangle's 16 leaves, at 1e-3 and
  // 1e-4 W, became more below; one step had been taken for the end). Each step down costs more
  // than the last: the links grow as the other sides refine.
  constexpr int kStalledSteps = 2;
  int c_lo = count(lo), previous = -1, stalled = 0;
  const double first_lo = lo;
  for (int k = 0; c_lo < leaves && stalled < kStalledSteps && k < kMaxSteps; ++k) {
    double next = lo / kStep;
    if (c_hi > 0 && c_lo > c_hi && hi > lo) {
      const double exponent = std::log(double(c_lo) / c_hi) / std::log(hi / lo);  // count ~ epsilon^-exponent
      next = std::max(next, kUndershoot * lo * std::pow(double(c_lo) / leaves, 1 / exponent));
    }
    hi = lo;
    c_hi = c_lo;
    lo = next;
    previous = c_lo;
    c_lo = count(lo);
    stalled = c_lo == previous ? stalled + 1 : 0;
  }
  if (c_lo < leaves) {
    char range[96];
    std::snprintf(range, sizeof range, " (from epsilon %.3g W down to %.3g W)", first_lo, lo);
    throw UserError(field, std::to_string(leaves) + " leaves on '" + side + "' cannot be reached: refinement stops at " +
                               std::to_string(c_lo) + range);
  }
  // The Illinois method on f = log(count / leaves) against log epsilon: regula falsi, with the
  // end kept twice in a row weighed down by half so that neither end stagnates.
  const auto f = [&](int c) { return c == kTooFine ? 1.0 : std::log(double(std::max(c, 1)) / leaves); };
  double f_lo = f(c_lo), f_hi = f(c_hi);
  int kept = 0;  // +1: lo was kept last step, -1: hi was
  for (int k = 0; k < kMaxNarrowings && c_lo != leaves && hi / lo > kBracket; ++k) {
    double t = f_lo > f_hi ? f_lo / (f_lo - f_hi) : 0.5;  // the way from lo to hi, in log epsilon
    const double mid = lo * std::pow(hi / lo, std::clamp(t, kLeast, 1 - kLeast));
    const int c = count(mid);
    if (c >= leaves) {
      lo = mid;
      c_lo = c;
      f_lo = f(c);
      if (kept == -1) f_hi /= 2;
      kept = -1;
    } else {
      hi = mid;
      f_hi = f(c);
      if (kept == 1) f_lo /= 2;
      kept = 1;
    }
  }
  if (c_lo == kTooFine)
    throw UserError(field, std::to_string(leaves) + " leaves on '" + side + "' need more than " +
                               std::to_string(options.max_links) + " links; use fewer leaves, or " +
                               limit_spec(Limit::links).option + " raises the limit (nothing was written)");
  options.leaf_gather = leaf_gather;
  options.epsilon_w = lo;
  options.leaf_cap = std::make_pair(side, leaves);
  options.progress_label = label;
  progress.done();  // the final solve reports on a line of its own
  Solution sol = solve_hierarchical(scene, options, spec, &cache);
  const size_t made = leaf_count(sol, side);
  if (made != static_cast<size_t>(leaves))
    throw UserError(field, "refinement gives " + std::to_string(made) + " leaves on '" + side + "', not exactly " +
                               std::to_string(leaves) + "; try a neighbouring count (1 + 3k)");
  sol.stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // Said whether the cap made the count: that epsilon alone gives more (quadtree-eps:E would not
  // reproduce the solution; an outside-in trial).
  if (!label.empty() && c_lo == leaves)
    std::fprintf(stderr, "%s: epsilon %.4g W gives %d leaves on %s\n", label.c_str(), lo, leaves, side.c_str());
  else if (!label.empty())
    std::fprintf(stderr, "%s: epsilon %.4g W with a cap of %d leaves on %s (that epsilon alone gives %d; the splits of "
                 "largest estimate kept)\n", label.c_str(), lo, leaves, side.c_str(), c_lo);
  return sol;
}

/// The minimum element size of `options`, or its default: a fraction of the longest edge.
double min_element_size_m(const Scene& scene, const HierarchicalOptions& options) {
  if (options.min_size_m > 0) return options.min_size_m;
  return longest_edge_m(scene) * tol::kMinElementFraction;
}

}  // namespace radrecon
