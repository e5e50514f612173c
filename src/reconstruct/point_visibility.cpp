// PointVisibility (barriers.h): which samples a query sees past the barriers, each point's side
// of every segment's line found once, and per cell of a grid the verdicts that hold for the whole
// cell.

#include "reconstruct/barriers.h"

#if defined(__AVX2__)
#include <immintrin.h>
#endif

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/check.h"
#include "reconstruct/orientation.h"

namespace radrecon {

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
