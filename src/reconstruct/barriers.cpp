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

namespace radrecon {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;

/// Shewchuk's bound on the round-off of the orientation determinant computed in doubles
/// ("Adaptive precision floating-point arithmetic", 1997: ccwerrboundA): when the computed value
/// exceeds it in magnitude, its sign is the exact sign.
constexpr double kOrientationErrorBound = (3.0 + 16.0 * 0x1p-53) * 0x1p-53;

/// Sign of the orientation of (a, b, c): +1 counter-clockwise, -1 clockwise, 0 collinear; exact.
/// The double determinant decides when it clears its error bound (almost always); CGAL's exact
/// predicate decides the rest.
[[gnu::noinline]] int exact_orientation(const Vec2& a, const Vec2& b, const Vec2& c) {
  const CGAL::Orientation o = CGAL::orientation(K::Point_2(a.x(), a.y()), K::Point_2(b.x(), b.y()),
                                                K::Point_2(c.x(), c.y()));
  return o == CGAL::LEFT_TURN ? 1 : (o == CGAL::RIGHT_TURN ? -1 : 0);
}
/// (The double path inlined into the visibility loops, the exact one called out of line.)
inline int orientation(const Vec2& a, const Vec2& b, const Vec2& c) {
  const double left = (b.x() - a.x()) * (c.y() - a.y()), right = (b.y() - a.y()) * (c.x() - a.x());
  const double det = left - right;
  const double bound = kOrientationErrorBound * (std::abs(left) + std::abs(right));
  if (det > bound) return 1;
  if (det < -bound) return -1;
  return exact_orientation(a, b, c);
}

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
  const Vec2 d = s.b - s.a;
  const double t = std::clamp((q - s.a).dot(d) / d.squaredNorm(), 0.0, 1.0);
  return (q - (s.a + t * d)).norm();
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

PointVisibility::PointVisibility(std::span<const Vec2> points, const Barriers& barriers)
    : points_(points), barriers_(&barriers) {
  const std::vector<BarrierSegment>& segs = barriers.segments();
  if (segs.empty() || segs.size() > kMaxSidedSegments) return;
  side_.resize(segs.size() * points.size());
  for (size_t k = 0; k < segs.size(); ++k)
    for (size_t i = 0; i < points.size(); ++i)
      side_[k * points.size() + i] = static_cast<signed char>(orientation(segs[k].a, segs[k].b, points[i]));
  px_.reserve(points.size());
  py_.reserve(points.size());
  for (const Vec2& p : points) px_.push_back(p.x()), py_.push_back(p.y());
  // The verdicts' grid: a square over the points and the segments' ends.
  static std::atomic<std::uint64_t> next_id{1};
  id_ = next_id.fetch_add(1, std::memory_order_relaxed);
  Vec2 lo = segs[0].a, hi = segs[0].a;
  for (const BarrierSegment& sg : segs) lo = lo.cwiseMin(sg.a).cwiseMin(sg.b), hi = hi.cwiseMax(sg.a).cwiseMax(sg.b);
  for (const Vec2& p : points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const double side_m = (hi - lo).maxCoeff();
  if (side_m > 0 && std::isfinite(side_m) && segs.size() * points.size() <= kMaxVerdictPairs) {
    grid_lo_ = lo;
    cell_m_ = side_m / kVerdictCells;
  }
}

/// What PointVisibility knows of the queries in one cell of its grid.
struct PointVisibility::Verdicts {
  std::uint64_t owner = 0;  ///< the PointVisibility's id_; 0: empty
  int cell = -1;
  std::vector<char> hidden;         ///< per point: hidden from every query in the cell
  std::vector<std::uint32_t> open;  ///< pairs k * n + i whose verdict differs within the cell
  bool used = false;  ///< false: too many pairs left open (kMaxOpenShare); the queries ask each pair
  /// The cell of the last query that found this slot holding another: classified only when a
  /// second query asks for it, so that scattered queries do not pay for cells they visit once.
  std::uint64_t asked_owner = 0;
  int asked_cell = -1;
};

namespace {

/// The sign of orient(u, v, c) at every corner of a box when the filter is certain of each and
/// they agree (orient is linear in c: then the same sign holds in the whole box); else 0.
int box_sign(const Vec2& u, const Vec2& v, const std::array<Vec2, 4>& corners) {
  int sign = 0;
  for (const Vec2& c : corners) {
    const double left = (v.x() - u.x()) * (c.y() - u.y()), right = (v.y() - u.y()) * (c.x() - u.x());
    const double det = left - right, bound = kOrientationErrorBound * (std::abs(left) + std::abs(right));
    const int s = det > bound ? 1 : det < -bound ? -1 : 0;
    if (s == 0 || (sign != 0 && s != sign)) return 0;
    sign = s;
  }
  return sign;
}

}  // namespace

std::array<Vec2, 4> PointVisibility::cell_corners(int cell) const {
  const int cx = cell % kVerdictCells, cy = cell / kVerdictCells;
  const double x0 = grid_lo_.x() + cx * cell_m_, y0 = grid_lo_.y() + cy * cell_m_;
  const double x1 = grid_lo_.x() + (cx + 1) * cell_m_, y1 = grid_lo_.y() + (cy + 1) * cell_m_;
  return {Vec2(x0, y0), Vec2(x1, y0), Vec2(x1, y1), Vec2(x0, y1)};
}

void PointVisibility::classify(int cell, Verdicts& v) const {
  const size_t n = points_.size();
  const std::vector<BarrierSegment>& segs = barriers_->segments();
  const std::array<Vec2, 4> corners = cell_corners(cell);
  v.hidden.assign(n, 0);
  v.open.clear();
  const size_t most_open = static_cast<size_t>(kMaxOpenShare * static_cast<double>(segs.size() * n));
  v.cell = cell;
  v.owner = id_;
  v.used = false;
  for (size_t k = 0; k < segs.size(); ++k) {
    const BarrierSegment& s = segs[k];
    // The query's side of the segment's line, for the whole cell if certain.
    const int cell_side = box_sign(s.a, s.b, corners);
    for (size_t i = 0; i < n; ++i) {
      if (v.hidden[i]) continue;
      const int point_side = side_[k * n + i];
      // A query on the point's side (or the point on the line while the query is not) sees it
      // past this segment.
      if (cell_side != 0 && point_side != -cell_side) continue;
      // Across: hidden where orient(q, p, a) and orient(q, p, b) differ in sign, i.e.
      // orient(p, a, q) and orient(p, b, q).
      const int s1 = box_sign(points_[i], s.a, corners), s2 = box_sign(points_[i], s.b, corners);
      if (s1 != 0 && s2 != 0) {
        if (s1 == s2) continue;                 // the line (q, p) passes beside the segment
        if (cell_side != 0) {
          v.hidden[i] = 1;  // strictly across, and through the segment
          continue;
        }
      }
      v.open.push_back(static_cast<std::uint32_t>(k * n + i));
      if (v.open.size() > most_open) {  // no use: the queries ask each pair
        v.open.clear();
        return;
      }
    }
  }
  v.used = true;
}

bool PointVisibility::pair_hides(const Vec2& q, size_t k, size_t i) const {
  const BarrierSegment& s = barriers_->segments()[k];
  const int point_side = side_[k * points_.size() + i];
  const int oq = orientation(s.a, s.b, q);
  if (oq == 0) return point_side == 0 && segment_blocked(q, points_[i], s);
  return point_side == -oq && orientation(q, points_[i], s.a) * orientation(q, points_[i], s.b) <= 0;
}

void PointVisibility::hidden_from(const Vec2& q, std::vector<char>& hidden) const {
  const size_t n = points_.size();
  const std::vector<BarrierSegment>& segs = barriers_->segments();
  hidden.assign(n, 0);
  if (side_.empty()) {  // no barrier, or many: the grid
    for (size_t i = 0; i < n; ++i) hidden[i] = barriers_->blocks(q, points_[i]);
    return;
  }
  // In the verdicts' grid: the cell's verdicts, and the pairs it left open.
  if (cell_m_ > 0) {
    const double fx = (q.x() - grid_lo_.x()) / cell_m_, fy = (q.y() - grid_lo_.y()) / cell_m_;
    if (fx >= 0 && fy >= 0 && fx < kVerdictCells && fy < kVerdictCells) {  // false for NaN
      const int cell = static_cast<int>(fy) * kVerdictCells + static_cast<int>(fx);
      // A thread's cells by their index: a raster's rows of cells fit side by side.
      constexpr size_t kCachedCells = 2 * kVerdictCells;
      thread_local std::array<Verdicts, kCachedCells> cache;
      Verdicts& v = cache[static_cast<size_t>(cell) % kCachedCells];
      if (v.owner != id_ || v.cell != cell) {
        if (v.asked_owner == id_ && v.asked_cell == cell) {
          classify(cell, v);
        } else {
          v.asked_owner = id_;
          v.asked_cell = cell;
        }
      }
      // The verdicts hold in the cell's box as its corners are rounded: q must lie in it.
      const std::array<Vec2, 4> box = cell_corners(cell);
      const bool inside = q.x() >= box[0].x() && q.x() <= box[2].x() && q.y() >= box[0].y() && q.y() <= box[2].y();
      if (v.owner == id_ && v.cell == cell && v.used && inside) {
        std::copy(v.hidden.begin(), v.hidden.end(), hidden.begin());
        for (const std::uint32_t pair : v.open) {
          const size_t i = pair % n;
          if (!hidden[i]) hidden[i] = pair_hides(q, pair / n, i);
        }
        return;
      }
    }
  }
  // The rule of segment_blocked(), with the points' sides known: a point across the segment's
  // line from q is hidden when the segment meets line (q, p) between its ends (o1 * o2 <= 0);
  // when q and p both lie on the line, the collinear case decides.
  char* const out = hidden.data();
  for (size_t k = 0; k < segs.size(); ++k) {
    const BarrierSegment& s = segs[k];
    const int oq = orientation(s.a, s.b, q);
    const signed char* side = &side_[k * n];
    if (oq == 0) {  // q on the segment's line: only the points on it can be hidden, by the collinear rule
      for (size_t i = 0; i < n; ++i)
        if (!out[i] && side[i] == 0) out[i] = segment_blocked(q, points_[i], s);
      continue;
    }
    // With AVX2, orientation(q, p_i, a) and orientation(q, p_i, b) four points at a time, in the
    // same operations as orientation()'s filter (so with its verdicts): a point across the line
    // whose two signs are both certain is decided here; the rare uncertain one below.
    const signed char across = static_cast<signed char>(-oq);
    bool uncertain = false;
    size_t i = 0;
#if defined(__AVX2__)
    const double ax = s.a.x() - q.x(), ay = s.a.y() - q.y(), bx = s.b.x() - q.x(), by = s.b.y() - q.y();
    const __m256d qx4 = _mm256_set1_pd(q.x()), qy4 = _mm256_set1_pd(q.y());
    const __m256d ax4 = _mm256_set1_pd(ax), ay4 = _mm256_set1_pd(ay), bx4 = _mm256_set1_pd(bx), by4 = _mm256_set1_pd(by);
    const __m256d bound4 = _mm256_set1_pd(kOrientationErrorBound), sign = _mm256_set1_pd(-0.0);
    for (; i + 4 <= n; i += 4) {
      const __m256d dx = _mm256_sub_pd(_mm256_loadu_pd(&px_[i]), qx4), dy = _mm256_sub_pd(_mm256_loadu_pd(&py_[i]), qy4);
      const __m256d la = _mm256_mul_pd(dx, ay4), ra = _mm256_mul_pd(dy, ax4), da = _mm256_sub_pd(la, ra);
      const __m256d lb = _mm256_mul_pd(dx, by4), rb = _mm256_mul_pd(dy, bx4), db = _mm256_sub_pd(lb, rb);
      const __m256d ea = _mm256_mul_pd(bound4, _mm256_add_pd(_mm256_andnot_pd(sign, la), _mm256_andnot_pd(sign, ra)));
      const __m256d eb = _mm256_mul_pd(bound4, _mm256_add_pd(_mm256_andnot_pd(sign, lb), _mm256_andnot_pd(sign, rb)));
      const int a_pos = _mm256_movemask_pd(_mm256_cmp_pd(da, ea, _CMP_GT_OQ));
      const int a_neg = _mm256_movemask_pd(_mm256_cmp_pd(da, _mm256_xor_pd(ea, sign), _CMP_LT_OQ));
      const int b_pos = _mm256_movemask_pd(_mm256_cmp_pd(db, eb, _CMP_GT_OQ));
      const int b_neg = _mm256_movemask_pd(_mm256_cmp_pd(db, _mm256_xor_pd(eb, sign), _CMP_LT_OQ));
      const int opposite = (side[i] == across) | (side[i + 1] == across) << 1 | (side[i + 2] == across) << 2 |
                           (side[i + 3] == across) << 3;
      const int certain = (a_pos | a_neg) & (b_pos | b_neg);
      const int apart = (a_pos & b_neg) | (a_neg & b_pos);  // o1 * o2 < 0 where certain
      const int hides = opposite & certain & apart;
      for (int lane = 0; lane < 4; ++lane) out[i + lane] |= static_cast<char>((hides >> lane) & 1);
      uncertain |= (opposite & ~certain) != 0;
    }
#endif
    // Point by point: those the packets left (all of them without AVX2), or all again when a
    // sign was uncertain (the certain ones get the same verdict).
    for (i = uncertain ? 0 : i; i < n; ++i)
      if (!out[i] && side[i] == across) out[i] = orientation(q, points_[i], s.a) * orientation(q, points_[i], s.b) <= 0;
  }
}

void PointVisibility::visible_from(const Vec2& q, std::vector<unsigned>& out, std::vector<char>& hidden) const {
  hidden_from(q, hidden);
  out.clear();
  for (size_t i = 0; i < hidden.size(); ++i)
    if (!hidden[i]) out.push_back(static_cast<unsigned>(i));
}

}  // namespace radrecon
