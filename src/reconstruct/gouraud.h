#pragma once
// Gouraud interpolation of a piecewise-constant function on rectangular cells (a quadtree's
// leaves or a grid's cells): the classic way to display a radiosity solution, which the paper
// argues against ([CW93] Cohen & Wallace, "Radiosity and Realistic Image Synthesis", 1993,
// pp. 147-149). In metres, on the rectangle the cells tile:
//
//  1. Balance (2:1): a leaf is split into its four quarters, which keep its value, while one of
//     its edges meets more than two leaves on the other side, i.e. has more than one hanging
//     node (a corner of other leaves inside the edge). On a quadtree this is the usual 2:1
//     balance (neighbours differ by at most one level); a grid needs none.
//  2. Triangulate without T-vertices: a leaf without hanging nodes is cut into two triangles by
//     its diagonal from (x0, y0) to (x1, y1); a leaf with hanging nodes is a fan of triangles
//     from its centre over all its boundary vertices (corners and hanging nodes, in order), so
//     that both sides of every edge are linear between the same vertices.
//  3. Vertex values: the plain mean of the values of the input cells (holes aside, see below)
//     whose closed rectangle contains the vertex, as [CW93] (1 to 4 cells; a balanced leaf's pieces count as the one
//     cell they came from, so balancing changes no value). Not area-weighted: a quadtree is fine
//     where the function changes, and area weights would let a large leaf, an average over a far
//     wider region, outweigh the small leaves at their own corners. A fan's centre takes the
//     mean of its leaf's four corner values (the leaf's bilinear value there: exact when the
//     corner values are those of a linear function).
//  4. Linear interpolation over the triangles: C0 everywhere (no cracks at T-vertices).
//
// Reproduces constants. On a regular grid with cell values f(centre) of a linear f, every
// interior vertex (four cells around it) gets f exactly, so the interpolant is f on every cell
// that does not touch the border of the domain (border vertices average 1 or 2 cells, half a
// cell inward). Outside the rectangle: the value at its nearest point (the point clamped onto
// it). A non-finite query gives NaN.
//
// The cells need not be dyadic: corners within tol::kCellSnapRelative of the domain's extent
// count as one point. They must tile a rectangle (ReconstructionError naming a point of a gap
// or an overlap otherwise), have finite values or NaN, and be balanceable without splitting a
// leaf into pieces narrower than half the narrowest cell (always true of a quadtree's leaves).
//
// Holes: a cell with a NaN value (in any channel) has no data, e.g. a cell whose centre lies in a
// region the caller excludes (the floor under a box). It takes part in the tiling and the
// balance but in no vertex mean; a point that only holes contain (inside one, or on its part of
// the domain's border, after clamping) gets the value at its nearest point of the cells that are
// not holes (of the lowest leaf, on a tie), NaN if every cell is one; a point on a hole's outline
// the value of the cells outside. So the values outside a hole do not depend on what lies under
// it, and the part of a hole cell that the caller does not exclude (a cell half under a lamp
// lying on a ceiling) takes its neighbours' values at the hole's outline; the caller masks what it
// excludes. (That extension is continuous but for the points equidistant from two parts of a
// concave hole's outline, deep inside it.) The nearest point is searched in rings of buckets
// around the point: the cost grows with its distance from the nearest cell that is no hole.

#include <array>
#include <vector>

#include "reconstruct/interpolant.h"
#include "reconstruct/samples.h"

namespace radrecon {

class Gouraud final : public Interpolant {
 public:
  explicit Gouraud(const CellSamples& cells);
  int channels() const override { return channels_; }
  void evaluate(std::span<const Vec2> points, std::span<double> out) const override;

  /// The balanced leaves (their corners snapped), and the input cell each one lies in.
  const std::vector<Rect>& leaves() const { return leaves_; }
  const std::vector<int>& leaf_cells() const { return leaf_cells_; }
  /// The triangulation: vertices (the leaves' corners, then the fans' centres), their values
  /// (vertex-major, channels() each) and triangles (counter-clockwise vertex indices).
  const std::vector<Vec2>& vertices() const { return vertices_; }
  const std::vector<double>& vertex_values() const { return vertex_values_; }
  size_t corner_count() const { return corner_count_; }
  const std::vector<std::array<int, 3>>& triangles() const { return triangles_; }

 private:
  /// Buckets over the domain, each listing the leaves whose closed rectangle meets it.
  struct LeafIndex {
    Rect bounds{};
    int nx = 1, ny = 1;
    std::vector<int> first, items;  ///< bucket b holds items[first[b] .. first[b + 1])
    void build(const std::vector<Rect>& rects, double min_w, double min_h);
    int bucket(const Vec2& p) const;
  };
  /// The leaf containing p (already clamped into the domain).
  int locate(const Vec2& p) const;
  /// The leaf that is no hole nearest to p (the lowest of a tie; some must exist), and in `on`
  /// its point nearest to p.
  int nearest_open_leaf(const Vec2& p, Vec2& on) const;

  int channels_ = 1;
  Rect bounds_{};
  std::vector<Rect> leaves_;
  std::vector<int> leaf_cells_;
  std::vector<char> leaf_holes_;     ///< the leaf's cell has a NaN value
  std::vector<int> leaf_triangles_;  ///< leaf k owns triangles [leaf_triangles_[k], [k + 1])
  bool any_open_ = false;             ///< some leaf is no hole
  std::vector<Vec2> vertices_;
  std::vector<double> vertex_values_;
  size_t corner_count_ = 0;
  std::vector<std::array<int, 3>> triangles_;
  LeafIndex index_;
};

}  // namespace radrecon
