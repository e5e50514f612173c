#include "reconstruct/nearest.h"

#include <algorithm>
#include <limits>
#include <vector>

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

namespace {

/// Buffers of the search for the nearest visible sample.
struct VisibleScratch {
  std::vector<unsigned> idx;
  std::vector<double> d2;
};

}  // namespace

void NearestSample::evaluate(std::span<const Vec2> points, std::span<double> out) const {
  const int C = samples_.channels;
  RR_CHECK(out.size() == points.size() * static_cast<size_t>(C), "output size does not match the query points");
  if (!barriers_.empty()) {
    // The nearest visible sample: the k nearest, k doubling until one of them is visible (in
    // (distance, index) order, so ties go as without barriers) or every sample was tried. Each
    // round tests its k from the first: equidistant points at the k-th place may come back in
    // another order with a larger k.
    const size_t n = samples_.points.size();
    parallel_for_with_scratch<VisibleScratch>(0, static_cast<std::int64_t>(points.size()), [&](std::int64_t k, VisibleScratch& s) {
      const size_t q = static_cast<size_t>(k);
      double* o = &out[q * C];
      for (int c = 0; c < C; ++c) o[c] = std::numeric_limits<double>::quiet_NaN();
      if (!points[q].allFinite()) return;
      for (size_t want = std::min<size_t>(8, n), tried = 0; tried < n; want = std::min(2 * want, n)) {
        s.idx.resize(want);
        s.d2.resize(want);
        tree_->nearest(points[q], static_cast<int>(want), s.idx, s.d2);
        for (size_t j = 0; j < want; ++j)
          if (!barriers_.blocks(points[q], samples_.points[s.idx[j]])) {
            for (int c = 0; c < C; ++c) o[c] = samples_.values[s.idx[j] * static_cast<size_t>(C) + c];
            return;
          }
        tried = want;
      }
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
