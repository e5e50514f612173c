#include "reconstruct/nearest.h"

#include <limits>

#include "core/check.h"
#include "core/parallel.h"
#include "reconstruct/kdtree.h"

namespace radrecon {

NearestSample::NearestSample(ScatteredSamples samples)
    : samples_(std::move(samples)), tree_(std::make_unique<KdTree2>(samples_.points)) {
  RR_CHECK(!samples_.points.empty(), "nearest-sample reconstruction needs a sample");
}

NearestSample::NearestSample(ScatteredSamples samples, Barriers barriers) : NearestSample(std::move(samples)) {
  barriers_ = std::move(barriers);
}

NearestSample::~NearestSample() = default;

void NearestSample::evaluate(std::span<const Vec2> points, std::span<double> out) const {
  const int C = samples_.channels;
  RR_CHECK(out.size() == points.size() * static_cast<size_t>(C), "output size does not match the query points");
  if (!barriers_.empty()) {
    // The nearest visible sample, ties as without barriers ((distance, index) order).
    parallel_for_with_scratch<VisibleNeighbours>(0, static_cast<std::int64_t>(points.size()),
                                                 [&](std::int64_t k, VisibleNeighbours& found) {
      const size_t q = static_cast<size_t>(k);
      double* o = &out[q * C];
      const bool seen = points[q].allFinite() && nearest_visible(*tree_, samples_.points, barriers_, points[q], 1, found) == 1;
      for (int c = 0; c < C; ++c)
        o[c] = seen ? samples_.values[found.idx[0] * static_cast<size_t>(C) + c] : std::numeric_limits<double>::quiet_NaN();
    });
    return;
  }
  parallel_for(0, static_cast<std::int64_t>(points.size()), [&](std::int64_t k) {
    const size_t q = static_cast<size_t>(k);
    if (!points[q].allFinite()) {
      for (int c = 0; c < C; ++c) out[q * C + c] = std::numeric_limits<double>::quiet_NaN();
      return;
    }
    unsigned idx[1];
    double d2[1];
    tree_->nearest(points[q], 1, idx, d2);
    for (int c = 0; c < C; ++c) out[q * C + c] = samples_.values[idx[0] * static_cast<size_t>(C) + c];
  });
}

}  // namespace radrecon
