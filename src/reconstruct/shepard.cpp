#include "reconstruct/shepard.h"

#include <algorithm>
#include <cmath>

#include <limits>

#include <Eigen/Core>

#include "core/check.h"
#include "core/tolerances.h"
#include "reconstruct/kdtree.h"
#include "core/parallel.h"
#include "core/simd.h"

namespace radrecon {

namespace {

// global_value_one_pass()'s weights are w = d^-mu themselves (not relative to the nearest
// sample's): safe while every squared distance d^2 lies in [kLeastDistSq, kMostDistSq] and every
// value's magnitude in [kLeastValue, kMostValue] (or is 0). Then a product of two d^2 (the shared
// division) lies in [1e-120, 1e120], w in [1e-120, 1e120] for mu up to 4, and w times a value in
// [1e-270, 1e270]: normal numbers, with the relative rounding of the relative weights.
[[maybe_unused]] constexpr double kLeastDistSq = 1e-60, kMostDistSq = 1e60;
constexpr double kLeastValue = 1e-150, kMostValue = 1e150;

}  // namespace

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
  one_pass_ = RADRECON_SIMD && (mu_ == 4.0 || mu_ == 2.0) && samples_.channels <= 3 &&
              std::all_of(samples_.values.begin(), samples_.values.end(), [](double v) {
                return v == 0 || (std::abs(v) >= kLeastValue && std::abs(v) <= kMostValue);
              });
  if (k_ > 0 && static_cast<size_t>(k_) < samples_.points.size()) {
    tree_ = std::make_unique<KdTree2>(samples_.points);
    nearest_ = std::make_unique<CoherentNearest>(*tree_, samples_.points, k_);
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

/// A sample's weight relative to the nearest one's, (d_min / d)^mu, from ratio = d_min^2 / d^2
/// in (0, 1]: no overflow or underflow whatever mu and the distances (the ratio cancels in the
/// quotient). The common even exponents without pow(); the global path's arrays do the same.
inline double relative_weight(double ratio, double mu) {
  if (mu == 4.0) return ratio * ratio;
  if (mu == 2.0) return ratio;
  return std::pow(ratio, 0.5 * mu);
}

}  // namespace

/// Per-thread buffers of Shepard::evaluate: the global path's distances and weights (one per
/// sample), the local path's k nearest.
struct Shepard::Scratch {
  Eigen::ArrayXd dist_sq, w;
  CoherentNearest::Scratch tile;  ///< the local path's k nearest
  VisibleNeighbours visible;  ///< with barriers: the k nearest visible samples
  std::vector<char> hidden;   ///< with barriers, global: which samples a query does not see
};

void Shepard::local_value(const Vec2& p, std::span<const unsigned> nearest_idx, std::span<const double> nearest_d2,
                          size_t nearest, Scratch& s, double* o) const {
  const int C = samples_.channels;
  const auto no_value = [&] {
    for (int c = 0; c < C; ++c) o[c] = std::numeric_limits<double>::quiet_NaN();
  };
  // The k nearest; with barriers the k nearest visible (nearest first), which are the k
  // nearest when no barrier comes within reach of the farthest of them.
  std::span<const unsigned> idx = nearest_idx;
  std::span<const double> d2 = nearest_d2;
  if (!barriers_.empty() && !barriers_.none_within(p, std::sqrt(*std::max_element(d2.begin(), d2.end())))) {
    const size_t found = nearest_visible(*tree_, samples_.points, barriers_, p, static_cast<size_t>(k_), s.visible);
    if (found == 0) return no_value();  // sees no sample
    idx = std::span<const unsigned>(s.visible.idx.data(), found);
    d2 = std::span<const double>(s.visible.dist_sq.data(), found);
    nearest = 0;
  }
  // Those within the radius.
  const bool radius = radius_sq_ < std::numeric_limits<double>::infinity();
  if (radius) {
    size_t within = 0;
    for (const double d : d2) within += d <= radius_sq_;
    if (within < min_points_ || within == 0) return no_value();
  }
  const double nearest_sq = d2[nearest];
  if (nearest_sq == 0) {  // at a sample: its value
    for (int c = 0; c < C; ++c) o[c] = samples_.values[idx[nearest] * static_cast<size_t>(C) + c];
    return;
  }
  double total = 0, s0 = 0, s1 = 0, s2 = 0;
  for (size_t j = 0; j < d2.size(); ++j) {
    if (radius && !(d2[j] <= radius_sq_)) continue;
    const double w = relative_weight(nearest_sq / d2[j], mu_);  // relative to the nearest: in (0, 1]
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
    for (size_t j = 0; j < d2.size(); ++j)
      if (d2[j] <= radius_sq_) sum += relative_weight(nearest_sq / d2[j], mu_) * samples_.values[idx[j] * static_cast<size_t>(C) + c];
    o[c] = sum / total;
  }
}

bool Shepard::global_value_one_pass(const Vec2& p, const char* hidden, double* o) const {
#if RADRECON_SIMD
  using simd::PackD;
  using Mask = PackD::Mask;
  constexpr size_t L = PackD::kLanes;
  const int C = samples_.channels;
  const size_t n = px_.size();
  const double* v0 = values_by_channel_.data();
  const double* v1 = C > 1 ? v0 + n : v0;
  const double* v2 = C > 2 ? v0 + 2 * n : v0;
  const bool square = mu_ == 4.0;
  const PackD x = PackD::set(p.x()), y = PackD::set(p.y()), one = PackD::set(1.0), zero = PackD::zero();
  PackD least = PackD::set(std::numeric_limits<double>::infinity()), most = zero;
  // Sums of weights and of weights times values, two sets (the even and the odd packets of
  // samples: two dependency chains), merged at the end.
  struct Sums {
    PackD total = PackD::zero(), s0 = total, s1 = total, s2 = total;
  } even, odd;
  const auto add = [&](Sums& sums, PackD w, size_t at, const auto& load) {  // w = d^-2 of samples at..
    if (square) w = w * w;
    sums.total = sums.total + w;
    sums.s0 = fmadd(w, load(v0 + at), sums.s0);
    if (C > 1) sums.s1 = fmadd(w, load(v1 + at), sums.s1);
    if (C > 2) sums.s2 = fmadd(w, load(v2 + at), sums.s2);
  };
  const auto whole = [](const double* q) { return PackD::load(q); };
  // The squared distances of the packet at i; a hidden sample's stands in as 1 (within range, it
  // moves no bound across a limit) and its weight is then 0.
  const auto dist_sq = [&](size_t i, const auto& load) {
    const PackD dx = x - load(&px_[i]), dy = y - load(&py_[i]);
    return fmadd(dx, dx, dy * dy);
  };
  size_t i = 0;
  // Two packets share one division (the divider is the bottleneck): with r = 1 / (a b),
  // 1 / a = b r and 1 / b = a r.
  for (; i + 2 * L <= n; i += 2 * L) {
    PackD a = dist_sq(i, whole), b = dist_sq(i + L, whole);
    Mask seen_a{}, seen_b{};
    if (hidden) {
      seen_a = Mask::where_zero(hidden + i);
      seen_b = Mask::where_zero(hidden + i + L);
      a = PackD::select(seen_a, a, one);
      b = PackD::select(seen_b, b, one);
    }
    least = min(least, min(a, b));
    most = max(most, max(a, b));
    const PackD r = one / (a * b);
    PackD wa = b * r, wb = a * r;
    if (hidden) {
      wa = PackD::select(seen_a, wa, zero);
      wb = PackD::select(seen_b, wb, zero);
    }
    add(even, wa, i, whole);
    add(odd, wb, i + L, whole);
  }
  for (; i < n; i += L) {  // at most two packets, the last masked: its lanes past the end weigh 0
    const size_t count = std::min(L, n - i);
    Mask in = Mask::first(static_cast<int>(count));
    if (hidden) {
      char flags[L] = {};
      std::copy_n(hidden + i, count, flags);
      in = in & Mask::where_zero(flags);
    }
    const auto masked = [in](const double* q) { return PackD::load(q, in); };
    const PackD a = PackD::select(in, dist_sq(i, masked), one);
    least = min(least, a);
    most = max(most, a);
    add(even, PackD::select(in, one / a, zero), i, masked);
  }
  if (!(least.min_lane() >= kLeastDistSq && most.max_lane() <= kMostDistSq)) return false;
  const double total = (even.total + odd.total).sum();
  if (total == 0) {  // every sample hidden: no value
    for (int c = 0; c < C; ++c) o[c] = std::numeric_limits<double>::quiet_NaN();
    return true;
  }
  o[0] = (even.s0 + odd.s0).sum() / total;
  if (C > 1) o[1] = (even.s1 + odd.s1).sum() / total;
  if (C > 2) o[2] = (even.s2 + odd.s2).sum() / total;
  return true;
#else
  (void)p, (void)hidden, (void)o;
  return false;
#endif
}

void Shepard::evaluate(std::span<const Vec2> points, std::span<double> out) const {
  const int C = samples_.channels;
  RR_CHECK(out.size() == points.size() * static_cast<size_t>(C), "output size does not match the query points");
  const size_t n = samples_.points.size();
  if (k_ > 0) {
    // The k nearest of coherent queries by tiles (kdtree.h), each query on its own values.
    for (size_t q = 0; q < points.size(); ++q)
      if (!points[q].allFinite())
        for (int c = 0; c < C; ++c) out[q * C + c] = std::numeric_limits<double>::quiet_NaN();
    const CoherentNearest::Tiles tiles = nearest_->tile(points);
    parallel_for_with_scratch<Shepard::Scratch>(0, static_cast<std::int64_t>(tiles.count()), 1, 2, [&](std::int64_t t, Scratch& s) {
      nearest_->visit_tile(tiles, points, static_cast<size_t>(t), s.tile,
                           [&](size_t q, std::span<const unsigned> idx, std::span<const double> d2, size_t nearest) {
                             local_value(points[q], idx, d2, nearest, s, &out[q * C]);
                           });
    });
    return;
  }
  parallel_for_with_scratch<Shepard::Scratch>(0, static_cast<std::int64_t>(points.size()), [&](std::int64_t k, Scratch& s) {
    const size_t q = static_cast<size_t>(k);
    double* o = &out[q * C];
    const Vec2 p = points[q];
    if (!p.allFinite()) {
      for (int c = 0; c < C; ++c) o[c] = std::numeric_limits<double>::quiet_NaN();
      return;
    }
    // With barriers, which samples p does not see (they weigh 0), found once for every path.
    bool hidden_known = false;
    if (one_pass_ && !(radius_sq_ < std::numeric_limits<double>::infinity())) {
      if (!barriers_.empty()) {
        visibility_->hidden_from(p, s.hidden);
        hidden_known = true;
      }
      if (global_value_one_pass(p, hidden_known ? s.hidden.data() : nullptr, o)) return;
    }
    // Otherwise (exact hits, extreme ranges, a radius, other mu, more channels): all samples at
    // once as Eigen arrays, with weights relative to the nearest sample's (SIMD, sums in a fixed
    // packet order).
    using Array = Eigen::Map<const Eigen::ArrayXd>;
    const Eigen::Index N = static_cast<Eigen::Index>(n);
    Eigen::ArrayXd& dist_sq = s.dist_sq;
    Eigen::ArrayXd& w = s.w;
    dist_sq = (p.x() - Array(px_.data(), N)).square() + (p.y() - Array(py_.data(), N)).square();
    if (!barriers_.empty()) {
      // A hidden sample is infinitely far: its weight is 0 below.
      if (!hidden_known) visibility_->hidden_from(p, s.hidden);
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
  });
}

}  // namespace radrecon
