// Bilinear and bicubic with barriers against independent answers: the plain methods where no
// barrier is near (bicubic: bit for bit beyond d2), exactly zero influence across a barrier
// (bicubic: within d1 of it), planes reproduced on each side of one (half-plane geometry, not
// the visibility code), the rule's plane fit against Eigen's least squares and bicubic's local
// scheme against Keys' kernel, continuity along lines that cross no barrier (the change between
// consecutive points shrinks with the step), and no value where nothing is seen.

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "reconstruct/barrier_grid.h"
#include "reconstruct/bicubic.h"
#include "reconstruct/bilinear.h"
#include "reconstruct/nodal.h"

namespace radrecon {
namespace barrier_grid_test {

using Kind = BarrierGrid::Kind;
using Fn = std::function<double(const Vec2&)>;

/// Arithmetic of a few dozen operations on values of order 1..10: agreement to 1e-12 relative
/// leaves ample room for round-off and catches any wrong weight.
constexpr double kRelative = 1e-12;

// A 12 x 10 cell grid on [-1, 2] x [0.5, 3.5] (cells 0.25 x 0.3, not square), or its 13 x 11
// corners as a node grid.
constexpr int kCellsX = 12, kCellsY = 10;
constexpr double kX0 = -1.0, kY0 = 0.5, kDx = 0.25, kDy = 0.3;
constexpr double kX1 = kX0 + kCellsX * kDx, kY1 = kY0 + kCellsY * kDy;

GridCells cells_of(const std::vector<Fn>& fns) {
  GridCells g;
  g.nx = kCellsX, g.ny = kCellsY, g.x0 = kX0, g.y0 = kY0, g.dx = kDx, g.dy = kDy;
  g.channels = static_cast<int>(fns.size());
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i)
      for (const Fn& f : fns) g.values.push_back(f(g.center(i, j)));
  return g;
}

Vec2 node_position(int i, int j) { return {kX0 + i * kDx, kY0 + j * kDy}; }

GridNodes nodes_of(const std::vector<Fn>& fns) {
  GridNodes g;
  g.nx = kCellsX + 1, g.ny = kCellsY + 1, g.x0 = kX0, g.y0 = kY0, g.dx = kDx, g.dy = kDy;
  g.channels = static_cast<int>(fns.size());
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i)
      for (const Fn& f : fns) g.values.push_back(f(node_position(i, j)));
  return g;
}

/// Arbitrary values per site (not smooth): a hash of the position and a seed.
Fn noise(unsigned seed) {
  return [seed](const Vec2& p) {
    const double h = std::sin(12.9898 * p.x() + 78.233 * p.y() + 37.719 * seed) * 43758.5453;
    return 2.0 + 3.0 * (h - std::floor(h));
  };
}

Barriers lines(const std::vector<Polyline>& polylines) { return Barriers::from_polylines(polylines).value(); }

std::vector<double> eval(const Interpolant& f, const std::vector<Vec2>& q) {
  std::vector<double> out(q.size() * static_cast<size_t>(f.channels()));
  f.evaluate(q, out);
  return out;
}

std::vector<Vec2> random_points(double x0, double x1, double y0, double y1, int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> ux(x0, x1), uy(y0, y1);
  std::vector<Vec2> p;
  for (int k = 0; k < count; ++k) p.emplace_back(ux(rng), uy(rng));
  return p;
}

std::string at(const Vec2& q) { return "at (" + std::to_string(q.x()) + ", " + std::to_string(q.y()) + ")"; }

/// An oblique line across the whole grid and beyond: (-1.5, 0.2) to (2.5, 3.1). Its side of a
/// point: > 0 above-left, < 0 below-right (a cross product, by plain geometry).
const Vec2 kCutA(-1.5, 0.2), kCutB(2.5, 3.1);
Barriers oblique_cut() { return lines({{kCutA, kCutB}}); }
double side(const Vec2& p) {
  const Vec2 d = kCutB - kCutA, r = p - kCutA;
  return (d.x() * r.y() - d.y() * r.x()) / d.norm();  // signed distance, metres
}

/// Bicubic's d1 and d2 on this grid (barrier_grid.h), metres.
const double kDiagonal = std::sqrt(kDx * kDx + kDy * kDy);
const double kD1 = BarrierGrid::kLocalDiagonals * kDiagonal, kD2 = BarrierGrid::kPlainDiagonals * kDiagonal;

/// The distance from p to the segment [a, b] (plain geometry: clamped projection).
double distance_to_segment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 d = b - a;
  const double t = std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
  return (p - (a + t * d)).norm();
}

/// The distance from q, clamped onto the grid (as the rule judges it), to the nearest segment
/// of `polylines`.
double barrier_distance(const Vec2& q, const std::vector<Polyline>& polylines) {
  const Vec2 p(std::clamp(q.x(), kX0, kX1), std::clamp(q.y(), kY0, kY1));
  double d = std::numeric_limits<double>::infinity();
  for (const Polyline& line : polylines)
    for (size_t k = 0; k + 1 < line.size(); ++k) d = std::min(d, distance_to_segment(p, line[k], line[k + 1]));
  return d;
}

/// Distances within this of d1 or d2 may round either way in the library: tests leave them out.
constexpr double kDistanceMargin = 1e-9;

struct Variant {
  Kind kind;
  bool cells;
  std::string name() const {
    return std::string(kind == Kind::bilinear ? "bilinear" : "bicubic") + (cells ? " of cells" : " of nodes");
  }
};
const Variant kVariants[] = {{Kind::bilinear, true}, {Kind::bilinear, false}, {Kind::bicubic, true}, {Kind::bicubic, false}};

/// The interpolant of a variant, with barriers, and the plain one, from the same functions.
std::unique_ptr<Interpolant> with_barriers(const Variant& v, const std::vector<Fn>& fns, Barriers b) {
  if (v.cells) return std::make_unique<BarrierGrid>(cells_of(fns), v.kind, std::move(b));
  return std::make_unique<BarrierGrid>(nodes_of(fns), v.kind, std::move(b));
}
std::unique_ptr<Interpolant> plain(const Variant& v, const std::vector<Fn>& fns) {
  GridNodes n = v.cells ? nodal_average(cells_of(fns)) : nodes_of(fns);
  if (v.kind == Kind::bilinear) return std::make_unique<Bilinear>(std::move(n));
  return std::make_unique<Bicubic>(std::move(n));
}

TEST(BarrierGrid, EqualsThePlainMethodWhereNoBarrierIsNear) {
  const std::vector<Fn> fns = {noise(1), noise(2)};
  // (1) a short barrier in the top right corner, queries away from it (some outside the grid:
  // clamped); (2) barriers just outside two borders, blocking nothing, with queries everywhere.
  // Bilinear: every query, the barrier path included, must find the plain values. Bicubic: the
  // queries (clamped) at least d2 from every barrier, bit for bit; many of them lie in the band
  // d2..d2 + 2 diagonals, in cells flagged as near a barrier, which measure their distance.
  const std::vector<Polyline> corner_lines = {{{1.6, 3.0}, {1.9, 3.3}}};
  const std::vector<Polyline> border_lines = {{{kX0 - 1, kY0 - 0.01}, {kX1 + 1, kY0 - 0.01}},
                                              {{kX0 - 0.01, kY0 - 1}, {kX0 - 0.01, kY1 + 1}}};
  const std::vector<Vec2> far = random_points(kX0 - 0.3, 0.5, kY0 - 0.3, 2.0, 3000, 11);
  const std::vector<Vec2> everywhere = random_points(kX0 - 0.3, kX1 + 0.3, kY0 - 0.3, kY1 + 0.3, 6000, 12);
  for (const Variant& v : kVariants) {
    int compared = 0, in_band = 0;
    for (const auto& [polylines, q] : {std::pair(corner_lines, far), std::pair(border_lines, everywhere)}) {
      const std::vector<double> want = eval(*plain(v, fns), q), got = eval(*with_barriers(v, fns, lines(polylines)), q);
      for (size_t k = 0; k < q.size(); ++k) {
        const double d = barrier_distance(q[k], polylines);
        if (v.kind == Kind::bicubic) {
          if (d < kD2 * (1 + kDistanceMargin)) continue;
          in_band += d < kD2 + 2 * kDiagonal;
        }
        ASSERT_EQ(got[2 * k], want[2 * k]) << v.name() << " " << at(q[k]);
        ASSERT_EQ(got[2 * k + 1], want[2 * k + 1]) << v.name() << " " << at(q[k]);
        ++compared;
      }
    }
    EXPECT_GT(compared, 2000) << v.name();
    if (v.kind == Kind::bicubic) {
      EXPECT_GT(in_band, 500) << v.name();
    }
  }
}

/// Cells of the grid whose 4 corners are not all on the query's side of the oblique cut.
bool cell_is_cut(const Vec2& q) {
  const int i = std::clamp(static_cast<int>((q.x() - kX0) / kDx), 0, kCellsX - 1);
  const int j = std::clamp(static_cast<int>((q.y() - kY0) / kDy), 0, kCellsY - 1);
  const bool up = side(q) > 0;
  for (int b = j; b <= j + 1; ++b)
    for (int a = i; a <= i + 1; ++a)
      if ((side(node_position(a, b)) > 0) != up) return true;
  return false;
}

TEST(BarrierGrid, ValuesAcrossABarrierHaveExactlyNoInfluence) {
  // Two data sets equal above the cut and unrelated below it; queries above it.
  const Fn above = noise(3), below_a = noise(4), below_b = [](const Vec2& p) { return -500.0 + 40 * p.x(); };
  const auto split = [&](const Fn& below) { return [&, below](const Vec2& p) { return side(p) > 0 ? above(p) : below(p); }; };
  const std::vector<Fn> a = {split(below_a), noise(5)}, b = {split(below_b), noise(5)};
  std::vector<Vec2> q;
  for (const Vec2& p : random_points(kX0, kX1, kY0, kY1, 6000, 13))
    if (side(p) > 1e-9) q.push_back(p);
  const std::vector<Polyline> cut = {{kCutA, kCutB}};
  for (const Variant& v : kVariants) {
    const std::vector<double> va = eval(*with_barriers(v, a, oblique_cut()), q);
    const std::vector<double> vb = eval(*with_barriers(v, b, oblique_cut()), q);
    int compared = 0, beyond = 0, beyond_differ = 0;
    double beyond_largest = 0;
    for (size_t k = 0; k < q.size(); ++k) {
      // Bilinear: everywhere. Bicubic: within d1 of the cut (Keys' local scheme alone); beyond,
      // the global spline's share couples all nodes (barrier_grid.h): the values differ, weakly
      // (the data below differ by some 500; measured: at most 0.08).
      if (v.kind == Kind::bicubic && barrier_distance(q[k], cut) > kD1 * (1 - kDistanceMargin)) {
        ++beyond;
        beyond_differ += va[2 * k] != vb[2 * k];
        beyond_largest = std::max(beyond_largest, std::abs(va[2 * k] - vb[2 * k]));
        continue;
      }
      ASSERT_EQ(va[2 * k], vb[2 * k]) << v.name() << " " << at(q[k]);
      ASSERT_EQ(va[2 * k + 1], vb[2 * k + 1]) << v.name() << " " << at(q[k]);
      ++compared;
    }
    EXPECT_GT(compared, 1000) << v.name();
    if (v.kind == Kind::bicubic) {
      EXPECT_GT(beyond_differ, beyond / 2) << v.name();
      EXPECT_LT(beyond_largest, 0.5) << v.name();
    }
    // Without the barrier the values below do reach the queries above.
    const std::vector<double> pa = eval(*plain(v, a), q), pb = eval(*plain(v, b), q);
    int differ = 0;
    for (size_t k = 0; k < q.size(); ++k) differ += pa[2 * k] != pb[2 * k];
    EXPECT_GT(differ, 200) << v.name();
  }
}

// Two planes, one on each side of a barrier.
double plane_up(const Vec2& p) { return 1.5 + 0.8 * p.x() - 0.6 * p.y(); }
double plane_down(const Vec2& p) { return -2.0 + 0.3 * p.x() + 1.1 * p.y(); }

void expect_planes(const Interpolant& f, const std::vector<Vec2>& q, const std::function<bool(const Vec2&)>& up,
                   const std::string& what) {
  const std::vector<double> got = eval(f, q);
  for (size_t k = 0; k < q.size(); ++k) {
    const double want = up(q[k]) ? plane_up(q[k]) : plane_down(q[k]);
    ASSERT_NEAR(got[k], want, kRelative * std::max(1.0, std::abs(want))) << what << " " << at(q[k]);
  }
}

TEST(BarrierGrid, BilinearReproducesAPlaneOnEachSideOfABarrier) {
  // Cell data: queries in cells whose corners are inner nodes (the plain mean of cells is exact
  // for planes there, not on the border). Node data: queries anywhere.
  std::vector<Vec2> inner, all;
  for (const Vec2& p : random_points(kX0 + kDx, kX1 - kDx, kY0 + kDy, kY1 - kDy, 4000, 14)) inner.push_back(p);
  for (const Vec2& p : random_points(kX0, kX1, kY0, kY1, 4000, 15)) all.push_back(p);

  // A barrier along the cell boundary x = 0.25 (and beyond the grid).
  const double wall = kX0 + 5 * kDx;
  const auto left = [&](const Vec2& p) { return p.x() < wall; };
  const Fn by_wall = [&](const Vec2& p) { return left(p) ? plane_up(p) : plane_down(p); };
  std::vector<Vec2> off_wall;
  for (const Vec2& p : inner)
    if (std::abs(p.x() - wall) > 1e-9) off_wall.push_back(p);
  expect_planes(BarrierGrid(cells_of({by_wall}), Kind::bilinear, lines({{{wall, 0}, {wall, 4}}})), off_wall, left,
                "cells, wall on a cell boundary");

  // The oblique cut, through cells and between nodes.
  const auto up = [](const Vec2& p) { return side(p) > 0; };
  const Fn by_cut = [&](const Vec2& p) { return up(p) ? plane_up(p) : plane_down(p); };
  std::vector<Vec2> inner_off, all_off;
  for (const Vec2& p : inner)
    if (std::abs(side(p)) > 1e-9) inner_off.push_back(p);
  for (const Vec2& p : all)
    if (std::abs(side(p)) > 1e-9) all_off.push_back(p);
  int cut = 0;
  for (const Vec2& p : inner_off) cut += cell_is_cut(p);
  EXPECT_GT(cut, 200);  // many queries in cells the barrier cuts
  expect_planes(BarrierGrid(cells_of({by_cut}), Kind::bilinear, oblique_cut()), inner_off, up, "cells, oblique cut");
  expect_planes(BarrierGrid(nodes_of({by_cut}), Kind::bilinear, oblique_cut()), all_off, up, "nodes, oblique cut");
}

TEST(BarrierGrid, BicubicReproducesAPlaneOnEachSideWithinD1OfABarrier) {
  // Within d1 of the cut Keys' scheme alone interpolates the nodal values as seen from q; with
  // cell data its nodes must be inner nodes (1 <= i - 1, i + 2 <= 11). Many queries lie in
  // cells the cut splits.
  const auto up = [](const Vec2& p) { return side(p) > 0; };
  const Fn by_cut = [&](const Vec2& p) { return up(p) ? plane_up(p) : plane_down(p); };
  const std::vector<Polyline> cut = {{kCutA, kCutB}};
  std::vector<Vec2> cells_q, nodes_q;
  int split = 0;
  for (const Vec2& p : random_points(kX0, kX1, kY0, kY1, 8000, 16)) {
    if (std::abs(side(p)) <= 1e-9 || barrier_distance(p, cut) > kD1 * (1 - kDistanceMargin)) continue;
    nodes_q.push_back(p);
    split += cell_is_cut(p);
    const int i = static_cast<int>((p.x() - kX0) / kDx), j = static_cast<int>((p.y() - kY0) / kDy);
    if (i >= 2 && i <= kCellsX - 3 && j >= 2 && j <= kCellsY - 3) cells_q.push_back(p);
  }
  ASSERT_GT(cells_q.size(), 1000u);
  ASSERT_GT(split, 300);
  expect_planes(BarrierGrid(cells_of({by_cut}), Kind::bicubic, oblique_cut()), cells_q, up, "cells");
  expect_planes(BarrierGrid(nodes_of({by_cut}), Kind::bicubic, oblique_cut()), nodes_q, up, "nodes");
}

TEST(BarrierGrid, ReproducesOnePlaneWhateverTheBarriers) {
  // One plane, barriers of several shapes (a full cut, an L with free ends, a short segment).
  // Node data (exact at every node, border included): every query, near them or not, gets it;
  // bicubic's queries cover Keys' zone (d <= d1), the blend zone (d1 < d < d2) and beyond. Cell
  // data: bicubic's queries within d1 whose stencil has inner nodes only (the plain mean is
  // exact there; in the blend zone the global spline also carries the border nodes' error), and
  // without the L: its free end lies 0.16 below the cut, and from the narrow gap between them
  // the nodes above the cut see fewer than 3 cells of their neighbourhood and take rule (c),
  // the mean of the visible cells they share, which is not exact for a plane.
  const Fn f = [](const Vec2& p) { return 0.7 - 1.2 * p.x() + 0.45 * p.y(); };
  const std::vector<Polyline> polylines = {{kCutA, kCutB}, {{0.1, 1.2}, {0.9, 1.2}, {0.9, 2.4}}, {{-0.6, 2.7}, {-0.2, 3.2}}};
  const Barriers b = lines(polylines);
  const std::vector<Vec2> q = random_points(kX0 - 0.2, kX1 + 0.2, kY0 - 0.2, kY1 + 0.2, 6000, 17);
  const auto expect_plane = [&](const std::vector<double>& got, size_t k, const std::string& what) {
    const Vec2 c(std::clamp(q[k].x(), kX0, kX1), std::clamp(q[k].y(), kY0, kY1));
    ASSERT_NEAR(got[k], f(c), kRelative * std::max(1.0, std::abs(f(c)))) << what << " " << at(q[k]);
  };
  for (Kind kind : {Kind::bilinear, Kind::bicubic}) {
    const std::vector<double> got = eval(BarrierGrid(nodes_of({f}), kind, b), q);
    int local = 0, blend = 0;
    for (size_t k = 0; k < q.size(); ++k) {
      expect_plane(got, k, "nodes");
      const double d = barrier_distance(q[k], polylines);
      local += d <= kD1;
      blend += d > kD1 && d < kD2;
    }
    EXPECT_GT(local, 1000);
    EXPECT_GT(blend, 50);
  }
  const std::vector<Polyline> without_l = {polylines[0], polylines[2]};
  const std::vector<double> got = eval(BarrierGrid(cells_of({f}), Kind::bicubic, lines(without_l)), q);
  int compared = 0;
  for (size_t k = 0; k < q.size(); ++k) {
    const int i = static_cast<int>(std::floor((q[k].x() - kX0) / kDx)), j = static_cast<int>(std::floor((q[k].y() - kY0) / kDy));
    if (i < 2 || i > kCellsX - 3 || j < 2 || j > kCellsY - 3) continue;
    if (barrier_distance(q[k], without_l) > kD1 * (1 - kDistanceMargin)) continue;
    expect_plane(got, k, "cells");
    ++compared;
  }
  EXPECT_GT(compared, 1000);
}

/// The least-squares plane through (points, values), at x (Eigen's QR: an independent solver).
double plane_fit_at(const std::vector<Vec2>& points, const std::vector<double>& values, const Vec2& x) {
  Eigen::MatrixXd A(points.size(), 3);
  Eigen::VectorXd y(points.size());
  for (size_t k = 0; k < points.size(); ++k) {
    A.row(static_cast<Eigen::Index>(k)) << 1, points[k].x(), points[k].y();
    y(static_cast<Eigen::Index>(k)) = values[k];
  }
  const Eigen::Vector3d c = A.colPivHouseholderQr().solve(y);
  return c(0) + c(1) * x.x() + c(2) * x.y();
}

TEST(BarrierGrid, BilinearHiddenCornersAreThePlanesOfTheirVisibleNeighbourhood) {
  // 6 x 6 unit cells, arbitrary values; a full cut x + y = 5.8. A query in cell (2, 2) below
  // it sees exactly the cells with i + j + 1 < 5.8. Corner (2, 2) sees its 4 cells (their
  // mean); corners (3, 2), (2, 3), (3, 3) do not: each gets the least-squares plane through the
  // visible cells of its 4 x 4 cells (i - 2..i + 1, j - 2..j + 1).
  GridCells g;
  g.nx = g.ny = 6, g.x0 = g.y0 = 0, g.dx = g.dy = 1, g.channels = 1;
  const Fn value = noise(6);
  for (int j = 0; j < 6; ++j)
    for (int i = 0; i < 6; ++i) g.values.push_back(value(g.center(i, j)));
  const auto cell = [&](int i, int j) { return g.values[static_cast<size_t>(j) * 6 + i]; };
  const auto seen = [](int i, int j) { return i + j + 1 < 5.8; };
  const auto corner = [&](int a, int b) {
    std::vector<Vec2> p;
    std::vector<double> v;
    for (int j = std::max(0, b - 2); j <= std::min(5, b + 1); ++j)
      for (int i = std::max(0, a - 2); i <= std::min(5, a + 1); ++i)
        if (seen(i, j)) p.push_back(g.center(i, j)), v.push_back(cell(i, j));
    return plane_fit_at(p, v, Vec2(a, b));
  };
  const double n22 = (cell(1, 1) + cell(2, 1) + cell(1, 2) + cell(2, 2)) / 4;
  const double n32 = corner(3, 2), n23 = corner(2, 3), n33 = corner(3, 3);
  const BarrierGrid f(g, Kind::bilinear, lines({{{-1, 6.8}, {6.8, -1}}}));
  std::vector<Vec2> q;
  for (const Vec2& p : random_points(2, 3, 2, 3, 400, 18))
    if (p.x() + p.y() < 5.8 - 1e-9) q.push_back(p);
  const std::vector<double> got = eval(f, q);
  for (size_t k = 0; k < q.size(); ++k) {
    const double u = q[k].x() - 2, v = q[k].y() - 2;
    const double want = (1 - u) * (1 - v) * n22 + u * (1 - v) * n32 + (1 - u) * v * n23 + u * v * n33;
    ASSERT_NEAR(got[k], want, kRelative * std::abs(want)) << at(q[k]);
  }
}

/// Keys' cubic convolution kernel with a = -1/2 (Keys 1981, eq. 15).
double keys_kernel(double s) {
  s = std::abs(s);
  if (s <= 1) return 1.5 * s * s * s - 2.5 * s * s + 1;
  if (s < 2) return -0.5 * s * s * s + 2.5 * s * s - 4 * s + 2;
  return 0;
}

/// Keys' interpolation of f (nx x ny values at the integers, row by row) at (x, y): the grid
/// extended by one node on every side with Keys' end condition (f(-1) = 3 f(0) - 3 f(1) + f(2),
/// linear extrapolation when only 2 nodes), then the kernel's sum over the extended grid.
double keys_interpolation(const std::vector<double>& f, int nx, int ny, double x, double y) {
  const auto extend = [](std::vector<double> line) {  // one node added at each end
    const size_t n = line.size();
    const double before = n == 2 ? 2 * line[0] - line[1] : 3 * line[0] - 3 * line[1] + line[2];
    const double after = n == 2 ? 2 * line[n - 1] - line[n - 2] : 3 * line[n - 1] - 3 * line[n - 2] + line[n - 3];
    line.insert(line.begin(), before);
    line.push_back(after);
    return line;
  };
  std::vector<std::vector<double>> rows;  // the rows, extended along x
  for (int j = 0; j < ny; ++j) rows.push_back(extend(std::vector<double>(f.begin() + j * nx, f.begin() + (j + 1) * nx)));
  double sum = 0;
  for (int a = 0; a < nx + 2; ++a) {
    std::vector<double> column;
    for (int j = 0; j < ny; ++j) column.push_back(rows[static_cast<size_t>(j)][static_cast<size_t>(a)]);
    column = extend(column);
    for (int b = 0; b < ny + 2; ++b)
      sum += column[static_cast<size_t>(b)] * keys_kernel(x - (a - 1)) * keys_kernel(y - (b - 1));
  }
  return sum;
}

TEST(BarrierGrid, BicubicWithAHiddenNodeIsKeysInterpolationOfTheSeenValues) {
  // 4 x 4 unit nodes, arbitrary values; a short barrier x + y = 5.5 near node (3, 3). From the
  // centre cell [1, 2]^2 only that node is hidden: it gets the least-squares plane through the
  // visible nodes of its 5 x 5 neighbourhood (the other 8 of 1..3 x 1..3), and the value (all
  // within d1 of the barrier) is Keys' interpolation of the 16 nodes.
  GridNodes g;
  g.nx = g.ny = 4, g.x0 = g.y0 = 0, g.dx = g.dy = 1, g.channels = 1;
  const Fn value = noise(7);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) g.values.push_back(value(Vec2(i, j)));
  std::vector<Vec2> p;
  std::vector<double> v;
  for (int j = 1; j <= 3; ++j)
    for (int i = 1; i <= 3; ++i)
      if (i + j < 6) p.emplace_back(i, j), v.push_back(g.values[static_cast<size_t>(j) * 4 + i]);
  std::vector<double> seen = g.values;
  seen[15] = plane_fit_at(p, v, Vec2(3, 3));
  const BarrierGrid f(g, Kind::bicubic, lines({{{2.4, 3.1}, {3.1, 2.4}}}));
  const std::vector<Vec2> q = random_points(1, 2, 1, 2, 300, 19);
  const std::vector<double> got = eval(f, q);
  for (size_t k = 0; k < q.size(); ++k) {
    const double want = keys_interpolation(seen, 4, 4, q[k].x(), q[k].y());
    ASSERT_NEAR(got[k], want, kRelative * std::abs(want)) << at(q[k]);
  }
  // And the plain spline (the barrier ignored) is another function there.
  const std::vector<double> plain = eval(Bicubic(g), q);
  EXPECT_GT(std::abs(plain[0] - got[0]), 1e-6);
}

TEST(BarrierGrid, BicubicNearABarrierIsKeysInterpolationUpToTheBorder) {
  // A barrier just beyond the grid's right border hides nothing but puts the whole grid within
  // d1 of it: Keys' interpolation of the plain nodal values everywhere, the border cells with
  // Keys' end condition; with 2 nodes along x, linear extrapolation (Keys' scheme then
  // interpolates linearly along x).
  for (const int nx : {2, 3, 5}) {
    GridNodes g;
    g.nx = nx, g.ny = 4, g.x0 = g.y0 = 0, g.dx = g.dy = 1, g.channels = 1;
    const Fn value = noise(20 + nx);
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < nx; ++i) g.values.push_back(value(Vec2(i, j)));
    const BarrierGrid f(g, Kind::bicubic, lines({{{nx - 0.9, -1}, {nx - 0.9, 5}}}));
    ASSERT_LT(nx - 0.9, BarrierGrid::kLocalDiagonals * std::sqrt(2.0));  // the farthest distance from it
    const std::vector<Vec2> q = random_points(0, nx - 1, 0, 3, 400, 21);
    const std::vector<double> got = eval(f, q);
    for (size_t k = 0; k < q.size(); ++k) {
      const double want = keys_interpolation(g.values, nx, g.ny, q[k].x(), q[k].y());
      ASSERT_NEAR(got[k], want, kRelative * std::abs(want)) << nx << " nodes along x " << at(q[k]);
    }
  }
}

TEST(BarrierGrid, AQueryThatSeesNothingHasNoValue) {
  // 6 x 6 unit cells (7 x 7 nodes); a closed square inside cell (2, 2) holding no centre and no
  // node; a query inside it.
  GridCells cells;
  cells.nx = cells.ny = 6, cells.x0 = cells.y0 = 0, cells.dx = cells.dy = 1, cells.channels = 2;
  for (int k = 0; k < 72; ++k) cells.values.push_back(1.0 + k);
  GridNodes nodes;
  nodes.nx = nodes.ny = 7, nodes.x0 = nodes.y0 = 0, nodes.dx = nodes.dy = 1, nodes.channels = 2;
  for (int k = 0; k < 98; ++k) nodes.values.push_back(1.0 + k);
  const Barriers box = lines({{{2.1, 2.1}, {2.4, 2.1}, {2.4, 2.4}, {2.1, 2.4}, {2.1, 2.1}}});
  const std::vector<Vec2> q = {Vec2(2.2, 2.3), Vec2(2.6, 2.6), Vec2(2.3, 2.15)};
  for (Kind kind : {Kind::bilinear, Kind::bicubic})
    for (const std::vector<double>& got : {eval(BarrierGrid(cells, kind, box), q), eval(BarrierGrid(nodes, kind, box), q)}) {
      for (int k : {0, 1, 4, 5}) EXPECT_TRUE(std::isnan(got[static_cast<size_t>(k)])) << k;
      EXPECT_TRUE(std::isfinite(got[2]) && std::isfinite(got[3]));  // outside the square
    }
}

TEST(BarrierGrid, AQueryEnclosedWithOneSiteGetsItsValue) {
  // A closed square around the centre of cell (2, 2) (and around node (2, 2)): a query inside
  // sees that site alone, and every nodal value is its value.
  GridCells cells;
  cells.nx = cells.ny = 6, cells.x0 = cells.y0 = 0, cells.dx = cells.dy = 1, cells.channels = 1;
  for (int k = 0; k < 36; ++k) cells.values.push_back(noise(8)(Vec2(k, 0)));
  GridNodes nodes;
  nodes.nx = nodes.ny = 7, nodes.x0 = nodes.y0 = 0, nodes.dx = nodes.dy = 1, nodes.channels = 1;
  for (int k = 0; k < 49; ++k) nodes.values.push_back(noise(9)(Vec2(k, 0)));
  const Barriers around_centre = lines({{{2.2, 2.2}, {2.8, 2.2}, {2.8, 2.8}, {2.2, 2.8}, {2.2, 2.2}}});
  const Barriers around_node = lines({{{1.8, 1.8}, {2.2, 1.8}, {2.2, 2.2}, {1.8, 2.2}, {1.8, 1.8}}});
  for (Kind kind : {Kind::bilinear, Kind::bicubic}) {
    const double want_cell = cells.values[2 * 6 + 2], want_node = nodes.values[2 * 7 + 2];
    for (const Vec2& q : {Vec2(2.3, 2.6), Vec2(2.7, 2.25)})
      EXPECT_NEAR(eval(BarrierGrid(cells, kind, around_centre), {q})[0], want_cell, kRelative * want_cell) << at(q);
    for (const Vec2& q : {Vec2(1.9, 2.1), Vec2(2.15, 1.85)})
      EXPECT_NEAR(eval(BarrierGrid(nodes, kind, around_node), {q})[0], want_node, kRelative * want_node) << at(q);
  }
}

TEST(BarrierGrid, NodesSharingTheOnlyVisibleCellsGetTheirMean) {
  // A closed rectangle around the centres of cells (2, 2) and (3, 2): a query inside sees two
  // cells, on a line (no plane). Each corner of its cell gets the mean of the visible cells it
  // shares: (2, 2) and (2, 3) cell (2, 2)'s value, (3, 2) and (3, 3) the mean of both.
  GridCells cells;
  cells.nx = cells.ny = 6, cells.x0 = cells.y0 = 0, cells.dx = cells.dy = 1, cells.channels = 1;
  for (int k = 0; k < 36; ++k) cells.values.push_back(noise(13)(Vec2(k, 1)));
  const Barriers around = lines({{{2.2, 2.2}, {3.8, 2.2}, {3.8, 2.8}, {2.2, 2.8}, {2.2, 2.2}}});
  const double v22 = cells.values[2 * 6 + 2], v32 = cells.values[2 * 6 + 3], mean = (v22 + v32) / 2;
  for (const Vec2& q : {Vec2(2.3, 2.6), Vec2(2.9, 2.25)}) {
    const double u = q.x() - 2, want = (1 - u) * v22 + u * mean;
    EXPECT_NEAR(eval(BarrierGrid(cells, Kind::bilinear, around), {q})[0], want, kRelative * want) << at(q);
  }
}

/// A second full cut, vertical, between node columns (x = 0.6), from below the grid to above it.
const Vec2 kCut2A(0.6, -1.0), kCut2B(0.6, 5.0);

/// The largest change of any channel between consecutive points A + (B - A) k / n, k = 0..n,
/// over every segment [A, B] of `lines` (every value must be a number).
double largest_step(const Interpolant& f, const std::vector<std::pair<Vec2, Vec2>>& lines, int n) {
  const size_t C = static_cast<size_t>(f.channels());
  double largest = 0;
  std::vector<Vec2> q(static_cast<size_t>(n) + 1);
  for (const auto& [a, b] : lines) {
    for (int k = 0; k <= n; ++k) q[static_cast<size_t>(k)] = a + (b - a) * (static_cast<double>(k) / n);
    const std::vector<double> v = eval(f, q);
    for (size_t k = 0; k < v.size(); ++k)
      if (!std::isfinite(v[k])) ADD_FAILURE() << "no value " << at(q[k / C]);
    for (size_t k = 0; k + 1 < q.size(); ++k)
      for (size_t c = 0; c < C; ++c) largest = std::max(largest, std::abs(v[(k + 1) * C + c] - v[k * C + c]));
  }
  return largest;
}

/// `count` random segments, `length` (a fraction of the domain's side) long, at angles within
/// `spread` (radians) of the x axis, centred where `centre` puts a uniform random point (nothing:
/// draw again), with their points inside the grid and in one of the convex regions that
/// `region` labels (so that they cross no full cut between regions). How many grid lines they
/// cross goes to `crossings`.
std::vector<std::pair<Vec2, Vec2>> random_segments(int count, unsigned seed, double length,
                                                   const std::function<std::optional<Vec2>(const Vec2&)>& centre,
                                                   const std::function<int(const Vec2&)>& region, double spread,
                                                   int& crossings) {
  const double length_m = length * std::max(kX1 - kX0, kY1 - kY0);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> ux(kX0, kX1), uy(kY0, kY1), angle(-spread, spread);
  std::vector<std::pair<Vec2, Vec2>> segments;
  crossings = 0;
  while (static_cast<int>(segments.size()) < count) {
    const std::optional<Vec2> drawn = centre(Vec2(ux(rng), uy(rng)));
    if (!drawn) continue;
    const Vec2 c = *drawn;
    const double t = angle(rng);
    const Vec2 h = 0.5 * length_m * Vec2(std::cos(t), std::sin(t)), a = c - h, b = c + h;
    const auto inside = [](const Vec2& p) { return p.x() > kX0 && p.x() < kX1 && p.y() > kY0 && p.y() < kY1; };
    if (!inside(a) || !inside(b) || region(a) != region(c) || region(b) != region(c)) continue;
    segments.emplace_back(a, b);
    crossings += static_cast<int>(std::abs(std::floor((a.x() - kX0) / kDx) - std::floor((b.x() - kX0) / kDx)) +
                                  std::abs(std::floor((a.y() - kY0) / kDy) - std::floor((b.y() - kY0) / kDy)));
  }
  return segments;
}

/// Whether f is continuous along `segments` (`length` of the domain's side long): the largest
/// change between consecutive points shrinks more than 50-fold from steps of 1e-4 to steps of
/// 1e-6 of the domain's side (100-fold for a function with a bounded derivative along them; a
/// jump does not shrink at all).
void expect_continuous(const Interpolant& f, const std::vector<std::pair<Vec2, Vec2>>& segments, double length,
                       const std::string& what) {
  const int coarse = static_cast<int>(std::lround(length / 1e-4)), fine = static_cast<int>(std::lround(length / 1e-6));
  const double step_coarse = largest_step(f, segments, coarse), step_fine = largest_step(f, segments, fine);
  EXPECT_GT(step_coarse, 50 * step_fine) << what << ": largest change " << step_coarse << " at steps of 1e-4, "
                                         << step_fine << " at 1e-6 of the domain";
}

TEST(BarrierGrid, IsContinuousAlongLinesThatCrossNoBarrier) {
  // Two full cuts (the oblique one and x = 0.6, both ending far outside the grid: no free end,
  // so no sight line past one, inside), arbitrary values. Random lines 4% of the domain long,
  // in any direction, centred within d2 of a cut (Keys' zone and the blend zone), each in one
  // of the four regions the cuts make. (The previous rule, a local natural spline on each
  // cell's stencil and the plain spline where the stencil saw everything, jumped at cell edges
  // here by up to 0.2.)
  const std::vector<Polyline> cuts = {{kCutA, kCutB}, {kCut2A, kCut2B}};
  int crossings = 0;  // grid lines crossed: where the local natural splines of before jumped
  const auto segments = random_segments(
      24, 21, 0.04, [&](const Vec2& c) { return barrier_distance(c, cuts) < kD2 ? std::optional(c) : std::nullopt; },
      [](const Vec2& p) { return 2 * (side(p) > 0) + (p.x() < kCut2A.x()); }, M_PI, crossings);
  ASSERT_GT(crossings, 10);
  const std::vector<Fn> fns = {noise(14), noise(15)};
  for (const Variant& v : kVariants) expect_continuous(*with_barriers(v, fns, lines(cuts)), segments, 0.04, v.name());
}

TEST(BarrierGrid, IsContinuousInAStripThatSeesOneRowOfSites) {
  // Two full cuts along x 0.1 on either side of a row of sites (node row 5 at y = 2, or the
  // centres of cell row 5 at y = 2.15): a query between them sees that row only, all on one line,
  // so the nodes off the row take the fallbacks (c) (cells sharing it), else (e), the visible
  // site nearest the node: functions of the node, not of where q is (before, the fallbacks used
  // the sites around q, and jumped where q's own site changed, by up to 0.37). Random lines along the strip (1% of
  // the domain long, within 0.1 rad of the x axis, within 0.08 of the row), each centred near a
  // cell edge or a cell's middle.
  for (const bool cells : {false, true}) {
    const double row = cells ? kY0 + 5.5 * kDy : kY0 + 5 * kDy;
    const std::vector<Polyline> strip = {{{kX0 - 1, row - 0.1}, {kX1 + 1, row - 0.1}}, {{kX0 - 1, row + 0.1}, {kX1 + 1, row + 0.1}}};
    int crossings = 0;
    const auto segments = random_segments(
        16, 22, 0.01,
        [&](const Vec2& c) -> std::optional<Vec2> {
          if (std::abs(c.y() - row) >= 0.08) return std::nullopt;
          const double half_cells = std::round((c.x() - kX0) / (kDx / 2));  // the nearest edge or middle
          return Vec2(kX0 + half_cells * kDx / 2 + 0.1 * (c.y() - row), c.y());
        },
        [&](const Vec2& p) { return std::abs(p.y() - row) < 0.1 ? 0 : 1; }, 0.1, crossings);
    ASSERT_GT(crossings, 5);
    const std::vector<Fn> fns = {noise(16)};
    for (Kind kind : {Kind::bilinear, Kind::bicubic}) {
      const Variant v{kind, cells};
      expect_continuous(*with_barriers(v, fns, lines(strip)), segments, 0.01, v.name() + ", strip");
    }
  }
}

TEST(BarrierGrid, ABatchGivesWhatEachPointAloneGives) {
  // Enough points for the parallel loop; each point alone runs on one thread.
  const std::vector<Fn> fns = {noise(10), noise(11), noise(12)};
  const Barriers b = lines({{kCutA, kCutB}, {{0.1, 1.2}, {0.9, 1.2}, {0.9, 2.4}}, {{1.1, 0.7}, {1.3, 0.7}, {1.3, 0.9}, {1.1, 0.9}, {1.1, 0.7}}});
  const std::vector<Vec2> q = random_points(kX0 - 0.2, kX1 + 0.2, kY0 - 0.2, kY1 + 0.2, 40000, 20);
  for (const Variant& v : kVariants) {
    const auto f = with_barriers(v, fns, b);
    const std::vector<double> batch = eval(*f, q);
    for (size_t k = 0; k < q.size(); k += 7) {
      const std::vector<double> alone = eval(*f, {q[k]});
      ASSERT_EQ(std::memcmp(alone.data(), &batch[3 * k], 3 * sizeof(double)), 0) << v.name() << " " << at(q[k]);
    }
  }
}

TEST(BarrierGrid, ManyQueriesOfACellGiveWhatEachAloneGives) {
  // A query alone is computed by the rules; in a batch a cell's later queries may reuse the
  // stencil values of its first ones where every site they consult is provably seen alike from
  // the whole cell (or from its part on one side of the one barrier line that crosses it).
  // Dense queries where that proof is hardest: across the cut, around the barriers' free ends
  // (sight lines grazing an end sweep across the cells there), at an L's corner, on the barrier
  // itself and on grid lines. Each point alone, bit for bit.
  const std::vector<Fn> fns = {noise(21), noise(22), noise(23)};
  const std::vector<Polyline> walls = {{{0.1, 1.2}, {0.9, 1.2}, {0.9, 2.4}}, {{-0.4, 2.9}, {1.6, 2.05}}};
  const Barriers b = lines(walls);
  std::vector<Vec2> q;
  for (const Vec2& centre : {Vec2(0.1, 1.2), Vec2(0.9, 1.2), Vec2(0.9, 2.4), Vec2(-0.4, 2.9), Vec2(1.6, 2.05),
                             Vec2(0.5, 1.2), Vec2(0.9, 1.8), Vec2(0.6, 2.5)}) {
    const std::vector<Vec2> around = random_points(centre.x() - 0.6, centre.x() + 0.6, centre.y() - 0.6,
                                                   centre.y() + 0.6, 6000, static_cast<unsigned>(100 * centre.x() + 10 * centre.y() + 50));
    q.insert(q.end(), around.begin(), around.end());
  }
  for (int k = 0; k <= 400; ++k) {  // on the barriers and on the grid's lines
    const double t = k / 400.0;
    q.emplace_back(0.1 + 0.8 * t, 1.2);
    q.emplace_back(0.9, 1.2 + 1.2 * t);
    q.emplace_back(-0.4 + 2.0 * t, 2.9 - 0.85 * t);
    q.emplace_back(0.5, 0.8 + 2.0 * t);   // the grid line x = 0.5
    q.emplace_back(-0.2 + 2.0 * t, 2.0);  // y = 2.0: the line x = 0.5 and y = 2.0 are node lines
  }
  std::shuffle(q.begin(), q.end(), std::mt19937(24));
  for (const Variant& v : kVariants) {
    const auto f = with_barriers(v, fns, b);
    const std::vector<double> batch = eval(*f, q);
    for (size_t k = 0; k < q.size(); ++k) {
      const std::vector<double> alone = eval(*f, {q[k]});
      ASSERT_EQ(std::memcmp(alone.data(), &batch[3 * k], 3 * sizeof(double)), 0) << v.name() << " " << at(q[k]);
    }
  }
}

}  // namespace barrier_grid_test
}  // namespace radrecon
