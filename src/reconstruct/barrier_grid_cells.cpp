// BarrierGrid's grid cells against the barriers (barrier_grid.h, "Cost"): which cells may lie
// near one (their queries take the barrier path), and the proof that a cell sees the sites its
// queries consult alike from all of it, by exact orientations at its corners.

#include <algorithm>
#include <cmath>

#include "reconstruct/barrier_grid_scratch.h"
#include "reconstruct/orientation.h"

namespace radrecon {

namespace {

using barrier_grid_detail::kMemoBoxMargin;
using barrier_grid_detail::kMemoMostSegments;
using barrier_grid_detail::kWindow;

/// Barrier marking: points along each barrier segment at most this fraction of the smaller grid
/// spacing apart; each marks its cell and the cells around it, so that every cell the segment
/// touches is marked.
constexpr double kMarkStep = 0.5;

/// The common sign of orientation(x, y, c) over the corners c, when all are strictly that sign;
/// else 0.
int strict_side(const Vec2& x, const Vec2& y, const std::array<Vec2, 4>& corners) {
  const int first = orientation(x, y, corners[0]);
  if (first == 0) return 0;
  for (size_t k = 1; k < corners.size(); ++k)
    if (orientation(x, y, corners[k]) != first) return 0;
  return first;
}

/// Whether segment g blocks the sight line from every point q of the convex box (corners) to the
/// site p alike, or from none of them, by orientations (exact) that are linear in q: each holds
/// for the whole box when it holds strictly at its corners. The rule (barriers.h) decides the
/// open segment (q, p) against the closed [a, b] from the signs of orient(a, b, q), orient(a, b,
/// p), orient(p, a, q) and orient(p, b, q), so the answer is the same wherever none of the signs
/// that matter changes:
///   - the queries strictly on one side of line(a, b), p on that side or on the line: never
///     blocked;
///   - the box and p strictly on opposite sides, orient(p, a, .) and orient(p, b, .) strictly
///     constant: where (q, p) crosses the line is on the same side of a and of b for all q;
///   - p off line(a, b) and the box strictly outside the cone at p spanned by a and b (the
///     cone holds [a, b], and every sight line from p to a point of it): never blocked.
/// `line`: the common strict sign of orient(a, b, .) over the queries concerned (strict_side() of
/// the box, or the side of the box's part that the memo's key holds), 0 when there is none.
bool blocks_alike(const std::array<Vec2, 4>& corners, const Vec2& p, const BarrierSegment& g, int line) {
  const int site = orientation(g.a, g.b, p);
  if (line != 0 && (site == line || site == 0)) return true;
  const int by_a = strict_side(p, g.a, corners), by_b = strict_side(p, g.b, corners);
  if (line != 0 && site == -line && by_a != 0 && by_b != 0) return true;
  if (site == 0) return false;
  return (by_a != 0 && by_a == -orientation(p, g.a, g.b)) || (by_b != 0 && by_b == -orientation(p, g.b, g.a));
}

/// Whether the boxes [lo0, hi0] and [lo1, hi1] meet (closed).
bool boxes_meet(const Vec2& lo0, const Vec2& hi0, const Vec2& lo1, const Vec2& hi1) {
  return lo0.x() <= hi1.x() && lo1.x() <= hi0.x() && lo0.y() <= hi1.y() && lo1.y() <= hi0.y();
}

}  // namespace

void BarrierGrid::mark_cells_near_barriers() {
  const int cx = nodes_.nx - 1, cy = nodes_.ny - 1;
  near_.assign(static_cast<size_t>(cx) * cy, 0);
  if (barriers_.empty()) return;
  const double dx = nodes_.dx, dy = nodes_.dy;
  const double step = kMarkStep * std::min(dx, dy);
  // The cells to mark around each sample point of a barrier (rx, ry along x, y), and how far
  // beyond the grid a barrier can matter (margin).
  int rx, ry;
  double margin;
  if (kind_ == Kind::bilinear) {
    // A query in cell (i, j) tests segments from it to sites whose segments stay within the
    // cells up to `reach` away (the 3 x 3 cells whose centres the corners share, or the cell
    // itself for nodes). A barrier can only block them if it touches one of those cells. Every
    // sample point marks its cell and those around it: one more than reach.
    const int reach = cell_sites_ ? 1 : 0;
    rx = ry = reach + 1;
    margin = 0;  // all sites and clamped queries lie in the grid's closed box
  } else {
    // Bicubic: every cell with a point nearer a barrier than plain_distance_. Such a point is
    // within plain_distance_ of a point of the barrier, which lies within step / 2 of a sample
    // point; so within plain_distance_ + step of a sample point along each axis, hence at most
    // ceil(that / spacing) + 1 cells from the sample point's cell (clamping onto the grid only
    // brings them closer).
    margin = plain_distance_ + step;
    rx = static_cast<int>(std::ceil(margin / dx)) + 1;
    ry = static_cast<int>(std::ceil(margin / dy)) + 1;
  }
  // The grid's box, one cell wider and widened by the margin: the part of a barrier that can matter.
  const Vec2 lo(nodes_.x0 - margin - dx, nodes_.y0 - margin - dy),
      hi(nodes_.x0 + cx * dx + margin + dx, nodes_.y0 + cy * dy + margin + dy);
  for (const BarrierSegment& seg : barriers_.segments()) {
    const Vec2 d = seg.b - seg.a;
    double t0 = 0, t1 = 1;
    bool outside = false;
    for (int axis = 0; axis < 2 && !outside; ++axis) {
      if (d[axis] == 0) {
        outside = seg.a[axis] < lo[axis] || seg.a[axis] > hi[axis];
        continue;
      }
      double ta = (lo[axis] - seg.a[axis]) / d[axis], tb = (hi[axis] - seg.a[axis]) / d[axis];
      if (ta > tb) std::swap(ta, tb);
      t0 = std::max(t0, ta);
      t1 = std::min(t1, tb);
      outside = t0 > t1;
    }
    if (outside) continue;
    const double length = d.norm() * (t1 - t0);
    const long n = static_cast<long>(std::ceil(length / step));
    int last_i = -1, last_j = -1;
    for (long k = 0; k <= n; ++k) {
      const double t = n == 0 ? t0 : t0 + (t1 - t0) * static_cast<double>(k) / static_cast<double>(n);
      const Vec2 p = seg.a + t * d;
      const int ci = std::clamp(static_cast<int>(std::floor((p.x() - nodes_.x0) / dx)), 0, cx - 1);
      const int cj = std::clamp(static_cast<int>(std::floor((p.y() - nodes_.y0) / dy)), 0, cy - 1);
      if (ci == last_i && cj == last_j) continue;
      last_i = ci, last_j = cj;
      for (int j = std::max(0, cj - ry); j <= std::min(cy - 1, cj + ry); ++j)
        for (int i = std::max(0, ci - rx); i <= std::min(cx - 1, ci + rx); ++i) near_[static_cast<size_t>(j) * cx + i] = 1;
    }
  }
}

bool BarrierGrid::near_barrier(const Vec2& q) const {
  if (near_.empty() || barriers_.empty()) return false;
  const int nx = nodes_.nx, ny = nodes_.ny;
  const double gx = std::clamp((q.x() - nodes_.x0) / nodes_.dx, 0.0, double(nx - 1));
  const double gy = std::clamp((q.y() - nodes_.y0) / nodes_.dy, 0.0, double(ny - 1));
  const int i = std::min(static_cast<int>(gx), nx - 2), j = std::min(static_cast<int>(gy), ny - 2);
  return near_[static_cast<size_t>(j) * (nx - 1) + i] != 0;
}

std::array<Vec2, 4> BarrierGrid::cell_box(const Stencil& st) const {
  const double ex = nodes_.dx * (nodes_.nx - 1), ey = nodes_.dy * (nodes_.ny - 1);
  const double mx = kMemoBoxMargin * (ex + nodes_.dx + std::abs(nodes_.x0)),
               my = kMemoBoxMargin * (ey + nodes_.dy + std::abs(nodes_.y0));
  const Vec2 lo(nodes_.x0 + st.i * nodes_.dx - mx, nodes_.y0 + st.j * nodes_.dy - my),
      hi(nodes_.x0 + (st.i + 1) * nodes_.dx + mx, nodes_.y0 + (st.j + 1) * nodes_.dy + my);
  return {lo, Vec2(hi.x(), lo.y()), hi, Vec2(lo.x(), hi.y())};
}

int BarrierGrid::line_crossing(const Stencil& st) const {
  const std::array<Vec2, 4> corners = cell_box(st);
  int found = -1;
  const std::vector<BarrierSegment>& segments = barriers_.segments();
  for (size_t k = 0; k < segments.size(); ++k) {
    const BarrierSegment& g = segments[k];
    if (!boxes_meet(corners[0], corners[2], g.a.cwiseMin(g.b), g.a.cwiseMax(g.b))) continue;
    if (strict_side(g.a, g.b, corners) != 0) continue;
    if (found >= 0) return -1;  // a second: the cell's parts are not one side of one line
    found = static_cast<int>(k);
  }
  return found;
}

bool BarrierGrid::cell_sees_alike(const Stencil& st, const Scratch& s, int cut, int side) const {
  const std::array<Vec2, 4> corners = cell_box(st);
  const Vec2& lo = corners[0];
  const Vec2& hi = corners[2];
  // The sites this query tested (every other is never consulted by a query of the cell that
  // sees these alike: the rules go on the answers alone), and the segments that come near them.
  Vec2 all_lo = lo, all_hi = hi;
  for (int k = 0; k < kWindow * kWindow; ++k)
    if (s.vis[k] >= 0) {
      const Vec2 p = site(s.wi0 + k % kWindow, s.wj0 + k / kWindow);
      all_lo = all_lo.cwiseMin(p), all_hi = all_hi.cwiseMax(p);
    }
  struct Near {
    const BarrierSegment* g;
    int line;  // the common strict sign of orient(a, b, q) over the key's queries, or 0
  };
  std::array<Near, kMemoMostSegments> near{};
  size_t count = 0;
  const std::vector<BarrierSegment>& segments = barriers_.segments();
  for (size_t k = 0; k < segments.size(); ++k) {
    const BarrierSegment& g = segments[k];
    if (!boxes_meet(all_lo, all_hi, g.a.cwiseMin(g.b), g.a.cwiseMax(g.b))) continue;
    if (count == near.size()) return false;
    near[count++] = {&g, static_cast<int>(k) == cut ? side : strict_side(g.a, g.b, corners)};
  }
  for (int k = 0; k < kWindow * kWindow; ++k) {
    if (s.vis[k] < 0) continue;
    const Vec2 p = site(s.wi0 + k % kWindow, s.wj0 + k / kWindow);
    const Vec2 site_lo = lo.cwiseMin(p), site_hi = hi.cwiseMax(p);
    for (size_t m = 0; m < count; ++m) {
      const BarrierSegment& g = *near[m].g;
      if (boxes_meet(site_lo, site_hi, g.a.cwiseMin(g.b), g.a.cwiseMax(g.b)) && !blocks_alike(corners, p, g, near[m].line))
        return false;
    }
  }
  return true;
}

}  // namespace radrecon
