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
// i-2..i+2 x j-2..j+2 (5 x 5 nodes), clipped to the grid; likewise Nr(n) is the r rings: cells
// i-r..i+r-1 x j-r..j+r-1, or nodes i-r..i+r x j-r..j+r, clipped.
//
// The value of node n as seen from q is the first that applies of:
//   (a) every site n shares is visible: the plain nodal value (the mean of its cells,
//       nodal_average(), or the node's value);
//   (b) the least-squares plane through the visible sites of N(n), evaluated at n, when they
//       are at least 3 and not all on one line;
//   (c) the mean of the visible sites n shares, when there is one (cell data only);
//   (d) the least-squares plane through the visible sites of N3(n), else of N4(n), evaluated
//       at n, when they are at least 3 and not all on one line;
//   (e) the value of the site nearest n among all sites visible from q (ties: the lowest index
//       j * nx + i); when q sees no site at all, q has no value (NaN in every channel).
// Each rule depends on q only through which sites q sees (the visible set): nothing else of q
// enters a nodal value.
//
// Bilinear: the plain formula over the 4 corner nodes of q's grid cell, with their values as
// seen from q.
//
// Bicubic: by the distance d from q to the nearest barrier segment (Barriers::distance_to), in
// cell diagonals D = sqrt(dx^2 + dy^2), with d1 = kLocalDiagonals D and d2 = kPlainDiagonals D:
//   - d >= d2: the plain natural bicubic spline of the whole grid (bicubic.h), bit for bit;
//   - d < d2: S = (1 - w) S_plain + w S_local, with w = 1 for d <= d1 and the smoothstep
//     w = t^2 (3 - 2 t), t = (d2 - d) / (d2 - d1), between (0 at d2; w is C1 in d).
// S_local is Keys' cubic convolution (a = -1/2, the Catmull-Rom spline) over the 4 x 4 stencil
// of nodes i-1..i+2 x j-1..j+2 around q's cell (i, j), with their values as seen from q: along x
// through each row, then along y. At the grid's border Keys' end condition stands in for the
// missing node (f(-1) = 3 f(0) - 3 f(1) + f(2), and its mirror image; with only 2 nodes along an
// axis, linear extrapolation). On a cell edge it depends only on the 4 nodes of that edge's grid
// line, so neighbouring cells agree there. S_plain is the plain spline at q: where w < 1,
// d > d1 = 3 D, while every site of the stencil lies within 2.5 D of q (2 D with node data), so
// q sees them all and the plain nodal values are the values as seen from q.
//
// Consequences:
//   - continuity: a node's value as seen from q depends on q only through the set of sites q
//     sees; for given nodal values both schemes are continuous across cell edges; w is
//     continuous in q. So bilinear and bicubic are continuous wherever that set does not
//     change: everywhere except across barriers and along the sight lines that graze a
//     barrier's end (where a site comes into or out of view);
//   - where no barrier is near the plain method is reproduced exactly (the same arithmetic):
//     bilinear where no site of its stencil is hidden, bicubic beyond d2;
//   - a cell cut by a barrier is split, each side extrapolating from its own side;
//   - a function linear on the visible part of the neighbourhoods is reproduced wherever rules
//     (a), (b) and (d) give the nodal values (exact for linear data, given node data or interior
//     nodes of cell data, whose plain mean is exact; (c) and (e) are not), since bilinear, Keys'
//     scheme and the plain spline are exact for linear data. The blend zone d1 < d < d2 with cell
//     data is exact only as far as the plain spline is: the border nodes (the mean of 2 border
//     cells) are not exact, and the global spline carries that inward, decaying by about 0.27 a
//     node;
//   - a site never seen from q has exactly no influence on q's value with bilinear, and with
//     bicubic wherever d <= d1 (Keys' scheme is local: the stencil's values as seen from q).
//     For d1 < d < d2 the plain spline's share (1 - w) still feels, weakly, the nodes behind a
//     barrier, all beyond the stencil: the global spline's weights decay by a factor of about
//     0.27 (2 - sqrt 3) per node.
//
// Cost: a query in a cell flagged when built (conservatively: bilinear, its stencil may see a
// barrier; bicubic, some point of it lies within d2 of one) runs on the barrier path; the others
// cost the plain method's plus a look-up. On it, bicubic first measures the distance to the
// barriers: beyond d2 the plain spline; beyond d1, or beyond the stencil's farthest site, Keys'
// scheme of the plain nodal values (all seen: no visibility test) and where w < 1 the plain
// spline too. Otherwise the visibility of the stencil's sites is tested (9 or 25 cells, 4 or 16
// nodes), and of more sites only when one is hidden. Barrier-path queries run in parallel
// (core/parallel.h). Rule (e) searches rings of sites outward from the node, so a query that
// sees nothing (enclosed by barriers with no site inside) tests every site of the grid (once:
// it then has no value). A thread keeps, for the cells its queries come back to, the stencil's
// values as seen from the cell, once it has proven (exact orientations at the cell's corners,
// linear in q) that every site they consult is seen, or hidden, alike from all of the cell, or
// from all of its part on one side of the one barrier line crossing it: the rules then give
// every such query the same values, which it takes instead of the tests. Thread-safe; every
// point gets what it would get on its own, bit for bit, so results never depend on the batch or
// the number of threads.

#include <array>
#include <memory>
#include <vector>

#include "reconstruct/barriers.h"
#include "reconstruct/interpolant.h"
#include "reconstruct/samples.h"

namespace radrecon {

/// Bilinear, bicubic or hermite interpolation of grid data with barriers (the rule above).
/// Hermite is bicubic's rule with the plain hermite interpolant (hermite.h) in place of the
/// natural spline: as hermite is Keys' scheme itself, the blend then changes nothing where every
/// site is seen, and every value depends on the 4 x 4 nodes around its cell only.
class BarrierGrid final : public Interpolant {
 public:
  enum class Kind { bilinear, bicubic, hermite };
  /// Bicubic: within this many cell diagonals of a barrier, Keys' local scheme alone (d1 of the
  /// rule). At least 2.5, the farthest a stencil's site can be from q (cell data, q at a node),
  /// so that the plain spline, weighed only beyond d1, always sees its whole stencil; half a
  /// diagonal more keeps that so whatever the round-off of the distance.
  static constexpr double kLocalDiagonals = 3.0;
  /// Bicubic: from this many cell diagonals of a barrier on, the plain global spline alone (d2
  /// of the rule). 1.5 diagonals of blend keep the smoothstep's slope (at most 1.5 / (d2 - d1),
  /// one per diagonal) gentle: the blend adds w' (S_local - S_plain), the two schemes' difference
  /// per diagonal, to the gradient.
  static constexpr double kPlainDiagonals = 4.5;

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
  /// The stencil's node values as seen from its query into s.values (rules (a) to (e));
  /// all_plain: rule (a) held for every node (bilinear then leaves the values unset); false when
  /// q sees no site.
  bool stencil_values_seen(const Stencil& st, Scratch& s, bool& all_plain) const;
  /// The stencil's cell's box, widened a little (counter-clockwise from the lower left): every
  /// query placed in the cell lies inside it.
  std::array<Vec2, 4> cell_box(const Stencil& st) const;
  /// The index of the one barrier segment whose line crosses the cell's box (not strictly on
  /// one side of it), or -1 when none or several do.
  int line_crossing(const Stencil& st) const;
  /// Whether every site the query tested (in s's window) is seen, or hidden, alike from every
  /// point of the stencil's cell (with `cut` >= 0: every point strictly on `side` of segment
  /// cut's line): then every such query tests the same sites with the same answers and computes
  /// the same stencil values (the rules depend on q only through them).
  bool cell_sees_alike(const Stencil& st, const Scratch& s, int cut, int side) const;
  /// The value of a node not seen whole (rules (b) to (e)); false when q sees no site.
  bool hidden_node_value(int a, int b, const Stencil& st, Scratch& s, double* out) const;
  /// Rule (b)/(d): the least-squares plane through the visible sites of [si0, si1] x [sj0, sj1]
  /// at node (a, b); false when fewer than 3 or all on a line.
  bool plane_at_node(int a, int b, int si0, int si1, int sj0, int sj1, const Stencil& st, Scratch& s,
                     double* out) const;
  /// Bicubic: the distance from the stencil's query to its farthest site (the sites its nodes
  /// share).
  double stencil_reach(const Stencil& st) const;
  /// Bicubic: Keys' scheme over the stencil's values in the scratch, blended with the plain
  /// spline at q when w < 1; into out[0, channels).
  void keys_blend(const Stencil& st, double w, Scratch& s, const Vec2& q, double* out) const;
  /// Whether site (si, sj) is visible from the stencil's query (cached in the scratch).
  bool visible(int si, int sj, const Stencil& st, Scratch& s) const;
  /// Rule (e): the index of the site nearest node (a, b) among those visible from the stencil's
  /// query (ties: the lowest index), or -1 when it sees none.
  long nearest_visible_site(int a, int b, const Stencil& st, Scratch& s) const;
  Vec2 site(int si, int sj) const;

  Kind kind_;
  GridNodes nodes_;                    ///< the plain nodal values
  std::vector<double> site_values_;    ///< sites_x_ * sites_y_ * channels, row by row
  bool cell_sites_;
  int sites_x_, sites_y_;
  std::unique_ptr<Interpolant> plain_;  ///< Bilinear or Bicubic of nodes_
  Barriers barriers_;
  double local_distance_ = 0, plain_distance_ = 0;  ///< bicubic's d1 and d2, metres
  std::vector<unsigned char> near_;    ///< per grid cell (nodes_.nx - 1 by nodes_.ny - 1): may be near a barrier
};

}  // namespace radrecon
