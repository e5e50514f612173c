#include "reconstruct/multiquadric.h"

#include <cmath>
#include <algorithm>
#include <bit>
#include <cstdint>
#include <limits>
#include <map>
#include <optional>

#include <Eigen/Core>

#include "core/check.h"
#include "core/parallel.h"
#include "core/tolerances.h"
#include "reconstruct/kdtree.h"
#include "reconstruct/rbf_system.h"
#include "reconstruct/multiquadric_basis.h"

namespace radrecon {

Multiquadric::Multiquadric(const ScatteredSamples& samples, const RbfKernel& kernel, std::optional<double> r_m,
                           Barriers barriers)
    : points_(samples.points), channels_(samples.channels), kernel_(kernel), barriers_(std::move(barriers)) {
  RR_CHECK(kernel.is_thin_plate() || kernel.mu != 0, "multiquadric mu must be nonzero");
  RR_CHECK(!kernel.is_thin_plate() || !r_m, "the thin-plate spline has no radius");
  const size_t n = points_.size();
  const std::string name = kernel_.name();
  if (n == 0) throw ReconstructionError(name + " needs at least one sample");
  if (kernel_.is_thin_plate()) {
    if (n >= 2) eck_radii_sq(points_, KdTree2(points_));  // refuses duplicate samples by name
    r_sq_.assign(n, 0.0);
  } else if (r_m) {
    r_sq_.assign(n, *r_m * *r_m);
  } else {
    if (n < 2) throw ReconstructionError("multiquadric with Eck's r needs at least 2 samples (or a fixed radius r)");
    const KdTree2 tree(points_);
    r_sq_ = eck_radii_sq(points_, tree);
  }
  std::vector<unsigned> all(n);
  for (size_t i = 0; i < n; ++i) all[i] = static_cast<unsigned>(i);
  fit_ = fit_rbf(points_, r_sq_, samples.values, channels_, kernel_, std::move(all));
  rcond_ = fit_.rcond;
  rbf_system::warn_if_poorly_conditioned(rcond_, name + " system", "; results may be inaccurate");
  if (!barriers_.empty()) {
    values_ = samples.values;
    visibility_ = std::make_unique<PointVisibility>(points_, barriers_);
  }
}

namespace {

/// A subset at most this many samples (added plus dropped) away from a root's is derived from
/// its factorisation (fit_rbf_near(): about two solves with the root's LU a sample, against a
/// factorisation's third of the subset's size); farther ones are roots themselves. 8 made the
/// fewest operations on the paper's barrier data (2,344 subsets, 85 roots).
constexpr size_t kMostSamplesFromRoot = 8;
/// A subset looks for its root among the last this many roots made, in the subsets' sorted order
/// (similar subsets sort near each other).
constexpr size_t kRootsSearched = 256;
/// Queries whose visible subsets are found at a time (by a thread, in order: runs of queries see
/// the same subset).
constexpr std::int64_t kSubsetChunk = 1024;

/// The number of samples in one of two sets but not the other, as bit sets.
size_t distance(const std::vector<std::uint64_t>& a, const std::vector<std::uint64_t>& b) {
  size_t d = 0;
  for (size_t w = 0; w < a.size(); ++w) d += static_cast<size_t>(std::popcount(a[w] ^ b[w]));
  return d;
}

}  // namespace

std::vector<std::shared_ptr<const RbfFit>> Multiquadric::visible_fits(std::span<const Vec2> points,
                                                                      std::vector<int>& fit_of) const {
  const std::int64_t count = static_cast<std::int64_t>(points.size());
  fit_of.assign(points.size(), kSeesNone);
  // Each chunk's distinct subsets in order of first sight, and its queries' indices into them.
  const std::int64_t chunks = (count + kSubsetChunk - 1) / kSubsetChunk;
  std::vector<std::vector<std::vector<unsigned>>> seen(static_cast<size_t>(chunks));
  struct Scratch {
    std::vector<unsigned> visible;
    std::vector<char> hidden;
  };
  parallel_for_with_scratch<Scratch>(0, chunks, 1, 2, [&](std::int64_t c, Scratch& s) {
    std::vector<std::vector<unsigned>>& distinct = seen[static_cast<size_t>(c)];
    for (std::int64_t q = c * kSubsetChunk; q < std::min(count, (c + 1) * kSubsetChunk); ++q) {
      int& id = fit_of[static_cast<size_t>(q)];
      if (!points[static_cast<size_t>(q)].allFinite()) continue;  // kSeesNone: NaN
      visibility_->visible_from(points[static_cast<size_t>(q)], s.visible, s.hidden);
      if (s.visible.size() == points_.size()) id = kSeesAll;
      else if (s.visible.empty()) id = kSeesNone;
      else {
        const auto it = std::find(distinct.rbegin(), distinct.rend(), s.visible);  // the recent first
        if (it != distinct.rend()) id = static_cast<int>(distinct.rend() - it - 1);
        else {
          id = static_cast<int>(distinct.size());
          distinct.push_back(s.visible);
        }
      }
    }
  });
  // The call's distinct subsets, numbered in order of first sight.
  std::map<std::vector<unsigned>, int> number;
  std::vector<const std::vector<unsigned>*> subsets;
  for (std::int64_t c = 0; c < chunks; ++c) {
    std::vector<int> global;
    for (const std::vector<unsigned>& v : seen[static_cast<size_t>(c)]) {
      const auto [it, inserted] = number.try_emplace(v, static_cast<int>(subsets.size()));
      if (inserted) subsets.push_back(&it->first);
      global.push_back(it->second);
    }
    for (std::int64_t q = c * kSubsetChunk; q < std::min(count, (c + 1) * kSubsetChunk); ++q)
      if (int& id = fit_of[static_cast<size_t>(q)]; id >= 0) id = global[static_cast<size_t>(id)];
  }
  std::vector<std::shared_ptr<const RbfFit>> fits(subsets.size());
  std::vector<size_t> missing;  // in the subsets' (lexicographic) order: similar ones adjacent
  for (const auto& [subset, k] : number) {
    fits[static_cast<size_t>(k)] = fits_.find(0, subset);
    if (!fits[static_cast<size_t>(k)]) missing.push_back(static_cast<size_t>(k));
  }
  // Roots, and each other subset under the nearest of the recent roots: a plan made in one
  // thread from the subsets alone, so that no result depends on the threads.
  const size_t words = (points_.size() + 63) / 64;
  std::vector<std::vector<std::uint64_t>> root_bits;
  std::vector<size_t> roots;                    // subset numbers
  std::vector<std::vector<size_t>> children;    // per root
  for (size_t k : missing) {
    std::vector<std::uint64_t> bits(words, 0);
    for (unsigned i : *subsets[k]) bits[i / 64] |= std::uint64_t{1} << (i % 64);
    size_t best = roots.size(), best_distance = kMostSamplesFromRoot + 1;
    for (size_t r = roots.size() > kRootsSearched ? roots.size() - kRootsSearched : 0; r < roots.size(); ++r)
      if (const size_t d = distance(bits, root_bits[r]); d < best_distance) best = r, best_distance = d;
    if (best < roots.size()) {
      children[best].push_back(k);
    } else {
      roots.push_back(k);
      root_bits.push_back(std::move(bits));
      children.emplace_back();
    }
  }
  parallel_for_grained(0, static_cast<std::int64_t>(roots.size()), 1, [&](std::int64_t r) {
    const RbfRootFit root = fit_rbf_root(points_, r_sq_, values_, channels_, kernel_, *subsets[roots[static_cast<size_t>(r)]]);
    fits[roots[static_cast<size_t>(r)]] = std::make_shared<const RbfFit>(root.fit);
    for (size_t k : children[static_cast<size_t>(r)]) {
      std::optional<RbfFit> near = fit_rbf_near(root, points_, r_sq_, values_, channels_, kernel_, *subsets[k]);
      if (!near) near = fit_rbf(points_, r_sq_, values_, channels_, kernel_, *subsets[k]);
      fits[k] = std::make_shared<const RbfFit>(std::move(*near));
    }
  });
  for (size_t k : missing) {
    const std::shared_ptr<const RbfFit> made = fits[k];
    fits[k] = fits_.get(0, *subsets[k], [&] { return made; });
  }
  return fits;
}

void Multiquadric::evaluate(std::span<const Vec2> points, std::span<double> out) const {
  const int C = channels_;
  RR_CHECK(out.size() == points.size() * static_cast<size_t>(C), "output size does not match the query points");
  std::vector<int> fit_of;
  std::vector<std::shared_ptr<const RbfFit>> fits;
  if (!barriers_.empty()) fits = visible_fits(points, fit_of);
  parallel_for_with_scratch<Eigen::ArrayXd>(0, static_cast<std::int64_t>(points.size()), [&](std::int64_t k, Eigen::ArrayXd& b) {
    const size_t q = static_cast<size_t>(k);
    const Vec2 p = points[q];
    const int which = barriers_.empty() ? kSeesAll : fit_of[q];
    if (!p.allFinite() || which == kSeesNone) {
      for (int c = 0; c < C; ++c) out[q * C + c] = std::numeric_limits<double>::quiet_NaN();
      return;
    }
    evaluate_rbf_fit(which == kSeesAll ? fit_ : *fits[static_cast<size_t>(which)], kernel_, C, p, b, &out[q * C]);
  });
}

}  // namespace radrecon
