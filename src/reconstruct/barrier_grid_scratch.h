#pragma once
// The per-thread state of BarrierGrid's queries (barrier_grid.h): a query's stencil, its
// visibility cache, and the cells whose stencil values a thread keeps. Internal to
// reconstruct/barrier_grid*.cpp.

#include <array>
#include <vector>

#include "reconstruct/barrier_grid.h"

namespace radrecon {

namespace barrier_grid_detail {

/// The visibility cache of a query covers sites i-5..i+6 x j-5..j+6 around its cell (i, j):
/// every N(n), N3(n) and N4(n) of its stencil (nodes i-1..i+2), for cell and node sites.
inline constexpr int kWindowBefore = 5;
inline constexpr int kWindow = 12;
/// At most 4 x 4 stencil nodes.
inline constexpr int kStencil = 4;
/// The cells whose stencil values a thread keeps (direct-mapped by cell index): a view's
/// scanline crosses a few dozen cells near a barrier before the next line comes back to them.
inline constexpr size_t kMemoCells = 64;
/// A cell's stencil values are kept only when at most this many barrier segments come near its
/// consulted sites: beyond, proving the visible set the same costs more than it spares.
inline constexpr size_t kMemoMostSegments = 32;
/// With more barrier segments than this in all, no cell is memoised (finding a cell's segments
/// scans them all).
inline constexpr size_t kMemoMostBarrierSegments = 1024;
/// The cell's box is widened by this fraction of the grid's extent plus a spacing, far above the
/// round-off that places a query in its cell (a few ulps of the coordinates), so that every
/// query the cell gets lies inside the box the proof covers.
inline constexpr double kMemoBoxMargin = 1e-9;

}  // namespace barrier_grid_detail

/// One query near a barrier: where it is on the grid and which nodes it interpolates.
struct BarrierGrid::Stencil {
  Vec2 p;             ///< the query clamped onto the grid: visibility is judged from it
  int i, j;           ///< its grid cell
  double u, v;        ///< its position in the cell, [0, 1]
  int a0, a1, b0, b1; ///< the stencil's nodes a0..a1 x b0..b1
};

/// Per-thread buffers of evaluate(); overwritten per query before use.
struct BarrierGrid::Scratch {
  signed char vis[barrier_grid_detail::kWindow * barrier_grid_detail::kWindow];  ///< -1 not tested yet, 0 hidden, 1 visible
  int wi0 = 0, wj0 = 0;                ///< the cache's first site
  bool sees_nothing = false;           ///< rule (e) found no visible site: q sees none
  bool plain[barrier_grid_detail::kStencil * barrier_grid_detail::kStencil];     ///< per stencil node: rule (a)
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
  std::array<CellMemo, barrier_grid_detail::kMemoCells> memo;
  /// Per cell, the one barrier segment whose line crosses its box, if it has exactly one: the
  /// cell's queries are memoised by their side of it (each side's part of the cell sees alike).
  struct CellCut {
    long cell = -1;
    int segment = -1;  ///< the segment's index; -1: none (or several)
  };
  std::array<CellCut, barrier_grid_detail::kMemoCells> cuts;
};

}  // namespace radrecon
