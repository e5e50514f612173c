#pragma once
// Cells of a surface's parameter domain (scene/scene.h): the unit square of a quad, the unit
// right triangle {u, v >= 0, u + v <= 1} of a triangle. Every mesh element and quadtree node is
// one: a (u,v) box, or a half of one cut by its anti-diagonal. Regular subdivision and the 4-way
// split keep both kinds closed: a triangle's cells are the lower and upper halves of the boxes of
// a regular grid, and splitting a half-box at its edges' midpoints gives three halves of its own
// kind at its corners and one of the other kind in the middle.

#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include "core/vec.h"

namespace radrecon {

enum class CellShape : std::uint8_t {
  box,    ///< [u0,u1] x [v0,v1]
  lower,  ///< the triangle (u0,v0), (u1,v0), (u0,v1): the half below the anti-diagonal
  upper,  ///< the triangle (u1,v0), (u1,v1), (u0,v1): the half above it
};

/// "box", "lower" or "upper" (the solution file's names).
const char* cell_shape_name(CellShape shape);
std::optional<CellShape> parse_cell_shape(const std::string& name);

struct ParamCell {
  double u0 = 0, v0 = 0, u1 = 1, v1 = 1;
  CellShape shape = CellShape::box;

  bool is_triangle() const { return shape != CellShape::box; }
  int vertex_count() const { return is_triangle() ? 3 : 4; }
  /// The vertices counter-clockwise in (u,v), box from (u0,v0), lower from its right angle,
  /// upper from (u1,v0); a triangle repeats its last vertex in the fourth slot.
  std::array<Vec2, 4> vertices() const;
  /// The centroid in (u,v).
  Vec2 centroid() const;
  /// Area in (u,v).
  double area() const { return (u1 - u0) * (v1 - v0) * (is_triangle() ? 0.5 : 1.0); }
  /// The 4-way split at the edges' midpoints: a box's quarters in the order (u low, v low),
  /// (u high, v low), (u low, v high), (u high, v high); a half-box's three corner halves of its
  /// own kind (counter-clockwise from vertex 0) and then its middle, of the other kind.
  std::array<ParamCell, 4> quarters() const;
  /// The index in quarters() of the quarter holding (u, v), a point of this cell; each point
  /// has exactly one (the quarters are half-open towards the cell's interior).
  int quarter_of(double u, double v) const;
  /// The midpoint rule's points of order n: the centroids of the n^2 congruent cells of the
  /// regular subdivision of this cell (n x n boxes, or n^2 halves), all of equal area, in a fixed
  /// order; calls f(Vec2) for each.
  template <class F>
  void for_each_midpoint(int n, F&& f) const;
  /// The cells of that subdivision, in the same order: calls f(ParamCell) for each; the k-th
  /// point of for_each_midpoint(n) is the k-th cell's centroid (up to rounding).
  template <class F>
  void for_each_subcell(int n, F&& f) const;
};

/// The parameter domain of a polygon of `corner_count` corners: the unit box or the lower half
/// of the unit box.
inline ParamCell parameter_domain(int corner_count) {
  return ParamCell{0, 0, 1, 1, corner_count == 3 ? CellShape::lower : CellShape::box};
}

template <class F>
void ParamCell::for_each_midpoint(int n, F&& f) const {
  const double du = (u1 - u0) / n, dv = (v1 - v0) / n;
  if (shape == CellShape::box) {
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) f(Vec2(u0 + (i + 0.5) * du, v0 + (j + 0.5) * dv));
    return;
  }
  // The lower half's sub-triangles; the upper half is its point reflection in the box's centre.
  const bool flip = shape == CellShape::upper;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i + j < n; ++i) {
      const double third = 1.0 / 3.0, two_thirds = 2.0 / 3.0;
      for (int half = 0; half < (i + j < n - 1 ? 2 : 1); ++half) {
        const double a = (i + (half ? two_thirds : third)) * du, b = (j + (half ? two_thirds : third)) * dv;
        f(flip ? Vec2(u1 - a, v1 - b) : Vec2(u0 + a, v0 + b));
      }
    }
}

template <class F>
void ParamCell::for_each_subcell(int n, F&& f) const {
  const double du = (u1 - u0) / n, dv = (v1 - v0) / n;
  if (shape == CellShape::box) {
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        f(ParamCell{u0 + i * du, v0 + j * dv, u0 + (i + 1) * du, v0 + (j + 1) * dv, CellShape::box});
    return;
  }
  // As for_each_midpoint(): the lower half's sub-triangles, the upper half's by point reflection,
  // which turns the box [a, a + du] x [b, b + dv] into [u1 - a - du, u1 - a] x [v1 - b - dv, v1 - b]
  // and swaps its halves.
  const bool flip = shape == CellShape::upper;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i + j < n; ++i)
      for (int half = 0; half < (i + j < n - 1 ? 2 : 1); ++half) {
        const CellShape kind = (half == 0) != flip ? CellShape::lower : CellShape::upper;
        if (!flip) f(ParamCell{u0 + i * du, v0 + j * dv, u0 + (i + 1) * du, v0 + (j + 1) * dv, kind});
        else f(ParamCell{u1 - (i + 1) * du, v1 - (j + 1) * dv, u1 - i * du, v1 - j * dv, kind});
      }
}

}  // namespace radrecon
