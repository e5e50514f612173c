// Nodal averaging: node values worked out by hand, and exactness for linear data in the interior.

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "reconstruct/nodal.h"

namespace radrecon {
namespace nodal_test {

// Means of at most four small numbers: exact up to a few ulps.
constexpr double kExact = 1e-12;

double Node(const GridNodes& n, int i, int j, int c = 0) {
  return n.values[(static_cast<size_t>(j) * n.nx + i) * n.channels + c];
}

TEST(NodalAverage, TwoByTwoGridByHand) {
  // Cells (i, j):  (0,1)=3 (1,1)=4
  //                (0,0)=1 (1,0)=2
  GridCells cells;
  cells.nx = 2;
  cells.ny = 2;
  cells.x0 = -1;
  cells.y0 = 2;
  cells.dx = 0.5;
  cells.dy = 0.25;
  cells.values = {1, 2, 3, 4};
  const GridNodes n = nodal_average(cells);
  ASSERT_EQ(n.nx, 3);
  ASSERT_EQ(n.ny, 3);
  EXPECT_EQ(n.channels, 1);
  ASSERT_EQ(n.values.size(), 9u);
  // Nodes are the cell corners.
  EXPECT_EQ(n.x0, -1.0);
  EXPECT_EQ(n.y0, 2.0);
  EXPECT_EQ(n.dx, 0.5);
  EXPECT_EQ(n.dy, 0.25);
  const double want[3][3] = {// [j][i]
                             {1.0, 1.5, 2.0},
                             {2.0, 2.5, 3.0},
                             {3.0, 3.5, 4.0}};
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(Node(n, i, j), want[j][i], kExact) << "node " << i << "," << j;
}

TEST(NodalAverage, ThreeByTwoGridByHandTwoChannels) {
  // Channel 0, cells:  row 1:  8 16 32
  //                    row 0:  1  2  4
  // Channel 1 is minus ten times channel 0.
  GridCells cells;
  cells.nx = 3;
  cells.ny = 2;
  cells.channels = 2;
  const double c0[6] = {1, 2, 4, 8, 16, 32};
  for (double v : c0) {
    cells.values.push_back(v);
    cells.values.push_back(-10 * v);
  }
  const GridNodes n = nodal_average(cells);
  ASSERT_EQ(n.nx, 4);
  ASSERT_EQ(n.ny, 3);
  ASSERT_EQ(n.channels, 2);
  ASSERT_EQ(n.values.size(), 24u);
  const double want[3][4] = {
      // Bottom edge: corner, mean of 2, mean of 2, corner.
      {1.0, (1 + 2) / 2.0, (2 + 4) / 2.0, 4.0},
      // Middle row: edge mean of 2, interior mean of 4, interior mean of 4, edge mean of 2.
      {(1 + 8) / 2.0, (1 + 2 + 8 + 16) / 4.0, (2 + 4 + 16 + 32) / 4.0, (4 + 32) / 2.0},
      // Top edge.
      {8.0, (8 + 16) / 2.0, (16 + 32) / 2.0, 32.0}};
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 4; ++i) {
      EXPECT_NEAR(Node(n, i, j, 0), want[j][i], kExact) << "node " << i << "," << j;
      EXPECT_NEAR(Node(n, i, j, 1), -10 * want[j][i], 10 * kExact) << "node " << i << "," << j;
    }
}

TEST(NodalAverage, SingleCellGivesItsValueAtAllFourCorners) {
  GridCells cells;
  cells.nx = 1;
  cells.ny = 1;
  cells.values = {7.25};
  const GridNodes n = nodal_average(cells);
  ASSERT_EQ(n.values.size(), 4u);
  for (double v : n.values) EXPECT_EQ(v, 7.25);
}

TEST(NodalAverage, LinearDataIsExactAtInteriorNodes) {
  // f = a + b x + c y sampled at the cell centres. An interior node is the centre of the four
  // cells around it, and the mean of a linear function over points symmetric about a centre is
  // its value there. Border nodes are means of border cells only (no extrapolation), so they are
  // off by half a cell's gradient: a documented property, checked here as its defining rule.
  const double a = 3.5, b = -1.25, c = 0.75;
  auto f = [&](double x, double y) { return a + b * x + c * y; };
  GridCells cells;
  cells.nx = 5;
  cells.ny = 4;
  cells.x0 = 0.5;
  cells.y0 = -1.0;
  cells.dx = 0.25;
  cells.dy = 0.5;
  for (int j = 0; j < cells.ny; ++j)
    for (int i = 0; i < cells.nx; ++i)
      cells.values.push_back(f(cells.x0 + (i + 0.5) * cells.dx, cells.y0 + (j + 0.5) * cells.dy));
  const GridNodes n = nodal_average(cells);
  ASSERT_EQ(n.nx, 6);
  ASSERT_EQ(n.ny, 5);
  // Values of order 1-5: relative 1e-12 is a few hundred ulps of slack for the sums.
  for (int j = 1; j < n.ny - 1; ++j)
    for (int i = 1; i < n.nx - 1; ++i) {
      const double want = f(n.x0 + i * n.dx, n.y0 + j * n.dy);
      EXPECT_NEAR(Node(n, i, j), want, kExact * std::abs(want) + kExact) << "node " << i << "," << j;
    }
  // A corner node is its one cell's value, i.e. f at that cell's centre, not f at the corner.
  const double corner_cell = f(cells.x0 + 0.5 * cells.dx, cells.y0 + 0.5 * cells.dy);
  EXPECT_NEAR(Node(n, 0, 0), corner_cell, kExact);
  // That is f at the corner plus half a cell of gradient: b dx/2 + c dy/2 = 0.03125 here.
  const double border_offset = b * cells.dx / 2 + c * cells.dy / 2;
  ASSERT_NE(border_offset, 0.0);
  EXPECT_NEAR(Node(n, 0, 0) - f(n.x0, n.y0), border_offset, kExact);
}

}  // namespace nodal_test
}  // namespace radrecon
