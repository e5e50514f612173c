#pragma once
// The data a reconstruction starts from, on a 2-D domain in metres (a surface's (s, t), see
// SurfaceFrame in scene/scene.h). Values are stored point-major: `channels` values per point.

#include <algorithm>
#include <array>
#include <span>
#include <vector>

#include "core/tolerances.h"
#include "core/vec.h"

namespace radrecon {

/// An axis-aligned rectangle [x0, x1] x [y0, y1], metres.
struct Rect {
  double x0, y0, x1, y1;
  Vec2 center() const { return {0.5 * (x0 + x1), 0.5 * (y0 + y1)}; }
};

/// A raster of query points: width x height cell centres of `domain`,
/// point (i, j) = (x0 + (i + 0.5) (x1 - x0) / width, y0 + (j + 0.5) (y1 - y0) / height),
/// in the order row by row, the y0 row first (index j * width + i).
struct Raster {
  int width = 0, height = 0;
  Rect domain{0, 0, 1, 1};
  /// The spacing of the columns and of the rows, metres.
  double dx() const { return (domain.x1 - domain.x0) / width; }
  double dy() const { return (domain.y1 - domain.y0) / height; }
  /// Column i's x and row j's y, metres: the formula above, to the bit.
  double x(size_t i) const { return domain.x0 + (static_cast<double>(i) + 0.5) * dx(); }
  double y(size_t j) const { return domain.y0 + (static_cast<double>(j) + 0.5) * dy(); }
  /// Point (i, j), metres.
  Vec2 point(size_t i, size_t j) const { return {x(i), y(j)}; }
};

/// A piecewise-constant function: disjoint cells, one value (per channel) on each.
struct CellSamples {
  std::vector<Rect> cells;
  std::vector<double> values;  ///< cells.size() * channels
  int channels = 1;
  /// Empty, or one per cell: the cell is this triangle (counter-clockwise), `cells` holding its
  /// bounding box (the elements of a triangle's side).
  std::vector<std::array<Vec2, 3>> triangles;
};

/// Scattered samples: arbitrary points, values per point.
struct ScatteredSamples {
  std::vector<Vec2> points;
  std::vector<double> values;  ///< points.size() * channels
  int channels = 1;
  /// Empty, or points.size() * channels * 2: each value's slope (d/dx, d/dy per channel) where
  /// it is known, NaN where it is not. Border samples (border_samples.h) carry the slope of the
  /// plane their value was fitted from; sibson-c1 takes it instead of fitting one (a fit over
  /// two such samples a millionth of a metre apart, fitted from different neighbours, gave
  /// slopes of 1e5 and values of -314 for data between 0.69 and 1.13).
  std::vector<double> slopes;
};

/// The box of points, and the area they spread over for grids sized by the area per point (the
/// local multiquadric's patches, the k-nearest search's tiles): a box of no width (points on a
/// line) gets tol::kFlatBoxWidthRelative of its length as width, and at least
/// tol::kFlatBoxAreaRelative of its squared length as area, so that such grids stay finite.
/// Relative to the box's length alone, so that the grids scale with the points in any unit (a
/// floor of 1e-12 in absolute units made every box below that size flat and wide: a local
/// thin-plate of data 1e-13 across became the global one). A single point: length 1.
struct PointSpread {
  Vec2 lo, hi;    ///< the box, metres
  Vec2 extent;    ///< its sides, widened where flat
  double area_m2 = 0;
};
inline PointSpread point_spread(std::span<const Vec2> points) {
  PointSpread s{points.front(), points.front(), Vec2::Zero(), 0};
  for (const Vec2& p : points) s.lo = s.lo.cwiseMin(p), s.hi = s.hi.cwiseMax(p);
  const double length = (s.hi - s.lo).maxCoeff();
  s.extent = (s.hi - s.lo).cwiseMax(Vec2::Constant(tol::kFlatBoxWidthRelative * (length > 0 ? length : 1.0)));
  s.area_m2 = std::max(s.extent.x() * s.extent.y(), s.extent.maxCoeff() * s.extent.maxCoeff() * tol::kFlatBoxAreaRelative);
  return s;
}

/// A regular grid of nx x ny cells of size dx x dy starting at (x0, y0), one value per cell,
/// stored row by row from y0 upward (cell (i, j) at j * nx + i).
struct GridCells {
  int nx = 0, ny = 0;
  double x0 = 0, y0 = 0, dx = 1, dy = 1;
  int channels = 1;
  std::vector<double> values;  ///< nx * ny * channels
  /// The centre of cell (i, j).
  Vec2 center(int i, int j) const { return {x0 + (i + 0.5) * dx, y0 + (j + 0.5) * dy}; }
  /// The cells as scattered samples at their centres, in cell order.
  ScatteredSamples centres() const;
};

/// Values at the nodes of a regular grid: node (i, j) at (x0 + i dx, y0 + j dy), i in [0, nx),
/// j in [0, ny), stored row by row (node (i, j) at j * nx + i).
struct GridNodes {
  int nx = 0, ny = 0;
  double x0 = 0, y0 = 0, dx = 1, dy = 1;
  int channels = 1;
  std::vector<double> values;  ///< nx * ny * channels
};


/// The cells of a grid as a general piecewise-constant function.
CellSamples to_cells(const GridCells& grid);

}  // namespace radrecon
