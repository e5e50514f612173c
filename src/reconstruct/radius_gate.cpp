#include "reconstruct/radius_gate.h"

#include <limits>
#include <vector>

#include "core/check.h"
#include "core/parallel.h"
#include "reconstruct/kdtree.h"

namespace radrecon {

RadiusGate::RadiusGate(std::unique_ptr<Interpolant> inner, const ScatteredSamples& samples, double radius_m, int min_points)
    : inner_(std::move(inner)), tree_(std::make_unique<KdTree2>(samples.points)), radius_sq_(radius_m * radius_m),
      min_points_(min_points) {
  RR_CHECK(radius_m > 0 && min_points >= 1, "search radius out of range");
}

RadiusGate::~RadiusGate() = default;

namespace {
struct GateScratch {
  std::vector<unsigned> idx;
  std::vector<double> d2;
};
}  // namespace

void RadiusGate::evaluate(std::span<const Vec2> points, std::span<double> out) const {
  inner_->evaluate(points, out);
  const int C = channels();
  parallel_for_with_scratch<GateScratch>(0, static_cast<std::int64_t>(points.size()), [&](std::int64_t q, GateScratch& s) {
    const Vec2& p = points[static_cast<size_t>(q)];
    if (!p.allFinite()) return;
    // At least min_points samples within the radius <=> the min_points-th nearest is within it.
    s.idx.resize(static_cast<size_t>(min_points_));
    s.d2.resize(static_cast<size_t>(min_points_));
    const size_t found = tree_->nearest(p, min_points_, s.idx, s.d2);
    if (found < static_cast<size_t>(min_points_) || s.d2[found - 1] > radius_sq_)
      for (int c = 0; c < C; ++c) out[static_cast<size_t>(q) * C + c] = std::numeric_limits<double>::quiet_NaN();
  });
}

}  // namespace radrecon
