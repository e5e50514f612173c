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
#include "reconstruct/barrier_grid_scratch.h"
#include "reconstruct/bilinear.h"
#include "reconstruct/keys_cubic.h"
#include "reconstruct/nodal.h"
#include "reconstruct/orientation.h"

namespace radrecon {

namespace {

using barrier_grid_detail::kMemoCells;
using barrier_grid_detail::kMemoMostBarrierSegments;
using barrier_grid_detail::kStencil;
using barrier_grid_detail::kWindow;
using barrier_grid_detail::kWindowBefore;

/// Bicubic skips the visibility tests of a query nearer a barrier than d1 when the barrier is
/// farther than the stencil's farthest site by this many cell diagonals: the distances' round-off
/// is some 1e-16 of the coordinates and of the barrier segments' lengths, far below it unless
/// those exceed 1e12 cells.
constexpr double kSeenMarginDiagonals = 1e-3;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace

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
