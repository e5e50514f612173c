#include "reconstruct/barriers.h"

#if defined(__AVX2__)
#include <immintrin.h>
#endif

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <string>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include "core/check.h"
#include "core/parse.h"
#include "core/tolerances.h"
#include "reconstruct/kdtree.h"
#include "reconstruct/orientation.h"

namespace radrecon {

int exact_orientation(const Vec2& a, const Vec2& b, const Vec2& c) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  const CGAL::Orientation o = CGAL::orientation(K::Point_2(a.x(), a.y()), K::Point_2(b.x(), b.y()),
                                                K::Point_2(c.x(), c.y()));
  return o == CGAL::LEFT_TURN ? 1 : (o == CGAL::RIGHT_TURN ? -1 : 0);
}

namespace {

/// The grid index of coordinate v (origin o, cells of cell_m, n of them), clamped to [0, n) in
/// double before the conversion: far points (up to 1e100) would overflow an int.
int grid_index(double v, double o, double cell_m, int n) {
  return static_cast<int>(std::clamp(std::floor((v - o) / cell_m), 0.0, static_cast<double>(n - 1)));
}

/// Cells of the barrier grid per segment, on average: a few segments per cell keeps the tests
/// per cell low without a grid much larger than the segments.
constexpr double kSegmentsPerCell = 0.5;
/// At most this many cells along an axis.
constexpr int kMaxGridSide = 1024;
/// A cell is skipped only when all its corners lie beyond this fraction of the magnitudes in
/// their side test on one side of the query's line (blocks()): some 45 ulps, far above the test's
/// round-off.
constexpr double kCellSkipRelative = 1e-14;

}  // namespace

bool all_on_one_line(std::span<const Vec2> points) {
  size_t second = 1;
  while (second < points.size() && points[second] == points[0]) ++second;
  for (size_t i = second + 1; i < points.size(); ++i)
    if (orientation(points[0], points[second], points[i]) != 0) return false;
  return true;
}

bool segment_blocked(const Vec2& p, const Vec2& q, const BarrierSegment& s) {
  const int o1 = orientation(p, q, s.a), o2 = orientation(p, q, s.b);
  if (o1 == 0 && o2 == 0) {
    // All four on one line: blocked when the open interval (p, q) overlaps [a, b] along it.
    const int axis = std::abs(q.x() - p.x()) >= std::abs(q.y() - p.y()) ? 0 : 1;
    const double lo = std::min(p[axis], q[axis]), hi = std::max(p[axis], q[axis]);
    const double a = std::min(s.a[axis], s.b[axis]), b = std::max(s.a[axis], s.b[axis]);
    return lo < b && a < hi && lo < hi;
  }
  const int o3 = orientation(s.a, s.b, p), o4 = orientation(s.a, s.b, q);
  // p or q on the barrier's line (or both strictly on one side): the open segment does not meet it.
  if (o3 * o4 >= 0) return false;
  // p and q strictly on opposite sides of the barrier's line: the lines meet strictly between
  // p and q; blocked if that point is on [a, b] (an end point included).
  return o1 * o2 <= 0;
}

Result<Barriers> Barriers::from_polylines(std::span<const Polyline> polylines) {
  std::vector<BarrierSegment> segments;
  for (size_t k = 0; k < polylines.size(); ++k) {
    const Polyline& line = polylines[k];
    const std::string where = "barrier " + std::to_string(k + 1);
    if (line.size() < 2) return Failure{where + " has " + std::to_string(line.size()) + " point(s); a line needs 2"};
    for (size_t i = 0; i < line.size(); ++i)
      if (!line[i].allFinite())
        return Failure{where + ", point " + std::to_string(i + 1) + ": coordinates must be finite numbers"};
    for (size_t i = 0; i + 1 < line.size(); ++i) {
      if (line[i] == line[i + 1])
        return Failure{where + ", points " + std::to_string(i + 1) + " and " + std::to_string(i + 2) +
                       " coincide at (" + format_number(line[i].x()) + ", " + format_number(line[i].y()) +
                       "): a segment of zero length"};
      segments.push_back({line[i], line[i + 1]});
    }
  }
  return Barriers(std::move(segments));
}

Barriers::Barriers(std::vector<BarrierSegment> segments) : segments_(std::move(segments)) {
  if (segments_.empty()) return;
  Vec2 lo = segments_[0].a, hi = lo;
  for (const BarrierSegment& s : segments_) {
    lo = lo.cwiseMin(s.a).cwiseMin(s.b);
    hi = hi.cwiseMax(s.a).cwiseMax(s.b);
  }
  const Vec2 extent = hi - lo;
  const double side = extent.maxCoeff();  // > 0: segments have a length
  // About kSegmentsPerCell segments a cell over the box's area (segments on one line: along it),
  // at most kMaxGridSide cells a side.
  const double cells = std::max(1.0, static_cast<double>(segments_.size()) / kSegmentsPerCell);
  const double area = extent.x() * extent.y();
  cell_m_ = std::max(area > 0 ? std::sqrt(area / cells) : side / cells, side / kMaxGridSide);
  origin_ = lo;
  nx_ = std::clamp(static_cast<int>(std::floor(extent.x() / cell_m_)) + 1, 1, kMaxGridSide + 1);
  ny_ = std::clamp(static_cast<int>(std::floor(extent.y() / cell_m_)) + 1, 1, kMaxGridSide + 1);
  // Each segment goes into every cell its bounding box covers (conservative).
  std::vector<std::vector<unsigned>> buckets(static_cast<size_t>(nx_) * ny_);
  const auto cell = [&](double v, double o, int n) { return grid_index(v, o, cell_m_, n); };
  for (size_t k = 0; k < segments_.size(); ++k) {
    const BarrierSegment& s = segments_[k];
    const int i0 = cell(std::min(s.a.x(), s.b.x()), origin_.x(), nx_), i1 = cell(std::max(s.a.x(), s.b.x()), origin_.x(), nx_);
    const int j0 = cell(std::min(s.a.y(), s.b.y()), origin_.y(), ny_), j1 = cell(std::max(s.a.y(), s.b.y()), origin_.y(), ny_);
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) buckets[static_cast<size_t>(j) * nx_ + i].push_back(static_cast<unsigned>(k));
  }
  cell_start_.assign(buckets.size() + 1, 0);
  for (size_t c = 0; c < buckets.size(); ++c) cell_start_[c + 1] = cell_start_[c] + static_cast<unsigned>(buckets[c].size());
  cell_segments_.reserve(cell_start_.back());
  for (const auto& b : buckets) cell_segments_.insert(cell_segments_.end(), b.begin(), b.end());
}

namespace {

/// Whether the boxes of [p, q] and of s overlap (closed): a segment whose box misses the
/// barrier's cannot meet it, and the test is far cheaper than the predicates.
inline bool boxes_overlap(const Vec2& p, const Vec2& q, const BarrierSegment& s) {
  return std::max(p.x(), q.x()) >= std::min(s.a.x(), s.b.x()) && std::min(p.x(), q.x()) <= std::max(s.a.x(), s.b.x()) &&
         std::max(p.y(), q.y()) >= std::min(s.a.y(), s.b.y()) && std::min(p.y(), q.y()) <= std::max(s.a.y(), s.b.y());
}

/// Up to this many segments are tested one by one, without the grid.
constexpr size_t kDirectTestSegments = 8;


}  // namespace

bool Barriers::blocks(const Vec2& p, const Vec2& q) const {
  if (segments_.size() <= kDirectTestSegments) {
    for (const BarrierSegment& s : segments_)
      if (boxes_overlap(p, q, s) && segment_blocked(p, q, s)) return true;
    return false;
  }
  // The cells of the query segment's bounding box, clipped to the grid; a segment outside the
  // grid's box meets no barrier there. Cells are visited in the box (simple and exact: every
  // cell the segment passes through is in it); each candidate is tested exactly.
  const Vec2 lo = p.cwiseMin(q), hi = p.cwiseMax(q);
  const double gx1 = origin_.x() + nx_ * cell_m_, gy1 = origin_.y() + ny_ * cell_m_;
  if (hi.x() < origin_.x() || hi.y() < origin_.y() || lo.x() > gx1 || lo.y() > gy1) return false;
  const int i0 = grid_index(lo.x(), origin_.x(), cell_m_, nx_), i1 = grid_index(hi.x(), origin_.x(), cell_m_, nx_);
  const int j0 = grid_index(lo.y(), origin_.y(), cell_m_, ny_), j1 = grid_index(hi.y(), origin_.y(), cell_m_, ny_);
  const Vec2 d = q - p;
  const double p_size = p.cwiseAbs().maxCoeff();
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i) {
      // Skip cells of the box that the segment's line misses (the cell's corners all strictly on
      // one side). The side of corner c is d x (c - p), d = q - p; with d, c - p and the products
      // rounded, its error is below a few ulps of (|d| + |p| + |q|) (|c| + |p|) (max norms), so
      // a margin far above that never skips a cell the segment touches (the exact tests decide).
      const double x0 = origin_.x() + i * cell_m_, x1 = x0 + cell_m_, y0 = origin_.y() + j * cell_m_, y1 = y0 + cell_m_;
      const double corner = std::max({std::abs(x0), std::abs(x1), std::abs(y0), std::abs(y1)});
      const double margin = kCellSkipRelative * (d.cwiseAbs().maxCoeff() + p_size + q.cwiseAbs().maxCoeff()) * (corner + p_size);
      const auto side = [&](double cx, double cy) { return d.x() * (cy - p.y()) - d.y() * (cx - p.x()); };
      const double s00 = side(x0, y0), s10 = side(x1, y0), s01 = side(x0, y1), s11 = side(x1, y1);
      if ((s00 > margin && s10 > margin && s01 > margin && s11 > margin) ||
          (s00 < -margin && s10 < -margin && s01 < -margin && s11 < -margin))
        continue;
      const size_t c = static_cast<size_t>(j) * nx_ + i;
      for (unsigned k = cell_start_[c]; k < cell_start_[c + 1]; ++k) {
        const BarrierSegment& s = segments_[cell_segments_[k]];
        if (boxes_overlap(p, q, s) && segment_blocked(p, q, s)) return true;
      }
    }
  return false;
}

namespace {

/// The distance from q to the closed segment s: to the point of s nearest q (its projection onto
/// the segment's line, clamped to the end points).
double distance_to_segment(const Vec2& q, const BarrierSegment& s) {
  return (q - (s.a + nearest_on_segment_t(q, s.a, s.b) * (s.b - s.a))).norm();
}

}  // namespace

double Barriers::distance_to(const Vec2& q, double max_distance) const {
  if (!q.allFinite()) return max_distance;
  double best = max_distance;
  if (segments_.size() <= kDirectTestSegments) {
    for (const BarrierSegment& s : segments_) best = std::min(best, distance_to_segment(q, s));
    return best;
  }
  if (!(max_distance > 0)) return max_distance;  // nothing can be nearer (and NaN stays NaN)
  // The cells that the box [q - max_distance, q + max_distance] overlaps, clipped to the grid: a
  // segment with a point nearer than max_distance has that point in the box, and in a cell its
  // own box covers (segments are bucketed by their boxes), so it is among them. Indices are
  // clamped in double before the conversion (max_distance may be infinite).
  const double gx1 = origin_.x() + nx_ * cell_m_, gy1 = origin_.y() + ny_ * cell_m_;
  if (q.x() + max_distance < origin_.x() || q.y() + max_distance < origin_.y() || q.x() - max_distance > gx1 ||
      q.y() - max_distance > gy1)
    return max_distance;
  const int i0 = grid_index(q.x() - max_distance, origin_.x(), cell_m_, nx_);
  const int i1 = grid_index(q.x() + max_distance, origin_.x(), cell_m_, nx_);
  const int j0 = grid_index(q.y() - max_distance, origin_.y(), cell_m_, ny_);
  const int j1 = grid_index(q.y() + max_distance, origin_.y(), cell_m_, ny_);
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i) {
      const size_t c = static_cast<size_t>(j) * nx_ + i;
      for (unsigned k = cell_start_[c]; k < cell_start_[c + 1]; ++k)
        best = std::min(best, distance_to_segment(q, segments_[cell_segments_[k]]));
    }
  return best;
}

bool Barriers::none_within(const Vec2& q, double reach_m) const {
  if (segments_.empty()) return true;
  // Margins above the distance's round-off: relative to the reach, and absolute, relative to the
  // coordinates' magnitude (the distance is computed from differences of coordinates).
  const Vec2 far_corner = origin_ + Vec2(nx_ * cell_m_, ny_ * cell_m_);
  const double size = std::max(origin_.cwiseAbs().maxCoeff(), far_corner.cwiseAbs().maxCoeff());
  const double margin = tol::kBarrierReachRelative * (reach_m + q.cwiseAbs().maxCoeff() + size);
  const double r = reach_m + margin;
  return distance_to(q, 2 * r) > r;
}

size_t nearest_visible(const KdTree2& tree, std::span<const Vec2> points, const Barriers& barriers, const Vec2& q,
                       size_t k, VisibleNeighbours& found) {
  constexpr size_t kFirstRound = 8;
  const size_t n = std::min(points.size(), std::max(kMaxVisibleCandidates, 2 * k));
  for (size_t want = std::min(std::max(2 * k, kFirstRound), n);; want = std::min(2 * want, n)) {
    found.candidates.resize(want);
    found.candidates_dist_sq.resize(want);
    tree.nearest(q, static_cast<int>(want), found.candidates, found.candidates_dist_sq);
    found.idx.clear();
    found.dist_sq.clear();
    for (size_t j = 0; j < want && found.idx.size() < k; ++j)
      if (!barriers.blocks(q, points[found.candidates[j]])) {
        found.idx.push_back(found.candidates[j]);
        found.dist_sq.push_back(found.candidates_dist_sq[j]);
      }
    if (found.idx.size() == k || want == n) return found.idx.size();
  }
}

}  // namespace radrecon
