// Piecewise-constant reconstruction: cell lookup against a brute-force search, on grids and on
// random quadtree-like subdivisions.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "reconstruct/constant.h"
#include "reconstruct/methods.h"

namespace radrecon {
namespace constant_test {

constexpr unsigned kSeed = 12345;

std::string Str(const Vec2& p) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%.17g, %.17g)", p.x(), p.y());
  return buf;
}

Rect Bounds(const std::vector<Rect>& cells) {
  Rect b = cells[0];
  for (const Rect& r : cells) {
    b.x0 = std::min(b.x0, r.x0);
    b.y0 = std::min(b.y0, r.y0);
    b.x1 = std::max(b.x1, r.x1);
    b.y1 = std::max(b.y1, r.y1);
  }
  return b;
}

/// The documented rule, by looking at every cell: clamp into the bounding box, then cells are
/// half-open [x0, x1) x [y0, y1) except on the far border of the domain, where they are closed.
long BruteLocate(const std::vector<Rect>& cells, Vec2 p) {
  const Rect b = Bounds(cells);
  const double x = std::clamp(p.x(), b.x0, b.x1), y = std::clamp(p.y(), b.y0, b.y1);
  long found = -1;
  for (size_t k = 0; k < cells.size(); ++k) {
    const Rect& r = cells[k];
    const bool in_x = (r.x0 <= x && x < r.x1) || (x == r.x1 && r.x1 == b.x1);
    const bool in_y = (r.y0 <= y && y < r.y1) || (y == r.y1 && r.y1 == b.y1);
    if (in_x && in_y) {
      EXPECT_EQ(found, -1) << "cells overlap at " << Str(p);  // the test data must be disjoint
      found = static_cast<long>(k);
    }
  }
  return found;
}

/// A random dyadic subdivision of the square [x0, x0 + size]^2: each square splits into four
/// with a probability falling with depth, down to `max_depth` levels.
void Split(std::mt19937& rng, double x0, double y0, double size, int depth, int max_depth,
           std::vector<Rect>& out) {
  std::uniform_real_distribution<double> u(0, 1);
  if (depth < max_depth && u(rng) < 0.9 - 0.12 * depth) {
    const double h = size / 2;
    Split(rng, x0, y0, h, depth + 1, max_depth, out);
    Split(rng, x0 + h, y0, h, depth + 1, max_depth, out);
    Split(rng, x0, y0 + h, h, depth + 1, max_depth, out);
    Split(rng, x0 + h, y0 + h, h, depth + 1, max_depth, out);
  } else {
    out.push_back({x0, y0, x0 + size, y0 + size});
  }
}

TEST(PiecewiseConstant, GridQueryInsideACellGivesThatCellsValue) {
  // A 4 x 3 grid of 0.5 x 0.25 cells from (1, -2), two channels of distinct values.
  const int nx = 4, ny = 3;
  const double x0 = 1, y0 = -2, dx = 0.5, dy = 0.25;
  CellSamples s;
  s.channels = 2;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      s.cells.push_back({x0 + i * dx, y0 + j * dy, x0 + (i + 1) * dx, y0 + (j + 1) * dy});
      s.values.push_back(10.0 * j + i);
      s.values.push_back(-100.0 - (10.0 * j + i));
    }
  const PiecewiseConstant pc(s);
  ASSERT_EQ(pc.channels(), 2);

  std::mt19937 rng(kSeed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      for (int trial = 0; trial < 20; ++trial) {
        // Strictly inside: keep away from the edges so the half-open rule does not matter.
        const Vec2 p(x0 + (i + 0.01 + 0.98 * u(rng)) * dx, y0 + (j + 0.01 + 0.98 * u(rng)) * dy);
        double out[2];
        pc.evaluate(std::span<const Vec2>(&p, 1), out);
        EXPECT_EQ(out[0], 10.0 * j + i) << Str(p);
        EXPECT_EQ(out[1], -100.0 - (10.0 * j + i)) << Str(p);
        EXPECT_EQ(pc.locate(p), j * nx + i) << Str(p);
      }

  // The same through the method factory on GridCells.
  GridCells g;
  g.nx = nx;
  g.ny = ny;
  g.x0 = x0;
  g.y0 = y0;
  g.dx = dx;
  g.dy = dy;
  g.channels = 2;
  g.values = s.values;
  const auto f = make_grid_interpolant(Method::constant, g).value();
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const Vec2 p(x0 + (i + 0.5) * dx, y0 + (j + 0.5) * dy);
      double out[2];
      f->evaluate(std::span<const Vec2>(&p, 1), out);
      EXPECT_EQ(out[0], 10.0 * j + i) << Str(p);
      EXPECT_EQ(out[1], -100.0 - (10.0 * j + i)) << Str(p);
    }
}

TEST(PiecewiseConstant, LocateAgreesWithBruteForceOnRandomQuadtrees) {
  std::mt19937 rng(kSeed);
  for (int tree = 0; tree < 20; ++tree) {
    SCOPED_TRACE("tree " + std::to_string(tree));
    // Domain [-1, 3]^2: every edge is a dyadic fraction of 4, exactly representable.
    const double x0 = -1, y0 = -1, size = 4;
    const int max_depth = 6;
    std::vector<Rect> cells;
    Split(rng, x0, y0, size, 0, max_depth, cells);
    std::shuffle(cells.begin(), cells.end(), rng);  // no reliance on any cell order
    CellSamples s;
    s.cells = cells;
    for (size_t k = 0; k < cells.size(); ++k) s.values.push_back(static_cast<double>(k));
    const PiecewiseConstant pc(s);

    std::vector<Vec2> pts;
    std::uniform_real_distribution<double> any(x0, x0 + size);
    // Points exactly on the finest dyadic lines (edges and corners of cells, the domain border).
    const int fine = 1 << max_depth;
    std::uniform_int_distribution<int> line(0, fine);
    for (int k = 0; k < 1500; ++k) {
      pts.emplace_back(any(rng), any(rng));
      pts.emplace_back(x0 + size * line(rng) / fine, y0 + size * line(rng) / fine);
      pts.emplace_back(x0 + size * line(rng) / fine, any(rng));
      pts.emplace_back(any(rng), y0 + size * line(rng) / fine);
    }
    std::vector<double> out(pts.size());
    pc.evaluate(pts, out);
    for (size_t k = 0; k < pts.size(); ++k) {
      const long want = BruteLocate(cells, pts[k]);
      ASSERT_GE(want, 0) << "a subdivision of a square has no gaps; " << Str(pts[k]);
      EXPECT_EQ(pc.locate(pts[k]), want) << Str(pts[k]);
      EXPECT_EQ(out[k], static_cast<double>(want)) << Str(pts[k]);
    }
  }
}

TEST(PiecewiseConstant, PointsOutsideTheBoundingBoxAreClamped) {
  std::mt19937 rng(kSeed + 1);
  std::vector<Rect> cells;
  Split(rng, 0, 0, 2, 0, 5, cells);
  CellSamples s;
  s.cells = cells;
  for (size_t k = 0; k < cells.size(); ++k) s.values.push_back(1000.0 + k);
  const PiecewiseConstant pc(s);

  // Far outside in every direction, including the corners and points at huge distances.
  std::uniform_real_distribution<double> inside(0, 2), off(0.001, 50);
  for (int k = 0; k < 2000; ++k) {
    Vec2 p(inside(rng), inside(rng));
    const int side = k % 8;
    if (side == 0 || side == 4 || side == 5) p.x() = -off(rng);
    if (side == 1 || side == 6 || side == 7) p.x() = 2 + off(rng);
    if (side == 2 || side == 4 || side == 6) p.y() = -off(rng);
    if (side == 3 || side == 5 || side == 7) p.y() = 2 + off(rng);
    const Vec2 clamped(std::clamp(p.x(), 0.0, 2.0), std::clamp(p.y(), 0.0, 2.0));
    const long want = BruteLocate(cells, clamped);
    ASSERT_GE(want, 0);
    EXPECT_EQ(pc.locate(p), want) << Str(p);
    double out;
    pc.evaluate(std::span<const Vec2>(&p, 1), std::span<double>(&out, 1));
    EXPECT_EQ(out, 1000.0 + want) << Str(p);
  }
  // The far corner of the domain belongs to the top-right cell (closed far border).
  const long top_right = BruteLocate(cells, Vec2(2, 2));
  EXPECT_EQ(cells[top_right].x1, 2.0);
  EXPECT_EQ(cells[top_right].y1, 2.0);
  EXPECT_EQ(pc.locate(Vec2(1e300, 1e300)), top_right);
}

TEST(PiecewiseConstant, GapBetweenCellsGivesNan) {
  // Two unit cells with a unit gap between them: [0,1] x [0,1] and [2,3] x [0,1].
  CellSamples s;
  s.cells = {{0, 0, 1, 1}, {2, 0, 3, 1}};
  s.values = {5, 6};
  const PiecewiseConstant pc(s);
  const std::vector<Vec2> pts = {{1.5, 0.5}, {1.0, 0.5}, {1.999, 0.2}, {0.5, 0.5}, {2.5, 0.5}};
  std::vector<double> out(pts.size());
  pc.evaluate(pts, out);
  EXPECT_EQ(pc.locate(pts[0]), -1);
  EXPECT_TRUE(std::isnan(out[0]));
  EXPECT_TRUE(std::isnan(out[1]));  // x = 1 is the open far edge of the first cell, not the domain's
  EXPECT_TRUE(std::isnan(out[2]));
  EXPECT_EQ(out[3], 5.0);
  EXPECT_EQ(out[4], 6.0);
  // A gap that the clamping reaches: below-and-between is clamped into the gap, still NaN.
  EXPECT_EQ(pc.locate(Vec2(1.5, -4.0)), -1);
}

TEST(PiecewiseConstant, ACellOfNoExtentIsRefusedNamedInItsOwnUnits) {
  // A cell of 1e-9 m with no height: its corners as they are, where "%f" printed 0.000000.
  CellSamples s;
  s.cells = {{1e-9, 2e-9, 3e-9, 2e-9}};
  s.values = {1};
  try {
    const PiecewiseConstant pc(s);
    FAIL() << "accepted";
  } catch (const ReconstructionError& e) {
    EXPECT_NE(std::string(e.what()).find("[1e-09, 3e-09] x [2e-09, 2e-09]"), std::string::npos) << e.what();
  }
}

}  // namespace constant_test
}  // namespace radrecon
