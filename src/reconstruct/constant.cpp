#include "reconstruct/constant.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/check.h"
#include "core/parse.h"
#include "core/parallel.h"
#include "core/tolerances.h"

namespace radrecon {

PiecewiseConstant::PiecewiseConstant(CellSamples samples) : samples_(std::move(samples)) {
  if (samples_.cells.empty()) throw ReconstructionError("piecewise constant needs at least one cell");
  RR_CHECK(samples_.values.size() == samples_.cells.size() * samples_.channels, "values do not match cells");
  RR_CHECK(samples_.triangles.empty() || samples_.triangles.size() == samples_.cells.size(), "triangles do not match cells");
  bounds_ = samples_.cells[0];
  double min_w = std::numeric_limits<double>::infinity(), min_h = min_w;
  for (const Rect& r : samples_.cells) {
    if (!(r.x1 > r.x0 && r.y1 > r.y0))
      throw ReconstructionError("a cell has no extent: [" + format_number(r.x0) + ", " + format_number(r.x1) + "] x [" +
                                format_number(r.y0) + ", " + format_number(r.y1) + "]");
    bounds_.x0 = std::min(bounds_.x0, r.x0);
    bounds_.y0 = std::min(bounds_.y0, r.y0);
    bounds_.x1 = std::max(bounds_.x1, r.x1);
    bounds_.y1 = std::max(bounds_.y1, r.y1);
    min_w = std::min(min_w, r.x1 - r.x0);
    min_h = std::min(min_h, r.y1 - r.y0);
  }
  // One bucket per smallest cell, at most 1024 per axis: a bucket then meets O(1) cells of a grid
  // or of a quadtree's finest level.
  buckets_x_ = static_cast<int>(std::clamp(std::ceil((bounds_.x1 - bounds_.x0) / min_w), 1.0, 1024.0));
  buckets_y_ = static_cast<int>(std::clamp(std::ceil((bounds_.y1 - bounds_.y0) / min_h), 1.0, 1024.0));
  buckets_.resize(static_cast<size_t>(buckets_x_) * buckets_y_);
  const double bw = (bounds_.x1 - bounds_.x0) / buckets_x_, bh = (bounds_.y1 - bounds_.y0) / buckets_y_;
  for (size_t k = 0; k < samples_.cells.size(); ++k) {
    const Rect& r = samples_.cells[k];
    int i0 = std::clamp(static_cast<int>(std::floor((r.x0 - bounds_.x0) / bw)), 0, buckets_x_ - 1);
    // Register the cell in every bucket its closed extent touches (a query is found by the
    // bucket of its clamped position, which may be the one just past the cell's far edge).
    int i1 = std::clamp(static_cast<int>(std::floor((r.x1 - bounds_.x0) / bw)), 0, buckets_x_ - 1);
    int j0 = std::clamp(static_cast<int>(std::floor((r.y0 - bounds_.y0) / bh)), 0, buckets_y_ - 1);
    int j1 = std::clamp(static_cast<int>(std::floor((r.y1 - bounds_.y0) / bh)), 0, buckets_y_ - 1);
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) buckets_[static_cast<size_t>(j) * buckets_x_ + i].push_back(static_cast<unsigned>(k));
  }
}

long PiecewiseConstant::locate(const Vec2& q) const {
  if (!q.allFinite()) return -1;
  const double x = std::clamp(q.x(), bounds_.x0, bounds_.x1), y = std::clamp(q.y(), bounds_.y0, bounds_.y1);
  const double bw = (bounds_.x1 - bounds_.x0) / buckets_x_, bh = (bounds_.y1 - bounds_.y0) / buckets_y_;
  int i = std::clamp(static_cast<int>((x - bounds_.x0) / bw), 0, buckets_x_ - 1);
  int j = std::clamp(static_cast<int>((y - bounds_.y0) / bh), 0, buckets_y_ - 1);
  if (!samples_.triangles.empty()) return locate_triangle(q, buckets_[static_cast<size_t>(j) * buckets_x_ + i]);
  for (unsigned k : buckets_[static_cast<size_t>(j) * buckets_x_ + i]) {
    const Rect& r = samples_.cells[k];
    bool in_x = (x >= r.x0 && x < r.x1) || (x == r.x1 && r.x1 == bounds_.x1);
    bool in_y = (y >= r.y0 && y < r.y1) || (y == r.y1 && r.y1 == bounds_.y1);
    if (in_x && in_y) return static_cast<long>(k);
  }
  return -1;
}

long PiecewiseConstant::locate_triangle(const Vec2& q, const std::vector<unsigned>& bucket) const {
  // The triangle whose smallest barycentric coordinate at q is largest: the one containing q, or
  // for a point on a shared edge either neighbour, and for a point outside by rounding only
  // (within tol::kQuadEdgeParameter of the side's size, in barycentric terms) the nearest.
  long best = -1;
  double best_min = -std::numeric_limits<double>::infinity();
  for (unsigned k : bucket) {
    const auto& t = samples_.triangles[k];
    const double area2 = cross(t[1] - t[0], t[2] - t[0]);
    const double b0 = cross(t[1] - q, t[2] - q) / area2, b1 = cross(t[2] - q, t[0] - q) / area2;
    const double lowest = std::min({b0, b1, 1 - b0 - b1});
    if (lowest > best_min) {
      best_min = lowest;
      best = static_cast<long>(k);
    }
  }
  return best_min >= -tol::kQuadEdgeParameter ? best : -1;
}

void PiecewiseConstant::evaluate(std::span<const Vec2> points, std::span<double> out) const {
  const int C = samples_.channels;
  RR_CHECK(out.size() == points.size() * C, "output size does not match the query points");
  parallel_for(0, static_cast<std::int64_t>(points.size()), [&](std::int64_t q) {
    const size_t k = static_cast<size_t>(q);
    const long cell = locate(points[k]);
    for (int c = 0; c < C; ++c)
      out[k * C + c] = cell < 0 ? std::numeric_limits<double>::quiet_NaN()
                                : samples_.values[static_cast<size_t>(cell) * C + c];
  });
}

}  // namespace radrecon
