#include "reconstruct/local_multiquadric.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include <Eigen/LU>

#include "core/check.h"
#include "core/parallel.h"
#include "core/tolerances.h"
#include "reconstruct/convex_hull.h"
#include "reconstruct/kdtree.h"
#include "reconstruct/multiquadric_basis.h"
#include "reconstruct/rbf_system.h"

namespace radrecon {

namespace {

/// Radius of a patch's sample disc over the radius of its support.
constexpr double kSampleMargin = 1.5;

/// A patch is passed over without its weight when the query's squared distance to its centre
/// exceeds h^2 widened by this: its Wendland weight is then 0 (t = d / h > 1 however d / h
/// rounds), as computed.
constexpr double kSupportSlack = 1e-12;

/// The grid columns and rows searched for a query's patches reach this far (in units of h)
/// beyond its support, against the rounding of its grid coordinates; the patch centres' own
/// rounding (origin + i h, a few ulps of the coordinates' magnitude) is added to it
/// (LocalMultiquadric::candidate_slack_). A patch passed over then lies farther than h from
/// the query, where its weight is 0.
constexpr double kCandidateSlack = 1e-6;

/// A patch on one line looks for a sample off it among the nearest this many times its own
/// samples (survey tracks: the next track lies within a few times a patch's reach).
constexpr size_t kOffLineSearch = 16;

/// Wendland's C2 function of t = d / h, zero for t >= 1.
inline double wendland(double t) {
  if (t >= 1) return 0;
  const double a = 1 - t, a2 = a * a;
  return a2 * a2 * (4 * t + 1);
}

/// Per-thread buffers of the patch loop: the samples near a patch centre.
struct NearestScratch {
  std::vector<std::pair<unsigned, double>> within;
  std::vector<unsigned> indices;
  std::vector<double> dist_sq;
};

}  // namespace

LocalMultiquadric::LocalMultiquadric(const ScatteredSamples& samples, const RbfKernel& kernel,
                                     std::optional<double> r_m, int k, Barriers barriers)
    : points_(samples.points), channels_(samples.channels), kernel_(kernel), barriers_(std::move(barriers)) {
  if (!barriers_.empty()) values_ = samples.values;
  RR_CHECK((kernel.is_thin_plate() || kernel.mu != 0) && k >= kMinPatchSamples,
           "local multiquadric parameters out of range");
  RR_CHECK(!kernel.is_thin_plate() || !r_m, "the thin-plate spline has no radius");
  const size_t n = points_.size();
  if (n < 2) throw ReconstructionError("the local " + kernel.name() + " needs at least 2 samples");
  const KdTree2 tree(points_);
  r_sq_ = eck_radii_sq(points_, tree);  // also refuses duplicate points, whatever r
  if (r_m) r_sq_.assign(n, *r_m * *r_m);
  if (kernel.is_thin_plate()) r_sq_.assign(n, 0.0);
  // Samples on a line (or nearly) have a box of no width: point_spread() gives it a sliver of
  // width and area so that the patch grid stays finite.
  const PointSpread spread = point_spread(points_);
  const Vec2 &lo = spread.lo, &hi = spread.hi, &extent = spread.extent;
  const double area = spread.area_m2;
  // The patch's samples come from a disc kSampleMargin times its support, so that its
  // interpolant never extrapolates where its weight is nonzero; that disc holds ~k samples.
  h_ = std::sqrt(std::min<double>(k, n) * area / (std::numbers::pi * n)) / kSampleMargin;
  origin_ = lo;
  box_max_ = hi;
  candidate_slack_ = kCandidateSlack + 4 * std::numeric_limits<double>::epsilon() *
                                          std::max(lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff()) / h_;
  nx_ = static_cast<int>(std::ceil(extent.x() / h_)) + 1;
  ny_ = static_cast<int>(std::ceil(extent.y() / h_)) + 1;
  patches_.resize(static_cast<size_t>(nx_) * ny_);
  // With barriers, part of a patch's samples may be hidden from where it is evaluated, and a
  // patch of a few samples near a wall (or the domain's edge) may see fewer than a plane needs:
  // it then holds at least k.
  const int kk = std::min<int>(barriers_.empty() ? kMinPatchSamples : k, static_cast<int>(n));
  // Each patch: the samples in its disc (one radius search), or the kk nearest when the disc
  // holds fewer. (The kk nearest are taken from a search of 2k, where ties at the kk-th distance
  // go to the lowest indices, kdtree.h.)
  // Whether the samples span a plane at all: if not, no patch looks for a sample off its line.
  bool spans_plane = false;
  if (kernel_.poly && barriers_.empty()) {
    std::vector<unsigned> all(n);
    for (size_t i = 0; i < n; ++i) all[i] = static_cast<unsigned>(i);
    RbfFit frame;
    rbf_system::polynomial_frame(points_, all, frame);
    spans_plane = frame.terms == 3;
  }
  parallel_for_with_scratch<NearestScratch>(0, static_cast<std::int64_t>(patches_.size()), [&](std::int64_t pk, NearestScratch& s) {
    Patch& patch = patches_[static_cast<size_t>(pk)];
    const int i = static_cast<int>(pk % nx_), j = static_cast<int>(pk / nx_);
    patch.center = origin_ + Vec2(i * h_, j * h_);
    const double reach_sq = kSampleMargin * kSampleMargin * h_ * h_;
    tree.within(patch.center, reach_sq, s.within);
    double farthest_sq = 0;
    if (s.within.size() >= static_cast<size_t>(kk)) {
      patch.samples.resize(s.within.size());
      for (size_t a = 0; a < s.within.size(); ++a) patch.samples[a] = s.within[a].first;
      farthest_sq = s.within.back().second;
    } else {  // too few in the disc: the kk nearest
      const int want = std::min<int>(std::max(kk, 2 * k), static_cast<int>(n));
      s.indices.resize(static_cast<size_t>(want));
      s.dist_sq.resize(static_cast<size_t>(want));
      tree.nearest(patch.center, want, s.indices, s.dist_sq);
      patch.samples.assign(s.indices.begin(), s.indices.begin() + kk);
      farthest_sq = s.dist_sq[static_cast<size_t>(kk) - 1];
    }
    // With a polynomial, samples on one line (a survey track) determine none of its term across:
    // every patch on the tracks gave way to none, and a linear function erred by 1.3 between
    // them (found by an outside-in trial). The patch takes the nearest sample off its line too,
    // so that its samples span a plane, as the global fit's do.
    if (kernel_.poly && barriers_.empty() && spans_plane && patch.samples.size() < n) {
      RbfFit frame;
      rbf_system::polynomial_frame(points_, patch.samples, frame);
      if (frame.terms == 2) {
        const Vec2 along = frame.axis1.normalized();
        const double length = 1 / frame.axis1.norm();  // the spread along the line
        // Among the nearest kOffLineSearch times the patch's samples at most: past them the
        // patch gives way as before (one stray sample far off a line of thousands cost every
        // patch a search of them all: minutes).
        const size_t most = std::min(n, kOffLineSearch * patch.samples.size());
        for (size_t want = std::min(most, 2 * patch.samples.size() + 1);; want = std::min(most, 2 * want)) {
          s.indices.resize(want);
          s.dist_sq.resize(want);
          tree.nearest(patch.center, static_cast<int>(want), s.indices, s.dist_sq);
          size_t off = want;  // the nearest sample off the line
          for (size_t a = 0; a < want && off == want; ++a) {
            const Vec2 d = points_[s.indices[a]] - frame.centre;
            if (std::abs(along.x() * d.y() - along.y() * d.x()) > tol::kRbfFlatSubsetRelative * std::max(length, d.norm())) off = a;
          }
          if (off < want) {
            patch.samples.push_back(s.indices[off]);
            farthest_sq = std::max(farthest_sq, s.dist_sq[off]);
            break;
          }
          if (want == most) break;  // none near enough: the fit gives way, as before
        }
      }
    }
    const size_t m = patch.samples.size();
    // From any point of its support (within h of its centre) to its farthest sample: no barrier
    // that near, no sample of the patch hidden.
    patch.reach_m = h_ + std::sqrt(farthest_sq);
    if (m > kMaxPatchSamples) return;  // refused below, outside the parallel loop
    patch.fit = fit_rbf(points_, r_sq_, samples.values, channels_, kernel_, patch.samples, true);
    patch.fit.hull = ConvexHull2(points_, patch.samples);
    patch.inside_sq = std::pow(patch.fit.hull.depth(patch.center), 2);
  });
  check_patches();
}

LocalMultiquadric::~LocalMultiquadric() = default;

double LocalMultiquadric::reciprocal_condition() const {
  double worst = 1;
  for (const Patch& p : patches_) worst = std::min(worst, p.fit.rcond);
  return worst;
}

void LocalMultiquadric::check_patches() const {
  for (const Patch& p : patches_) {
    if (p.samples.size() > kMaxPatchSamples) {
      char at[64];  // %g: six digits locate a patch at any scale of coordinates (%f printed 0.000000)
      std::snprintf(at, sizeof at, "(%g, %g)", p.center.x(), p.center.y());
      throw ReconstructionError("a local " + kernel_.name() + " patch at " + at + " holds " + std::to_string(p.samples.size()) +
                                     " samples (at most " + std::to_string(kMaxPatchSamples) +
                                     "): the samples are too clustered for patches of the requested size; use a smaller k");
    }
  }
  const double worst = reciprocal_condition();
  if (!(worst > 0) || !std::isfinite(worst)) throw ReconstructionError("a local " + kernel_.name() + " system is singular");
  rbf_system::warn_if_poorly_conditioned(worst, "a local " + kernel_.name() + " system");
}

void LocalMultiquadric::evaluate(std::span<const Vec2> points, std::span<double> out) const {
  const int C = channels_;
  RR_CHECK(out.size() == points.size() * static_cast<size_t>(C), "output size does not match the query points");
  struct Scratch {
    std::vector<unsigned> visible;
    std::vector<double> flat;  ///< the blend of the patches whose visible samples span no plane
    Eigen::ArrayXd basis;      ///< a patch's basis at the query
  };
  parallel_for_with_scratch<Scratch>(0, static_cast<std::int64_t>(points.size()), [&](std::int64_t k, Scratch& scratch) {
    std::vector<unsigned>& visible = scratch.visible;
    std::vector<double>& flat = scratch.flat;
    flat.assign(static_cast<size_t>(C), 0.0);
    const size_t q = static_cast<size_t>(k);
    double* o = &out[q * C];
    for (int c = 0; c < C; ++c) o[c] = 0;
    const Vec2 p = points[q];
    if (!p.allFinite()) {
      for (int c = 0; c < C; ++c) o[c] = std::numeric_limits<double>::quiet_NaN();
      return;
    }
    // Outside the samples' box, the weights of the nearest point x of the box. Each patch's RBF
    // is evaluated at the nearest point of its samples' hull, plus its polynomial's change from
    // there (the header says why).
    const Vec2 x = p.cwiseMax(origin_).cwiseMin(box_max_);
    // The patches whose centre may lie within h of x: those of the grid columns and rows within
    // h of it (two of each, three where x is within candidate_slack_ of a grid line).
    const double gx = (x.x() - origin_.x()) / h_, gy = (x.y() - origin_.y()) / h_;
    const int i0 = std::max(0, static_cast<int>(std::ceil(gx - 1 - candidate_slack_)));
    const int i1 = std::min(nx_ - 1, static_cast<int>(std::floor(gx + 1 + candidate_slack_)));
    const int j0 = std::max(0, static_cast<int>(std::ceil(gy - 1 - candidate_slack_)));
    const int j1 = std::min(ny_ - 1, static_cast<int>(std::floor(gy + 1 + candidate_slack_)));
    // Their weights first, each on its own (no chain of square roots and divisions from one
    // patch to the next), then their sums in grid order.
    const double support_sq = h_ * h_ * (1 + kSupportSlack);
    std::array<size_t, 9> near_index;
    std::array<double, 9> near_dist_sq, near_weight;
    size_t near = 0;
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const size_t index = static_cast<size_t>(j) * nx_ + i;
        // A patch beyond its support is passed over without a square root.
        const double dist_sq = (x - patches_[index].center).squaredNorm();
        if (dist_sq > support_sq) continue;
        near_index[near] = index;
        near_dist_sq[near++] = dist_sq;
      }
    for (size_t a = 0; a < near; ++a) near_weight[a] = wendland(std::sqrt(near_dist_sq[a]) / h_);
    double total = 0, flat_total = 0;
    for (size_t a = 0; a < near; ++a) {
      const size_t index = near_index[a];
      const Patch& patch = patches_[index];
      const double w = near_weight[a];
      if (w == 0) continue;
      // The patch's fit, or with barriers the fit through its samples x sees.
      const RbfFit* fit = &patch.fit;
      std::shared_ptr<const RbfFit> visible_fit;
      if (!barriers_.none_within(x, patch.reach_m)) {
        visible.clear();
        for (unsigned s : patch.samples)
          if (!barriers_.blocks(x, points_[s])) visible.push_back(s);
        if (visible.empty()) continue;  // the patch sees nothing of x: no weight
        if (visible.size() < patch.samples.size()) {
          visible_fit = fits_.get(static_cast<unsigned>(index), visible, [&] {
            RbfFit f = fit_rbf(points_, r_sq_, values_, channels_, kernel_, visible, true);
            f.hull = ConvexHull2(points_, visible);
            return f;
          });
          fit = visible_fit.get();
        }
      }
      const Vec2 e = fit == &patch.fit && (p - patch.center).squaredNorm() < patch.inside_sq ? p : fit->hull.nearest(p);
      // With a polynomial, a patch whose visible samples span no plane (its polynomial lacks a
      // term) gives way to those that span one, and counts only where none does.
      const bool lacks = fit->terms > 0 && fit->terms < 3;
      double* acc = lacks ? flat.data() : o;
      (lacks ? flat_total : total) += w;
      add_rbf_sum(*fit, kernel_, C, e, w, scratch.basis, acc);
      // RBF(e) + poly(e) + (poly(p) - poly(e)): the polynomial (or offset) continues past the hull.
      for (int c = 0; c < C; ++c) acc[c] += w * fit->polynomial(p, c);
    }
    if (total == 0 && flat_total > 0) {
      total = flat_total;
      for (int c = 0; c < C; ++c) o[c] = flat[static_cast<size_t>(c)];
    }
    for (int c = 0; c < C; ++c) o[c] = total > 0 ? o[c] / total : std::numeric_limits<double>::quiet_NaN();
  });
}

}  // namespace radrecon
