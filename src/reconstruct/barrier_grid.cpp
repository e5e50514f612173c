#include "reconstruct/barrier_grid.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

#include "core/check.h"
#include "core/parallel.h"
#include "reconstruct/bicubic.h"
#include "reconstruct/hermite.h"
#include "reconstruct/bilinear.h"
#include "reconstruct/keys_cubic.h"
#include "reconstruct/nodal.h"
#include "reconstruct/orientation.h"

namespace radrecon {

namespace {

/// The visibility cache of a query covers sites i-5..i+6 x j-5..j+6 around its cell (i, j):
/// every N(n), N3(n) and N4(n) of its stencil (nodes i-1..i+2), for cell and node sites.
constexpr int kWindowBefore = 5;
constexpr int kWindow = 12;
/// At most 4 x 4 stencil nodes.
constexpr int kStencil = 4;
/// Bicubic skips the visibility tests of a query nearer a barrier than d1 when the barrier is
/// farther than the stencil's farthest site by this many cell diagonals: the distances' round-off
/// is some 1e-16 of the coordinates and of the barrier segments' lengths, far below it unless
/// those exceed 1e12 cells.
constexpr double kSeenMarginDiagonals = 1e-3;
/// Barrier marking: points along each barrier segment at most this fraction of the smaller grid
/// spacing apart; each marks its cell and the cells around it, so that every cell the segment
/// touches is marked.
constexpr double kMarkStep = 0.5;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// The cells whose stencil values a thread keeps (direct-mapped by cell index): a view's
/// scanline crosses a few dozen cells near a barrier before the next line comes back to them.
constexpr size_t kMemoCells = 64;
/// A cell's stencil values are kept only when at most this many barrier segments come near its
/// consulted sites: beyond, proving the visible set the same costs more than it spares.
constexpr size_t kMemoMostSegments = 32;
/// With more barrier segments than this in all, no cell is memoised (finding a cell's segments
/// scans them all).
constexpr size_t kMemoMostBarrierSegments = 1024;
/// The cell's box is widened by this fraction of the grid's extent plus a spacing, far above the
/// round-off that places a query in its cell (a few ulps of the coordinates), so that every
/// query the cell gets lies inside the box the proof covers.
constexpr double kMemoBoxMargin = 1e-9;

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

/// One query near a barrier: where it is on the grid and which nodes it interpolates.
struct BarrierGrid::Stencil {
  Vec2 p;             ///< the query clamped onto the grid: visibility is judged from it
  int i, j;           ///< its grid cell
  double u, v;        ///< its position in the cell, [0, 1]
  int a0, a1, b0, b1; ///< the stencil's nodes a0..a1 x b0..b1
};

/// Per-thread buffers of evaluate(); overwritten per query before use.
struct BarrierGrid::Scratch {
  signed char vis[kWindow * kWindow];  ///< -1 not tested yet, 0 hidden, 1 visible
  int wi0 = 0, wj0 = 0;                ///< the cache's first site
  bool sees_nothing = false;           ///< rule (e) found no visible site: q sees none
  bool plain[kStencil * kStencil];     ///< per stencil node: rule (a)
  std::vector<double> values;          ///< stencil node values, ((b - b0) * 4 + (a - a0)) * C + c
  std::vector<double> sums;            ///< plane fits: sum f, u f, v f per channel
  std::vector<double> plain_values;    ///< bicubic: the plain spline's values at q, per channel
  bool left_window = false;            ///< the query tested a site outside the window (rule (e))
  /// A cell's stencil values as seen from any point of it, once they are shown to be the same
  /// for all (BarrierGrid::cell_sees_alike): then the cell's later queries skip the visibility
  /// tests and the rules, and compute what they would have computed.
  struct CellMemo {
    long cell = -1;           ///< row-major cell index, -1: none
    int queries = 0;          ///< queries in the cell since it came in
    bool checked = false;     ///< cell_sees_alike() was asked (once a cell)
    bool stored = false;      ///< values below hold
    bool no_value = false;    ///< q sees no site at all
    bool all_plain = false;   ///< rule (a) for every stencil node
    std::vector<double> values;  ///< as Scratch::values
  };
  std::array<CellMemo, kMemoCells> memo;
  /// Per cell, the one barrier segment whose line crosses its box, if it has exactly one: the
  /// cell's queries are memoised by their side of it (each side's part of the cell sees alike).
  struct CellCut {
    long cell = -1;
    int segment = -1;  ///< the segment's index; -1: none (or several)
  };
  std::array<CellCut, kMemoCells> cuts;
};

BarrierGrid::BarrierGrid(const GridCells& cells, Kind kind, Barriers barriers)
    : BarrierGrid(nodal_average(cells), cells.values, true, cells.nx, cells.ny, kind, std::move(barriers)) {}

BarrierGrid::BarrierGrid(const GridNodes& nodes, Kind kind, Barriers barriers)
    : BarrierGrid(nodes, nodes.values, false, nodes.nx, nodes.ny, kind, std::move(barriers)) {}

BarrierGrid::BarrierGrid(GridNodes plain_nodes, std::vector<double> site_values, bool cell_sites, int sites_x,
                         int sites_y, Kind kind, Barriers barriers)
    : kind_(kind),
      nodes_(std::move(plain_nodes)),
      site_values_(std::move(site_values)),
      cell_sites_(cell_sites),
      sites_x_(sites_x),
      sites_y_(sites_y),
      barriers_(std::move(barriers)) {
  RR_CHECK(nodes_.nx >= 2 && nodes_.ny >= 2, "grid interpolation needs at least 2 x 2 nodes");
  RR_CHECK(nodes_.dx > 0 && nodes_.dy > 0, "grid spacing must be positive");
  RR_CHECK(site_values_.size() == static_cast<size_t>(sites_x_) * sites_y_ * nodes_.channels,
           "grid values do not match the grid");
  if (kind_ == Kind::bilinear) plain_ = std::make_unique<Bilinear>(nodes_);
  else if (kind_ == Kind::bicubic) plain_ = std::make_unique<Bicubic>(nodes_);
  else plain_ = std::make_unique<Hermite>(nodes_);
  const double diagonal = std::hypot(nodes_.dx, nodes_.dy);
  local_distance_ = kLocalDiagonals * diagonal;
  plain_distance_ = kPlainDiagonals * diagonal;
  mark_cells_near_barriers();
}

BarrierGrid::~BarrierGrid() = default;

Vec2 BarrierGrid::site(int si, int sj) const {
  const double half = cell_sites_ ? 0.5 : 0.0;
  return {nodes_.x0 + (si + half) * nodes_.dx, nodes_.y0 + (sj + half) * nodes_.dy};
}

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

void BarrierGrid::evaluate(std::span<const Vec2> points, std::span<double> out) const {
  const size_t C = static_cast<size_t>(channels());
  RR_CHECK(out.size() == points.size() * C, "output size does not match the query points");
  if (barriers_.empty()) {  // the plain method, as it is
    plain_->evaluate(points, out);
    return;
  }
  // Runs of points far from barriers go to the plain method as they come (as cheap as it); the
  // points near one, which test visibility, are computed afterwards, in parallel.
  std::vector<size_t> near;
  const size_t n = points.size();
  size_t run = 0;  // first point of the current run for the plain method
  for (size_t k = 0; k < n; ++k) {
    if (!points[k].allFinite() || !near_barrier(points[k])) continue;
    if (run < k) plain_->evaluate(points.subspan(run, k - run), out.subspan(run * C, (k - run) * C));
    near.push_back(k);
    run = k + 1;
  }
  if (run < n) plain_->evaluate(points.subspan(run), out.subspan(run * C));
  parallel_for_with_scratch<Scratch>(0, static_cast<std::int64_t>(near.size()), [&](std::int64_t m, Scratch& s) {
    const size_t k = near[static_cast<size_t>(m)];
    evaluate_near(points[k], &out[k * C], s);
  });
}

bool BarrierGrid::visible(int si, int sj, const Stencil& st, Scratch& s) const {
  const int wi = si - s.wi0, wj = sj - s.wj0;
  if (wi < 0 || wi >= kWindow || wj < 0 || wj >= kWindow) {
    s.left_window = true;
    return !barriers_.blocks(st.p, site(si, sj));
  }
  signed char& cached = s.vis[wj * kWindow + wi];
  if (cached < 0) cached = barriers_.blocks(st.p, site(si, sj)) ? 0 : 1;
  return cached == 1;
}

void BarrierGrid::evaluate_near(const Vec2& q, double* out, Scratch& s) const {
  const int C = channels(), nx = nodes_.nx, ny = nodes_.ny;
  // Where q is, exactly as the plain methods place it.
  const double gx = std::clamp((q.x() - nodes_.x0) / nodes_.dx, 0.0, double(nx - 1));
  const double gy = std::clamp((q.y() - nodes_.y0) / nodes_.dy, 0.0, double(ny - 1));
  Stencil st;
  st.i = std::min(static_cast<int>(gx), nx - 2);
  st.j = std::min(static_cast<int>(gy), ny - 2);
  st.u = gx - st.i;
  st.v = gy - st.j;
  st.p = Vec2(std::clamp(q.x(), nodes_.x0, nodes_.x0 + (nx - 1) * nodes_.dx),
              std::clamp(q.y(), nodes_.y0, nodes_.y0 + (ny - 1) * nodes_.dy));
  if (kind_ == Kind::bilinear) {
    st.a0 = st.i, st.a1 = st.i + 1, st.b0 = st.j, st.b1 = st.j + 1;
  } else {
    st.a0 = std::max(0, st.i - 1), st.a1 = std::min(nx - 1, st.i + 2);
    st.b0 = std::max(0, st.j - 1), st.b1 = std::min(ny - 1, st.j + 2);
  }
  s.wi0 = st.i - kWindowBefore;
  s.wj0 = st.j - kWindowBefore;
  std::fill(std::begin(s.vis), std::end(s.vis), static_cast<signed char>(-1));
  s.sees_nothing = false;

  // Bicubic: the distance to the nearest barrier sets the blend (barrier_grid.h).
  double w = 1;  // the local scheme's weight
  bool all_seen = false;
  if (kind_ != Kind::bilinear) {
    const double d = barriers_.distance_to(st.p, plain_distance_);
    if (d >= plain_distance_) {  // the plain spline alone, the same arithmetic
      plain_->evaluate(std::span(&q, 1), std::span(out, static_cast<size_t>(C)));
      return;
    }
    if (d > local_distance_) {
      const double t = (plain_distance_ - d) / (plain_distance_ - local_distance_);
      w = t * t * (3 - 2 * t);
      all_seen = true;  // every site of the stencil is nearer q than any barrier (barrier_grid.h)
    } else {
      // The same when the barriers are farther than the stencil's farthest site: no sight
      // segment, all within that distance of q, can meet one; the margin is far above the
      // round-off of the distances (and only spares the visibility tests).
      all_seen = d > stencil_reach(st) + kSeenMarginDiagonals * std::hypot(nodes_.dx, nodes_.dy);
    }
  }

  s.values.resize(static_cast<size_t>(kStencil * kStencil) * C);
  if (all_seen) {
    for (int b = st.b0; b <= st.b1; ++b)
      for (int a = st.a0; a <= st.a1; ++a) {
        const double* node = &nodes_.values[(static_cast<size_t>(b) * nx + a) * C];
        std::copy(node, node + C, &s.values[static_cast<size_t>((b - st.b0) * kStencil + (a - st.a0)) * C]);
      }
    keys_blend(st, w, s, q, out);
    return;
  }

  // The stencil's values as seen from q: kept from an earlier query of the cell when they are
  // shown to be the same from all of it, else by the rules.
  // The memo's key: the cell, and q's side of the one segment whose line crosses it (if any).
  const long cell = static_cast<long>(st.j) * (nx - 1) + st.i;
  const bool memoised = barriers_.segments().size() <= kMemoMostBarrierSegments;
  int cut = -1, side = 0;
  if (memoised) {
    Scratch::CellCut& c = s.cuts[static_cast<size_t>(cell) % kMemoCells];
    if (c.cell != cell) c = {cell, line_crossing(st)};
    cut = c.segment;
    if (cut >= 0) {
      const BarrierSegment& g = barriers_.segments()[static_cast<size_t>(cut)];
      side = orientation(g.a, g.b, st.p);
    }
  }
  const long key = 3 * cell + side + 1;
  Scratch::CellMemo& memo = s.memo[static_cast<size_t>(key) % kMemoCells];
  if (memo.cell != key) memo.cell = key, memo.queries = 0, memo.checked = memo.stored = false;
  // A query on the cutting line has no side: it is computed alone.
  if (!memoised || (cut >= 0 && side == 0)) memo.checked = true;
  bool no_value = false, all_plain = true;
  if (memo.stored) {
    no_value = memo.no_value, all_plain = memo.all_plain;
    std::copy(memo.values.begin(), memo.values.end(), s.values.begin());
  } else {
    s.left_window = false;
    no_value = !stencil_values_seen(st, s, all_plain);
    if (++memo.queries >= 2 && !memo.checked) {  // a second query: the cell may get many
      memo.checked = true;
      if (!s.left_window && cell_sees_alike(st, s, cut, side)) {
        memo.stored = true, memo.no_value = no_value, memo.all_plain = all_plain;
        memo.values.assign(s.values.begin(), s.values.end());
      }
    }
  }
  if (no_value) {
    std::fill(out, out + C, kNaN);  // q sees no site at all
    return;
  }
  if (all_plain && kind_ == Kind::bilinear) {  // nothing hidden: the plain method, the same arithmetic
    plain_->evaluate(std::span(&q, 1), std::span(out, static_cast<size_t>(C)));
    return;
  }

  if (kind_ == Kind::bilinear) {
    const double u = st.u, v = st.v;
    const double* b00 = &s.values[0];
    const double* b10 = b00 + C;
    const double* b01 = b00 + static_cast<size_t>(kStencil) * C;
    const double* b11 = b01 + C;
    for (int c = 0; c < C; ++c)
      out[c] = (1 - u) * (1 - v) * b00[c] + u * (1 - v) * b10[c] + u * v * b11[c] + (1 - u) * v * b01[c];
    return;
  }
  keys_blend(st, w, s, q, out);
}

bool BarrierGrid::stencil_values_seen(const Stencil& st, Scratch& s, bool& all_plain) const {
  const int C = channels(), nx = nodes_.nx;
  // Rule (a) for every stencil node: are all the sites it shares visible?
  all_plain = true;
  for (int b = st.b0; b <= st.b1; ++b)
    for (int a = st.a0; a <= st.a1; ++a) {
      bool seen = true;
      if (cell_sites_) {
        for (int cj = std::max(0, b - 1); cj <= std::min(sites_y_ - 1, b) && seen; ++cj)
          for (int ci = std::max(0, a - 1); ci <= std::min(sites_x_ - 1, a) && seen; ++ci) seen = visible(ci, cj, st, s);
      } else {
        seen = visible(a, b, st, s);
      }
      s.plain[(b - st.b0) * kStencil + (a - st.a0)] = seen;
      all_plain = all_plain && seen;
    }
  if (all_plain && kind_ == Kind::bilinear) return true;  // the plain method needs no values
  s.sums.resize(3 * static_cast<size_t>(C));
  for (int b = st.b0; b <= st.b1; ++b)
    for (int a = st.a0; a <= st.a1; ++a) {
      const int slot = (b - st.b0) * kStencil + (a - st.a0);
      double* value = &s.values[static_cast<size_t>(slot) * C];
      if (s.plain[slot]) {
        const double* node = &nodes_.values[(static_cast<size_t>(b) * nx + a) * C];
        std::copy(node, node + C, value);
      } else if (!hidden_node_value(a, b, st, s, value)) {
        return false;
      }
    }
  return true;
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

double BarrierGrid::stencil_reach(const Stencil& st) const {
  // The box of the sites the stencil's nodes share: cells a0-1..a1 x b0-1..b1, or the nodes.
  const int si0 = cell_sites_ ? std::max(0, st.a0 - 1) : st.a0, si1 = cell_sites_ ? std::min(sites_x_ - 1, st.a1) : st.a1;
  const int sj0 = cell_sites_ ? std::max(0, st.b0 - 1) : st.b0, sj1 = cell_sites_ ? std::min(sites_y_ - 1, st.b1) : st.b1;
  const Vec2 lo = site(si0, sj0), hi = site(si1, sj1);
  return std::hypot(std::max(st.p.x() - lo.x(), hi.x() - st.p.x()), std::max(st.p.y() - lo.y(), hi.y() - st.p.y()));
}

void BarrierGrid::keys_blend(const Stencil& st, double w, Scratch& s, const Vec2& q, double* out) const {
  const int C = channels();
  // Keys' cubic convolution of the stencil's values, rows first (x), then the column (y).
  const AxisWeights wx = keys_weights(nodes_.nx, st.i, st.u), wy = keys_weights(nodes_.ny, st.j, st.v);
  const int ax = wx.first - st.a0, by = wy.first - st.b0;  // their first nodes in the stencil
  for (int c = 0; c < C; ++c) {
    double sum = 0;
    for (int row = 0; row < wy.count; ++row) {
      double along_x = 0;
      for (int col = 0; col < wx.count; ++col)
        along_x += wx.w[col] * s.values[static_cast<size_t>((by + row) * kStencil + ax + col) * C + c];
      sum += wy.w[row] * along_x;
    }
    out[c] = sum;
  }
  if (w == 1) return;
  // The blend with the plain spline (w in (0, 1)).
  s.plain_values.resize(static_cast<size_t>(C));
  double* plain = s.plain_values.data();
  plain_->evaluate(std::span(&q, 1), std::span(plain, static_cast<size_t>(C)));
  for (int c = 0; c < C; ++c) out[c] = (1 - w) * plain[c] + w * out[c];
}

bool BarrierGrid::hidden_node_value(int a, int b, const Stencil& st, Scratch& s, double* out) const {
  const int C = channels();
  // (b) the plane through the visible sites of N(n).
  const int lo = 2, hi = cell_sites_ ? 1 : 2;
  if (plane_at_node(a, b, std::max(0, a - lo), std::min(sites_x_ - 1, a + hi), std::max(0, b - lo),
                    std::min(sites_y_ - 1, b + hi), st, s, out))
    return true;
  // (c) the mean of the visible cells sharing n.
  if (cell_sites_) {
    int count = 0;
    std::fill(out, out + C, 0.0);
    for (int cj = std::max(0, b - 1); cj <= std::min(sites_y_ - 1, b); ++cj)
      for (int ci = std::max(0, a - 1); ci <= std::min(sites_x_ - 1, a); ++ci)
        if (visible(ci, cj, st, s)) {
          const double* cell = &site_values_[(static_cast<size_t>(cj) * sites_x_ + ci) * C];
          for (int c = 0; c < C; ++c) out[c] += cell[c];
          ++count;
        }
    if (count > 0) {
      for (int c = 0; c < C; ++c) out[c] /= count;
      return true;
    }
  }
  // (d) the plane through the visible sites of N3(n), else of N4(n).
  for (int rings = 3; rings <= 4; ++rings) {
    const int below = rings, above = cell_sites_ ? rings - 1 : rings;
    if (plane_at_node(a, b, std::max(0, a - below), std::min(sites_x_ - 1, a + above), std::max(0, b - below),
                      std::min(sites_y_ - 1, b + above), st, s, out))
      return true;
  }
  // (e) the visible site nearest n.
  if (s.sees_nothing) return false;
  const long nearest = nearest_visible_site(a, b, st, s);
  if (nearest < 0) {
    s.sees_nothing = true;  // the search tried every site
    return false;
  }
  const double* v = &site_values_[static_cast<size_t>(nearest) * C];
  std::copy(v, v + C, out);
  return true;
}

bool BarrierGrid::plane_at_node(int a, int b, int si0, int si1, int sj0, int sj1, const Stencil& st, Scratch& s,
                                double* out) const {
  const int C = channels();
  // Coordinates relative to the node in half spacings: integers, so that the collinearity test
  // (the determinant of the positions' scatter) is exact.
  const int offset = cell_sites_ ? 1 : 0;
  std::int64_t n = 0, su = 0, sv = 0, suu = 0, svv = 0, suv = 0;
  double* sf = &s.sums[0];
  double* suf = sf + C;
  double* svf = suf + C;
  std::fill(sf, sf + 3 * C, 0.0);
  for (int sj = sj0; sj <= sj1; ++sj)
    for (int si = si0; si <= si1; ++si) {
      if (!visible(si, sj, st, s)) continue;
      const std::int64_t u = 2 * si + offset - 2 * a, v = 2 * sj + offset - 2 * b;
      ++n, su += u, sv += v, suu += u * u, svv += v * v, suv += u * v;
      const double* f = &site_values_[(static_cast<size_t>(sj) * sites_x_ + si) * C];
      for (int c = 0; c < C; ++c) {
        sf[c] += f[c];
        suf[c] += static_cast<double>(u) * f[c];
        svf[c] += static_cast<double>(v) * f[c];
      }
    }
  if (n < 3) return false;
  // n^2 times the positions' covariance: [A X; X B], singular exactly when they are collinear.
  const std::int64_t A = n * suu - su * su, B = n * svv - sv * sv, X = n * suv - su * sv;
  const std::int64_t D = A * B - X * X;
  if (D == 0) return false;
  const double dn = static_cast<double>(n), dD = static_cast<double>(D);
  for (int c = 0; c < C; ++c) {
    const double P = dn * suf[c] - static_cast<double>(su) * sf[c], Q = dn * svf[c] - static_cast<double>(sv) * sf[c];
    const double slope_u = (P * static_cast<double>(B) - Q * static_cast<double>(X)) / dD;
    const double slope_v = (Q * static_cast<double>(A) - P * static_cast<double>(X)) / dD;
    out[c] = (sf[c] - slope_u * static_cast<double>(su) - slope_v * static_cast<double>(sv)) / dn;  // at u = v = 0
  }
  return true;
}

long BarrierGrid::nearest_visible_site(int a, int b, const Stencil& st, Scratch& s) const {
  // Rings of sites (Chebyshev distance r in index space) around the site nearest node n = (a, b)
  // (n itself, or the cell a, b clamped onto the grid: the node is one of its corners); n lies
  // within half a spacing of it along each axis, so a site of ring r is at least (r - 1/2) h
  // away: once (r - 1) h exceeds the best distance found, no farther ring can do better.
  // Distances from offsets in half spacings (integers): equidistant sites tie exactly.
  const double dx = nodes_.dx, dy = nodes_.dy, h = std::min(dx, dy);
  const int offset = cell_sites_ ? 1 : 0;
  const int bi = std::min(a, sites_x_ - 1), bj = std::min(b, sites_y_ - 1);
  long best = -1;
  double best_d2 = std::numeric_limits<double>::infinity();
  const auto consider = [&](int si, int sj) {
    const long index = static_cast<long>(sj) * sites_x_ + si;
    const double u = 0.5 * dx * (2 * si + offset - 2 * a), v = 0.5 * dy * (2 * sj + offset - 2 * b);
    const double d2 = u * u + v * v;
    if (d2 > best_d2 || (d2 == best_d2 && index > best)) return;
    if (!visible(si, sj, st, s)) return;
    best = index, best_d2 = d2;
  };
  const int rings = std::max(sites_x_, sites_y_);
  for (int r = 0; r <= rings; ++r) {
    if (best >= 0 && r >= 1 && (r - 1) * h * ((r - 1) * h) > best_d2) break;
    for (int sj = std::max(0, bj - r); sj <= std::min(sites_y_ - 1, bj + r); ++sj) {
      if (sj == bj - r || sj == bj + r) {
        for (int si = std::max(0, bi - r); si <= std::min(sites_x_ - 1, bi + r); ++si) consider(si, sj);
      } else {
        if (bi - r >= 0) consider(bi - r, sj);
        if (bi + r < sites_x_ && r > 0) consider(bi + r, sj);
      }
    }
  }
  return best;
}

}  // namespace radrecon
