// Gouraud interpolation of cells, against its definition checked by brute force (the 2:1
// balance over all pairs of leaves, the vertex means over all cells, linearity on each
// triangle), its defining property (no cracks: continuous across every leaf edge, T-vertices
// included) and the functions it reproduces (constants; linear functions on a grid away from
// its border).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "core/thread_pool.h"
#include "reconstruct/gouraud.h"
#include "reconstruct/methods.h"

namespace radrecon {
namespace gouraud_test {

// Values that are exact in exact arithmetic cost rounding only: a handful of multiply-adds of
// values of order 1, barycentric weights from coordinates of order 1. 1e-12 leaves ample margin
// and catches any wrong weight or vertex value (off by O(0.1) of the values here).
constexpr double kRelative = 1e-12;

constexpr unsigned kSeed = 20240917;

std::string Where(const Vec2& p) { return "at (" + std::to_string(p.x()) + ", " + std::to_string(p.y()) + ")"; }

/// Quadtree leaves over r: split while `split(r, depth)`.
void Refine(const Rect& r, int depth, const std::function<bool(const Rect&, int)>& split, std::vector<Rect>& out) {
  if (!split(r, depth)) {
    out.push_back(r);
    return;
  }
  const double mx = 0.5 * (r.x0 + r.x1), my = 0.5 * (r.y0 + r.y1);
  for (const Rect& c : {Rect{r.x0, r.y0, mx, my}, Rect{mx, r.y0, r.x1, my}, Rect{r.x0, my, mx, r.y1}, Rect{mx, my, r.x1, r.y1}})
    Refine(c, depth + 1, split, out);
}

/// Random values in [0.5, 2] (radiosity-like), `channels` per cell.
CellSamples WithValues(std::vector<Rect> rects, int channels, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> value(0.5, 2);
  CellSamples s;
  s.cells = std::move(rects);
  s.channels = channels;
  for (size_t k = 0; k < s.cells.size() * channels; ++k) s.values.push_back(value(rng));
  return s;
}

/// An unbalanced quadtree over [0, 2] x [0, 1]: depth 7 around one point next to leaves of depth
/// 1 to 4 (several hanging nodes on their edges), plus random splits.
std::vector<Rect> Unbalanced(const Rect& domain = {0, 0, 2, 1}) {
  std::mt19937 rng(kSeed);
  std::uniform_real_distribution<double> unit(0, 1);
  const Vec2 focus(domain.x0 + 0.305 * (domain.x1 - domain.x0), domain.y0 + 0.37 * (domain.y1 - domain.y0));
  std::vector<Rect> out;
  Refine(domain, 0, [&](const Rect& r, int depth) {
    const bool at_focus = focus.x() >= r.x0 && focus.x() <= r.x1 && focus.y() >= r.y0 && focus.y() <= r.y1;
    return depth < 1 || (at_focus && depth < 7) || (depth < 4 && unit(rng) < 0.3);
  }, out);
  return out;
}

/// A tensor grid with random (non-dyadic) lines: no hanging nodes, nothing to balance.
std::vector<Rect> UnevenGrid() {
  std::mt19937 rng(kSeed + 1);
  std::uniform_real_distribution<double> step(0.05, 0.3);
  std::vector<double> xs{0.1}, ys{-0.3};
  for (int k = 0; k < 8; ++k) xs.push_back(xs.back() + step(rng));
  for (int k = 0; k < 6; ++k) ys.push_back(ys.back() + step(rng));
  std::vector<Rect> out;
  for (size_t j = 0; j + 1 < ys.size(); ++j)
    for (size_t i = 0; i + 1 < xs.size(); ++i) out.push_back({xs[i], ys[j], xs[i + 1], ys[j + 1]});
  return out;
}

struct Layout {
  std::string name;
  std::vector<Rect> cells;
};

std::vector<Layout> Layouts() {
  // The second quadtree's corners are not dyadic numbers: its midpoints are rounded.
  return {{"unbalanced quadtree", Unbalanced()}, {"quadtree on [0.1, 0.8] x [0.3, 0.6]", Unbalanced({0.1, 0.3, 0.8, 0.6})},
          {"uneven grid", UnevenGrid()}};
}

std::vector<double> Eval(const Interpolant& f, const std::vector<Vec2>& points) {
  std::vector<double> out(points.size() * f.channels());
  f.evaluate(points, out);
  return out;
}

/// The number of leaves on the other side of each edge of `r` that share a piece of it.
std::array<int, 4> NeighboursPerEdge(const std::vector<Rect>& leaves, const Rect& r) {
  std::array<int, 4> n{0, 0, 0, 0};  // left, right, bottom, top
  for (const Rect& o : leaves) {
    const bool y_overlap = std::min(o.y1, r.y1) > std::max(o.y0, r.y0);
    const bool x_overlap = std::min(o.x1, r.x1) > std::max(o.x0, r.x0);
    n[0] += o.x1 == r.x0 && y_overlap;
    n[1] += o.x0 == r.x1 && y_overlap;
    n[2] += o.y1 == r.y0 && x_overlap;
    n[3] += o.y0 == r.y1 && x_overlap;
  }
  return n;
}

/// Brute force: the mean value of the cells whose closed rectangle contains p, holes (NaN
/// values) aside; NaN when there are none.
double CellMean(const CellSamples& s, const Vec2& p, int c) {
  double sum = 0;
  int count = 0;
  for (size_t k = 0; k < s.cells.size(); ++k) {
    const Rect& r = s.cells[k];
    if (p.x() >= r.x0 && p.x() <= r.x1 && p.y() >= r.y0 && p.y() <= r.y1 && !std::isnan(s.values[k * s.channels + c]))
      sum += s.values[k * s.channels + c], ++count;
  }
  return count ? sum / count : std::numeric_limits<double>::quiet_NaN();
}

TEST(Gouraud, BalancesTheQuadtree) {
  for (const Layout& layout : Layouts()) {
    SCOPED_TRACE(layout.name);
    const Gouraud g(WithValues(layout.cells, 1, kSeed));
    const std::vector<Rect>& leaves = g.leaves();
    // The input was unbalanced (else the test proves nothing), the output is not.
    int worst_before = 0, worst_after = 0;
    for (const Rect& r : layout.cells)
      for (int n : NeighboursPerEdge(layout.cells, r)) worst_before = std::max(worst_before, n);
    for (const Rect& r : leaves)
      for (int n : NeighboursPerEdge(leaves, r)) worst_after = std::max(worst_after, n);
    if (layout.name != "uneven grid") {
      EXPECT_GT(worst_before, 2);
    }
    EXPECT_LE(worst_after, 2);
    // The leaves tile the input: each lies in the input cell it names, and the areas add up.
    double area = 0;
    for (size_t k = 0; k < leaves.size(); ++k) {
      const Rect& l = leaves[k];
      const Rect& c = layout.cells[static_cast<size_t>(g.leaf_cells()[k])];
      EXPECT_TRUE(l.x0 >= c.x0 && l.x1 <= c.x1 && l.y0 >= c.y0 && l.y1 <= c.y1) << "leaf " << k;
      area += (l.x1 - l.x0) * (l.y1 - l.y0);
    }
    double want = 0;
    for (const Rect& c : layout.cells) want += (c.x1 - c.x0) * (c.y1 - c.y0);
    EXPECT_NEAR(area, want, kRelative * want);
    if (layout.name == "uneven grid") {
      EXPECT_EQ(leaves.size(), layout.cells.size());
    }
  }
}

TEST(Gouraud, IsContinuousAcrossEveryLeafEdge) {
  // Points along every edge of every balanced leaf (its corners, hanging nodes and points
  // between), 1e-9 m to either side. With no crack the two values differ by at most the
  // steepest triangle's slope times 2e-9 m (plus rounding); a crack at a T-vertex is O(0.1).
  for (const Layout& layout : Layouts()) {
    SCOPED_TRACE(layout.name);
    const CellSamples s = WithValues(layout.cells, 2, kSeed + 2);
    const Gouraud g(s);
    double slope = 0;
    for (const auto& t : g.triangles()) {
      const Vec2 a = g.vertices()[t[0]], ab = g.vertices()[t[1]] - a, ac = g.vertices()[t[2]] - a;
      const double det = ab.x() * ac.y() - ab.y() * ac.x();
      for (int c = 0; c < 2; ++c) {
        const double fa = g.vertex_values()[t[0] * 2 + c], db = g.vertex_values()[t[1] * 2 + c] - fa,
                     dc = g.vertex_values()[t[2] * 2 + c] - fa;
        slope = std::max(slope, Vec2((db * ac.y() - dc * ab.y()) / det, (dc * ab.x() - db * ac.x()) / det).norm());
      }
    }
    const double tol = slope * 2e-9 * 1.01 + kRelative * 10;
    Rect box = s.cells[0];
    for (const Rect& r : s.cells) box = {std::min(box.x0, r.x0), std::min(box.y0, r.y0), std::max(box.x1, r.x1), std::max(box.y1, r.y1)};
    std::vector<Vec2> minus, plus;
    for (const Rect& r : g.leaves())
      for (double t : {0.0, 0.1, 0.25, 0.3, 0.5, 0.7, 0.75, 0.9, 1.0}) {
        const double x = r.x0 + t * (r.x1 - r.x0), y = r.y0 + t * (r.y1 - r.y0);
        if (r.x0 > box.x0) minus.emplace_back(r.x0 - 1e-9, y), plus.emplace_back(r.x0 + 1e-9, y);
        if (r.y0 > box.y0) minus.emplace_back(x, r.y0 - 1e-9), plus.emplace_back(x, r.y0 + 1e-9);
      }
    const std::vector<double> a = Eval(g, minus), b = Eval(g, plus);
    for (size_t k = 0; k < a.size(); ++k) EXPECT_NEAR(a[k], b[k], tol) << Where(minus[k / 2]) << " channel " << k % 2;
  }
}

TEST(Gouraud, VertexValuesAreTheMeanOfTheCellsAroundThem) {
  // Each leaf corner: the plain mean of the input cells whose closed rectangle holds it; each fan
  // centre: the mean of its leaf's four corners. Read back through evaluate() at the vertices.
  for (const Layout& layout : Layouts()) {
    SCOPED_TRACE(layout.name);
    const CellSamples s = WithValues(layout.cells, 2, kSeed + 3);
    const Gouraud g(s);
    const std::vector<double> at = Eval(g, g.vertices());
    size_t centres = 0;
    for (size_t v = 0; v < g.vertices().size(); ++v) {
      const Vec2 p = g.vertices()[v];
      for (int c = 0; c < 2; ++c) {
        double want;
        if (v < g.corner_count()) {
          want = CellMean(s, p, c);
        } else {
          const auto leaf = std::find_if(g.leaves().begin(), g.leaves().end(), [&](const Rect& r) {
            return r.center().x() == p.x() && r.center().y() == p.y();
          });
          ASSERT_NE(leaf, g.leaves().end()) << "a fan centre at no leaf's centre " << Where(p);
          want = 0.25 * (CellMean(s, {leaf->x0, leaf->y0}, c) + CellMean(s, {leaf->x1, leaf->y0}, c) +
                         CellMean(s, {leaf->x0, leaf->y1}, c) + CellMean(s, {leaf->x1, leaf->y1}, c));
          centres += c == 0;
        }
        EXPECT_NEAR(at[v * 2 + c], want, kRelative) << "vertex " << v << " " << Where(p);
      }
    }
    if (layout.name != "uneven grid") {
      EXPECT_GT(centres, 0u);  // there were fans to check
    }
  }
}

TEST(Gouraud, IsLinearOnEachTriangle) {
  // At random barycentric points of every triangle, the value is the same combination of the
  // values at its vertices (the centroid among them: the mean of the three).
  const CellSamples s = WithValues(Unbalanced(), 1, kSeed + 4);
  const Gouraud g(s);
  std::mt19937 rng(kSeed);
  std::uniform_real_distribution<double> unit(0, 1);
  for (const auto& t : g.triangles()) {
    const Vec2 a = g.vertices()[t[0]], b = g.vertices()[t[1]], c = g.vertices()[t[2]];
    const std::vector<double> corner = Eval(g, {a, b, c});
    std::vector<std::array<double, 3>> weights{{1.0 / 3, 1.0 / 3, 1.0 / 3}};
    for (int k = 0; k < 3; ++k) {
      const double u = unit(rng), v = unit(rng) * (1 - u);
      weights.push_back({1 - u - v, u, v});
    }
    for (const auto& w : weights) {
      const Vec2 p = w[0] * a + w[1] * b + w[2] * c;
      EXPECT_NEAR(Eval(g, {p})[0], w[0] * corner[0] + w[1] * corner[1] + w[2] * corner[2], kRelative) << Where(p);
    }
  }
}

TEST(Gouraud, ReproducesConstantsInsideAndOutside) {
  CellSamples s = WithValues(Unbalanced(), 3, kSeed);
  for (size_t k = 0; k < s.cells.size(); ++k) s.values[k * 3] = 3.7, s.values[k * 3 + 1] = 0.25, s.values[k * 3 + 2] = 1e3;
  const Gouraud g(s);
  std::mt19937 rng(kSeed);
  std::uniform_real_distribution<double> x(-1, 3), y(-1, 2);
  std::vector<Vec2> pts;
  for (int k = 0; k < 2000; ++k) pts.emplace_back(x(rng), y(rng));
  const std::vector<double> out = Eval(g, pts);
  for (size_t k = 0; k < pts.size(); ++k) {
    EXPECT_NEAR(out[k * 3], 3.7, 3.7 * kRelative) << Where(pts[k]);
    EXPECT_NEAR(out[k * 3 + 1], 0.25, 0.25 * kRelative) << Where(pts[k]);
    EXPECT_NEAR(out[k * 3 + 2], 1e3, 1e3 * kRelative) << Where(pts[k]);
  }
}

TEST(Gouraud, ReproducesLinearFunctionsOnAGridAwayFromItsBorder) {
  // Cell values f(centre) of a linear f: the mean of the four centres around an interior vertex
  // is f there, so f is reproduced on every cell that does not touch the border. Built through
  // the factory from grid data (GridCells -> cells).
  GridCells grid;
  grid.nx = 9, grid.ny = 7, grid.x0 = -1.25, grid.y0 = 0.5, grid.dx = 0.3, grid.dy = 0.45;
  auto f = [](const Vec2& p) { return 1.5 - 0.75 * p.x() + 2.25 * p.y(); };
  for (int j = 0; j < grid.ny; ++j)
    for (int i = 0; i < grid.nx; ++i) grid.values.push_back(f(grid.center(i, j)));
  const auto g = make_grid_interpolant(Method::gouraud, grid);
  ASSERT_TRUE(g) << g.reason();
  std::mt19937 rng(kSeed);
  std::uniform_real_distribution<double> x(grid.x0 + grid.dx, grid.x0 + (grid.nx - 1) * grid.dx),
      y(grid.y0 + grid.dy, grid.y0 + (grid.ny - 1) * grid.dy);
  std::vector<Vec2> pts;
  for (int k = 0; k < 2000; ++k) pts.emplace_back(x(rng), y(rng));
  const std::vector<double> out = Eval(*g.value(), pts);
  for (size_t k = 0; k < pts.size(); ++k) EXPECT_NEAR(out[k], f(pts[k]), kRelative * 10) << Where(pts[k]);
  // On the border, a vertex is the mean of the 1 or 2 cells there: half a cell inward.
  const Vec2 corner(grid.x0, grid.y0), mid_bottom(grid.x0 + 3 * grid.dx, grid.y0);
  EXPECT_NEAR(Eval(*g.value(), {corner})[0], f(grid.center(0, 0)), kRelative * 10);
  EXPECT_NEAR(Eval(*g.value(), {mid_bottom})[0], f(mid_bottom + Vec2(0, 0.5 * grid.dy)), kRelative * 10);
}

TEST(Gouraud, OutsideTakesTheNearestPointOfTheCells) {
  const CellSamples s = WithValues(Unbalanced(), 1, kSeed + 5);
  const Gouraud g(s);
  const std::vector<std::pair<Vec2, Vec2>> cases = {{{-3, 0.4}, {0, 0.4}}, {{2.5, 0.61}, {2, 0.61}},
                                                     {{0.77, -1e6}, {0.77, 0}}, {{1.3, 1.01}, {1.3, 1}},
                                                     {{5, 5}, {2, 1}}, {{-1, -1}, {0, 0}}};
  for (const auto& [query, nearest] : cases)
    EXPECT_EQ(Eval(g, {query})[0], Eval(g, {nearest})[0]) << Where(query);
  // A corner of the domain lies in one cell: its value.
  EXPECT_NEAR(Eval(g, {Vec2(-1, -1)})[0], CellMean(s, {0, 0}, 0), kRelative);
  EXPECT_TRUE(std::isnan(Eval(g, {Vec2(std::numeric_limits<double>::quiet_NaN(), 0.5)})[0]));
}

TEST(Gouraud, SnapsCornersEqualUpToRoundOff) {
  // Corners off by a few ulps (as computed by different expressions) are the same corners.
  const CellSamples exact = WithValues(Unbalanced(), 1, kSeed + 6);
  CellSamples nudged = exact;
  std::mt19937 rng(kSeed);
  std::uniform_int_distribution<int> ulps(-3, 3);
  for (Rect& r : nudged.cells)
    for (double* v : {&r.x0, &r.y0, &r.x1, &r.y1})
      for (int k = ulps(rng); k != 0; k += k > 0 ? -1 : 1) *v = std::nextafter(*v, k > 0 ? 10.0 : -10.0);
  const Gouraud a(exact), b(nudged);
  EXPECT_EQ(a.leaves().size(), b.leaves().size());
  std::uniform_real_distribution<double> x(0, 2), y(0, 1);
  std::vector<Vec2> pts;
  for (int k = 0; k < 1000; ++k) pts.emplace_back(x(rng), y(rng));
  const std::vector<double> va = Eval(a, pts), vb = Eval(b, pts);
  for (size_t k = 0; k < pts.size(); ++k) EXPECT_NEAR(va[k], vb[k], 1e-9) << Where(pts[k]);
}

TEST(Gouraud, HolesTakeTheNearestValueOutsideThemAndHaveNoInfluence) {
  // The cells of [1, 2] x [0, 0.5] (a node of the quadtree) have NaN values: a hole. Every vertex
  // outside it, its outline included, is the mean of the cells around it that are not holes
  // (brute force), so nothing under the hole reaches the values outside; a point inside it (or on
  // its part of the domain's border) takes the value at its nearest point of the other cells
  // (brute force over the cells), where the hole of a cell half under a lamp was drawn black.
  CellSamples s = WithValues(Unbalanced(), 1, kSeed + 8);
  const Rect hole{1, 0, 2, 0.5};
  size_t holes = 0;
  for (size_t k = 0; k < s.cells.size(); ++k) {
    const Vec2 c = s.cells[k].center();
    if (c.x() > hole.x0 && c.x() < hole.x1 && c.y() > hole.y0 && c.y() < hole.y1)
      s.values[k] = std::numeric_limits<double>::quiet_NaN(), ++holes;
  }
  ASSERT_GT(holes, 0u);
  const Gouraud g(s);
  auto strictly_inside = [&](const Vec2& p) { return p.x() > hole.x0 && p.x() < hole.x1 && p.y() > hole.y0 && p.y() < hole.y1; };
  std::vector<Vec2> corners(g.vertices().begin(), g.vertices().begin() + static_cast<std::ptrdiff_t>(g.corner_count()));
  const std::vector<double> at = Eval(g, corners);
  for (size_t v = 0; v < corners.size(); ++v) {
    const double want = CellMean(s, corners[v], 0);  // NaN on the hole's part of the domain border
    if (strictly_inside(corners[v]) || std::isnan(want)) continue;  // points in the hole: below
    EXPECT_NEAR(at[v], want, kRelative) << Where(corners[v]);
  }
  std::mt19937 rng(kSeed);
  std::uniform_real_distribution<double> x(-0.5, 2.5), y(-0.5, 1.5);
  std::vector<Vec2> pts;
  for (int k = 0; k < 2000; ++k) pts.emplace_back(x(rng), y(rng));
  const std::vector<double> out = Eval(g, pts);
  std::vector<Vec2> nearest_outside;  // of the points that only holes hold, once clamped
  std::vector<double> in_holes;
  for (size_t k = 0; k < pts.size(); ++k) {
    const Vec2 clamped(std::clamp(pts[k].x(), 0.0, 2.0), std::clamp(pts[k].y(), 0.0, 1.0));
    EXPECT_FALSE(std::isnan(out[k])) << Where(pts[k]);
    if (!std::isnan(CellMean(s, clamped, 0))) continue;
    double best = std::numeric_limits<double>::infinity();
    Vec2 at_best = clamped;
    for (size_t c = 0; c < s.cells.size(); ++c) {
      if (std::isnan(s.values[c])) continue;
      const Rect& r = s.cells[c];
      const Vec2 on(std::clamp(clamped.x(), r.x0, r.x1), std::clamp(clamped.y(), r.y0, r.y1));
      if ((on - clamped).norm() < best) best = (on - clamped).norm(), at_best = on;
    }
    nearest_outside.push_back(at_best);
    in_holes.push_back(out[k]);
  }
  ASSERT_GT(in_holes.size(), 100u);
  const std::vector<double> there = Eval(g, nearest_outside);
  for (size_t k = 0; k < in_holes.size(); ++k) EXPECT_NEAR(in_holes[k], there[k], kRelative) << Where(nearest_outside[k]);
  // Every cell a hole: no value anywhere.
  CellSamples none = s;
  for (double& v : none.values) v = std::numeric_limits<double>::quiet_NaN();
  for (const double v : Eval(Gouraud(none), pts)) EXPECT_TRUE(std::isnan(v));
}

TEST(Gouraud, OneAndTwoThreadsAgreeBitForBit) {
  const CellSamples s = WithValues(Unbalanced(), 3, kSeed + 7);
  const Gouraud g(s);
  std::mt19937 rng(kSeed);
  std::uniform_real_distribution<double> x(-0.1, 2.1), y(-0.1, 1.1);
  std::vector<Vec2> pts;
  for (int k = 0; k < 20000; ++k) pts.emplace_back(x(rng), y(rng));
  const int threads = worker_thread_count();
  set_worker_thread_count(1);
  const std::vector<double> one = Eval(g, pts);
  set_worker_thread_count(2);
  const std::vector<double> two = Eval(g, pts);
  set_worker_thread_count(threads);
  ASSERT_EQ(0, std::memcmp(one.data(), two.data(), one.size() * sizeof(double)));
}

TEST(Gouraud, RefusesCellsThatDoNotTileARectangle) {
  const std::vector<Rect> grid = UnevenGrid();
  auto refused = [](std::vector<Rect> cells, const std::string& words) {
    const InterpolantResult r = make_cell_interpolant(Method::gouraud, WithValues(std::move(cells), 1, kSeed));
    ASSERT_FALSE(r) << "accepted; expected: " << words;
    EXPECT_NE(r.reason().find(words), std::string::npos) << r.reason();
  };
  std::vector<Rect> cells = grid;
  cells.erase(cells.begin() + 20);  // a hole inside
  refused(cells, "gap or overlap");
  cells = grid;
  cells.erase(cells.begin());  // a corner missing: an L-shape
  refused(cells, "do not tile a rectangle");
  cells = grid;
  cells.push_back(grid[13]);  // a duplicate
  refused(cells, "overlap");
  cells = grid;
  cells[10].x1 = 0.5 * (grid[11].x0 + grid[11].x1);  // reaching into its neighbour
  refused(cells, "overlap");
  cells = grid;
  cells[10].y1 -= 0.01;  // a sliver of a gap
  refused(cells, "gap");
  cells = grid;
  cells[3].x1 = cells[3].x0;
  refused(cells, "no extent");
  cells = grid;
  cells[4].y0 = std::numeric_limits<double>::quiet_NaN();
  refused(cells, "non-finite");

  CellSamples nan_value = WithValues(grid, 1, kSeed);
  nan_value.values[7] = std::numeric_limits<double>::infinity();
  const InterpolantResult v = make_cell_interpolant(Method::gouraud, nan_value);
  ASSERT_FALSE(v);
  EXPECT_NE(v.reason().find("finite"), std::string::npos) << v.reason();

  MethodParams walled;
  walled.barriers = Barriers::from_polylines(std::vector<Polyline>{{{0.2, -0.2}, {0.4, 0.1}}}).value();
  const InterpolantResult b = make_cell_interpolant(Method::gouraud, WithValues(grid, 1, kSeed), walled);
  ASSERT_FALSE(b);
  EXPECT_NE(b.reason().find("does not take barriers"), std::string::npos) << b.reason();
  ScatteredSamples points;
  points.points = {{0, 0}, {1, 0}, {0, 1}};
  points.values = {1, 2, 3};
  const InterpolantResult p = make_scattered_interpolant(Method::gouraud, points);
  ASSERT_FALSE(p);
  EXPECT_NE(p.reason().find("needs cells"), std::string::npos) << p.reason();
}

}  // namespace gouraud_test
}  // namespace radrecon
