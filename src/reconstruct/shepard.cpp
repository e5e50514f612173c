#include "reconstruct/shepard.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Core>

#include "core/check.h"
#include "core/tolerances.h"
#include "reconstruct/kdtree.h"
#include "core/parallel.h"

namespace radrecon {

Shepard::Shepard(ScatteredSamples samples, double mu, int k) : samples_(std::move(samples)), mu_(mu), k_(k) {
  RR_CHECK(mu > 0 && k >= 0, "Shepard parameters out of range");
  RR_CHECK(!samples_.points.empty(), "Shepard needs a sample");
  const size_t n = samples_.points.size();
  px_.reserve(n);
  py_.reserve(n);
  for (const Vec2& p : samples_.points) px_.push_back(p.x()), py_.push_back(p.y());
  values_by_channel_.resize(samples_.values.size());
  for (size_t i = 0; i < n; ++i)
    for (int c = 0; c < samples_.channels; ++c)
      values_by_channel_[static_cast<size_t>(c) * n + i] = samples_.values[i * samples_.channels + c];
  if (k_ > 0 && static_cast<size_t>(k_) < samples_.points.size()) {
    tree_ = std::make_unique<KdTree2>(samples_.points);
  } else {
    k_ = 0;
  }
}

Shepard::Shepard(ScatteredSamples samples, double mu, int k, Barriers barriers) : Shepard(std::move(samples), mu, k) {
  barriers_ = std::move(barriers);
  if (!barriers_.empty()) visibility_ = std::make_unique<PointVisibility>(samples_.points, barriers_);
}

Shepard::Shepard(ScatteredSamples samples, double mu, int k, Barriers barriers, double radius_m, int min_points)
    : Shepard(std::move(samples), mu, k, std::move(barriers)) {
  RR_CHECK(radius_m > 0 && min_points >= 1, "Shepard search radius out of range");
  radius_sq_ = radius_m * radius_m;
  min_points_ = static_cast<size_t>(min_points);
}

Shepard::~Shepard() = default;

namespace {

/// d^-mu from d^2: (d^2)^(-mu/2), with the common even exponents without pow(). Called with
/// d^2 relative to the nearest sample's (>= 1), so it never overflows.
inline double weight(double dist_sq, double mu) {
  if (mu == 4.0) return 1.0 / (dist_sq * dist_sq);
  if (mu == 2.0) return 1.0 / dist_sq;
  return std::pow(dist_sq, -0.5 * mu);
}

}  // namespace

/// Per-thread buffers of Shepard::evaluate: the global path's distances and weights (one per
/// sample), the local path's k nearest.
struct Shepard::Scratch {
  Eigen::ArrayXd dist_sq, w;
  std::vector<unsigned> idx;
  std::vector<double> d2;
  VisibleNeighbours visible;  ///< with barriers: the k nearest visible samples
  std::vector<char> hidden;   ///< with barriers, global: which samples a query does not see
};

void Shepard::evaluate(std::span<const Vec2> points, std::span<double> out) const {
  const int C = samples_.channels;
  RR_CHECK(out.size() == points.size() * static_cast<size_t>(C), "output size does not match the query points");
  const size_t n = samples_.points.size();
  parallel_for_with_scratch<Shepard::Scratch>(0, static_cast<std::int64_t>(points.size()), [&](std::int64_t k, Scratch& s) {
    const size_t q = static_cast<size_t>(k);
    double* o = &out[q * C];
    const Vec2 p = points[q];
    if (!p.allFinite()) {
      for (int c = 0; c < C; ++c) o[c] = std::numeric_limits<double>::quiet_NaN();
      return;
    }
    if (k_ == 0) {
      // Global: all samples at once as Eigen arrays (SIMD, sums in a fixed packet order).
      using Array = Eigen::Map<const Eigen::ArrayXd>;
      const Eigen::Index N = static_cast<Eigen::Index>(n);
      Eigen::ArrayXd& dist_sq = s.dist_sq;
      Eigen::ArrayXd& w = s.w;
      dist_sq = (p.x() - Array(px_.data(), N)).square() + (p.y() - Array(py_.data(), N)).square();
      if (!barriers_.empty()) {
        // A hidden sample is infinitely far: its weight is 0 below.
        visibility_->hidden_from(p, s.hidden);
        for (Eigen::Index i = 0; i < N; ++i)
          if (s.hidden[static_cast<size_t>(i)]) dist_sq[i] = std::numeric_limits<double>::infinity();
      }
      if (radius_sq_ < std::numeric_limits<double>::infinity()) {
        // Beyond the radius a sample is as good as hidden.
        size_t within = 0;
        for (Eigen::Index i = 0; i < N; ++i) {
          if (dist_sq[i] > radius_sq_) dist_sq[i] = std::numeric_limits<double>::infinity();
          else ++within;
        }
        if (within < min_points_) {
          for (int c = 0; c < C; ++c) o[c] = std::numeric_limits<double>::quiet_NaN();
          return;
        }
      }
      Eigen::Index first = 0;
      const double nearest_sq = dist_sq.minCoeff(&first);
      if (!(nearest_sq < std::numeric_limits<double>::infinity())) {  // sees no sample: no value
        for (int c = 0; c < C; ++c) o[c] = std::numeric_limits<double>::quiet_NaN();
        return;
      }
      if (nearest_sq == 0) {  // at a sample: its value (the limit of the weights)
        for (int c = 0; c < C; ++c) o[c] = samples_.values[static_cast<size_t>(first) * C + c];
        return;
      }
      // Weights relative to the nearest sample's, (d_min / d_i)^mu in (0, 1]: no overflow or
      // underflow whatever mu and the distances (the ratio cancels in the quotient).
      w = nearest_sq / dist_sq;
      if (mu_ == 4.0) w = w.square();
      else if (mu_ != 2.0) w = w.pow(0.5 * mu_);
      const double total = w.sum();
      for (int c = 0; c < C; ++c) o[c] = (w * Array(&values_by_channel_[static_cast<size_t>(c) * n], N)).sum() / total;
      return;
    }
    // k nearest, nearest first; with barriers the k nearest visible, which are the k nearest
    // when no barrier comes within reach of the k-th.
    size_t found = 0;
    s.idx.resize(static_cast<size_t>(k_));  // allocates on a thread's first query only
    s.d2.resize(static_cast<size_t>(k_));
    found = tree_->nearest(p, k_, s.idx, s.d2);
    const bool plain = barriers_.none_within(p, std::sqrt(s.d2[found - 1]));
    if (!plain) {
      found = nearest_visible(*tree_, samples_.points, barriers_, p, static_cast<size_t>(k_), s.visible);
      if (found == 0) {  // sees no sample: no value
        for (int c = 0; c < C; ++c) o[c] = std::numeric_limits<double>::quiet_NaN();
        return;
      }
    }
    const std::vector<unsigned>& idx = plain ? s.idx : s.visible.idx;
    const std::vector<double>& d2 = plain ? s.d2 : s.visible.dist_sq;
    while (found > 0 && d2[found - 1] > radius_sq_) --found;  // nearest first: those within the radius
    if (found < min_points_ || found == 0) {
      for (int c = 0; c < C; ++c) o[c] = std::numeric_limits<double>::quiet_NaN();
      return;
    }
    if (d2[0] == 0) {  // at a sample: its value
      for (int c = 0; c < C; ++c) o[c] = samples_.values[idx[0] * static_cast<size_t>(C) + c];
      return;
    }
    double total = 0, s0 = 0, s1 = 0, s2 = 0;
    for (size_t j = 0; j < found; ++j) {
      const double w = weight(d2[j] / d2[0], mu_);  // relative to the nearest: in (0, 1]
      const double* v = &samples_.values[idx[j] * static_cast<size_t>(C)];
      total += w;
      s0 += w * v[0];
      if (C > 1) s1 += w * v[1];
      if (C > 2) s2 += w * v[2];
    }
    o[0] = s0 / total;
    if (C > 1) o[1] = s1 / total;
    if (C > 2) o[2] = s2 / total;
    for (int c = 3; c < C; ++c) {
      double sum = 0;
      for (size_t j = 0; j < found; ++j) sum += weight(d2[j] / d2[0], mu_) * samples_.values[idx[j] * static_cast<size_t>(C) + c];
      o[c] = sum / total;
    }
  });
}

}  // namespace radrecon
