#pragma once
// Bilinear and bicubic interpolation of grid data with barriers (barriers.h): the plain methods
// of bilinear.h and bicubic.h, with every nodal value taken "as seen from the query".
//
// Sites are the data points: the cell centres (cell data, GridCells) or the nodes themselves
// (node data, GridNodes). A site is visible from a query q when !barriers.blocks(q, site). A
// query outside the grid is first clamped onto it, as the plain methods do, and visibility is
// judged from the clamped point. The sites a node n "shares" are: with cell data the (up to 4)
// cells having n as a corner, with node data n itself. Its neighbourhood N(n) is the 2 rings
// of sites around it: cells i-2..i+1 x j-2..j+1 for node (i, j) (4 x 4 cells), or nodes
// i-2..i+2 x j-2..j+2 (5 x 5 nodes), clipped to the grid. The query's window W(q) is the 5 x 5
// sites centred on q's own site (the cell containing q, or the node nearest q), clipped.
//
// The value of node n as seen from q is the first that applies of:
//   (a) every site n shares is visible: the plain nodal value (the mean of its cells,
//       nodal_average(), or the node's value);
//   (b) the least-squares plane through the visible sites of N(n), evaluated at n, when they
//       are at least 3 and not all on one line;
//   (c) the mean of the visible sites n shares, when there is one (cell data only);
//   (d) the least-squares plane through the visible sites of W(q), evaluated at n, when they
//       are at least 3 and not all on one line;
//   (e) the value of the site nearest q among all sites visible from q (ties: the lowest index
//       j * nx + i); when q sees no site at all, q has no value (NaN in every channel).
//
// Bilinear: the plain formula over the 4 corner nodes of q's grid cell, with their values as
// seen from q. Bicubic: when all nodes of q's stencil (nodes i-1..i+2 x j-1..j+2 around q's cell
// (i, j), clipped to the grid) get (a), the plain natural bicubic spline of the whole grid;
// otherwise a local natural cubic spline through the stencil's values as seen from q (zero
// second derivative at the stencil's ends), along x through each stencil row and then along y
// through the row results: the natural spline of the sub-grid formed by the stencil.
//
// Consequences: where no barrier blocks any site of q's stencil the plain method is
// reproduced exactly (the same arithmetic); a cell cut by a barrier is split, each side
// extrapolating from its own side; a function linear on the visible part of the neighbourhoods
// is reproduced (rules (a), (b), (d) and both splines are exact for linear data, given node
// data or interior nodes of cell data, whose plain mean is exact); and with bilinear a site
// never seen from q has no influence on q's value. Bicubic's plain path is the global natural
// spline, whose second derivatives couple every node of the grid (decaying by about 0.27 a
// node): a query whose stencil sees everything still feels, very weakly, nodes behind a barrier
// farther away.
//
// Cost: a query in a cell whose stencil has no barrier segment nearby (flagged per cell when
// built, conservatively) is the plain method's plus a look-up; the others test the visibility
// of their stencil's sites (9 or 25 cells, 4 or 16 nodes), and of more sites only when one is
// hidden, in parallel (core/parallel.h). Rule (e) searches rings of sites outward from q, so a
// query that sees nothing (enclosed by barriers with no site inside) tests every site of the
// grid. Thread-safe; every point is computed on its own, so results never depend on the batch
// or the number of threads.

#include <memory>
#include <vector>

#include "reconstruct/barriers.h"
#include "reconstruct/interpolant.h"
#include "reconstruct/samples.h"

namespace radrecon {

/// Bilinear or bicubic interpolation of grid data with barriers (the rule above).
class BarrierGrid final : public Interpolant {
 public:
  enum class Kind { bilinear, bicubic };
  /// Cell values (the paper's grid data): the plain nodal values are nodal_average(cells).
  /// Needs at least 1 x 1 cells.
  BarrierGrid(const GridCells& cells, Kind kind, Barriers barriers);
  /// Values at grid nodes (point samples on a regular grid). Needs at least 2 x 2 nodes.
  BarrierGrid(const GridNodes& nodes, Kind kind, Barriers barriers);
  ~BarrierGrid() override;
  int channels() const override { return nodes_.channels; }
  void evaluate(std::span<const Vec2> points, std::span<double> out) const override;

 private:
  struct Scratch;
  struct Stencil;

  /// The shared part of the constructors: sites are sites_x x sites_y values (cell centres when
  /// `cell_sites`, else the nodes).
  BarrierGrid(GridNodes plain_nodes, std::vector<double> site_values, bool cell_sites, int sites_x, int sites_y,
              Kind kind, Barriers barriers);
  /// The per-cell flags of near_.
  void mark_cells_near_barriers();
  /// Whether q (finite) lies in a cell flagged in near_.
  bool near_barrier(const Vec2& q) const;
  /// One query near a barrier: its values into out[0, channels).
  void evaluate_near(const Vec2& q, double* out, Scratch& s) const;
  /// The value of a node not seen whole (rules (b) to (e)); false when q sees no site.
  bool hidden_node_value(int a, int b, const Stencil& st, Scratch& s, double* out) const;
  /// Rule (b)/(d): the least-squares plane through the visible sites of [si0, si1] x [sj0, sj1]
  /// at node (a, b); false when fewer than 3 or all on a line.
  bool plane_at_node(int a, int b, int si0, int si1, int sj0, int sj1, const Stencil& st, Scratch& s,
                     double* out) const;
  /// Whether site (si, sj) is visible from the stencil's query (cached in the scratch).
  bool visible(int si, int sj, const Stencil& st, Scratch& s) const;
  /// Rule (e): the index of the site nearest p among those visible from p, or -1.
  long nearest_visible_site(const Vec2& p) const;
  Vec2 site(int si, int sj) const;

  Kind kind_;
  GridNodes nodes_;                    ///< the plain nodal values
  std::vector<double> site_values_;    ///< sites_x_ * sites_y_ * channels, row by row
  bool cell_sites_;
  int sites_x_, sites_y_;
  std::unique_ptr<Interpolant> plain_;  ///< Bilinear or Bicubic of nodes_
  Barriers barriers_;
  std::vector<unsigned char> near_;    ///< per grid cell (nodes_.nx - 1 by nodes_.ny - 1): may see a barrier
};

}  // namespace radrecon
