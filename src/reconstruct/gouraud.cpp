#include "reconstruct/gouraud.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <tuple>
#include <utility>

#include "core/check.h"
#include "core/parallel.h"
#include "core/tolerances.h"

namespace radrecon {
namespace {

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

/// Canonical coordinates along one axis: a value within `tol` of a known one is that one.
class Axis {
 public:
  explicit Axis(double tol) : tol_(tol) {}
  /// The nearest known value within tol of v; else v, which becomes known.
  double snap(double v) {
    const auto hi = known_.lower_bound(v);
    double best = v, dist = std::numeric_limits<double>::infinity();
    if (hi != known_.end() && *hi - v <= tol_) best = *hi, dist = *hi - v;
    if (hi != known_.begin() && v - *std::prev(hi) <= tol_ && v - *std::prev(hi) < dist) best = *std::prev(hi);
    if (best == v) known_.insert(v);
    return best;
  }

 private:
  double tol_;
  std::set<double> known_;
};

/// The leaves' corners on each grid line: lines[c] holds the other coordinate of every corner
/// on the line x = c (vertical lines) or y = c (horizontal lines).
using Lines = std::map<double, std::set<double>>;

/// The corners on `line` strictly between lo and hi, increasing; at most `limit`.
std::vector<double> inside(const Lines& lines, double line, double lo, double hi, size_t limit = SIZE_MAX) {
  std::vector<double> out;
  const auto it = lines.find(line);
  if (it == lines.end()) return out;
  for (auto v = it->second.upper_bound(lo); v != it->second.end() && *v < hi && out.size() < limit; ++v)
    out.push_back(*v);
  return out;
}

void add_corners(Lines& vertical, Lines& horizontal, const Rect& r) {
  for (double x : {r.x0, r.x1})
    for (double y : {r.y0, r.y1}) vertical[x].insert(y), horizontal[y].insert(x);
}

/// Refuses cells that do not tile `bounds`. Along each vertical line x = c, the cells starting
/// there (left edges) and those ending there (right edges) must each be disjoint and cover the
/// same y-intervals (the whole height on the domain's left and right borders): then the number
/// of cells over a point is the same on both sides of every line, 1 inside the domain.
void check_tiling(const std::vector<Rect>& cells, const Rect& bounds) {
  struct Edge {
    double x;
    int side;  // 0: a cell's left edge, 1: a right edge
    double y0, y1;
  };
  std::vector<Edge> edges;
  edges.reserve(2 * cells.size());
  for (const Rect& r : cells) edges.push_back({r.x0, 0, r.y0, r.y1}), edges.push_back({r.x1, 1, r.y0, r.y1});
  std::sort(edges.begin(), edges.end(), [](const Edge& a, const Edge& b) {
    return std::tie(a.x, a.side, a.y0) < std::tie(b.x, b.side, b.y0);
  });
  using Runs = std::vector<std::pair<double, double>>;
  const Runs whole = {{bounds.y0, bounds.y1}};
  for (size_t begin = 0; begin < edges.size();) {
    const double x = edges[begin].x;
    Runs runs[2];
    size_t end = begin;
    for (; end < edges.size() && edges[end].x == x; ++end) {
      const Edge& e = edges[end];
      Runs& r = runs[e.side];
      if (!r.empty() && e.y0 < r.back().second)
        throw ReconstructionError("the cells overlap: two cells " + std::string(e.side ? "end" : "start") +
                                  " on the line x = " + number(x) + " between y = " + number(e.y0) + " and " +
                                  number(std::min(e.y1, r.back().second)));
      if (!r.empty() && e.y0 == r.back().second) r.back().second = e.y1;
      else r.emplace_back(e.y0, e.y1);
    }
    // Cells start where others end, on the domain's left border where nothing ends, and end
    // on its right border where nothing starts (no cell ends on the left border nor starts on
    // the right one).
    const Runs& a = x == bounds.x1 ? runs[1] : runs[0];
    const Runs& b = x == bounds.x0 || x == bounds.x1 ? whole : runs[1];
    if (a != b) {
      size_t k = 0;
      while (k < a.size() && k < b.size() && a[k] == b[k]) ++k;
      double y;  // the first height where they differ
      if (k < a.size() && k < b.size())
        y = a[k].first != b[k].first ? std::min(a[k].first, b[k].first) : std::min(a[k].second, b[k].second);
      else
        y = k < a.size() ? a[k].first : b[k].first;
      throw ReconstructionError("the cells do not tile a rectangle: they leave a gap or overlap at the line x = " +
                                number(x) + " near y = " + number(y));
    }
    begin = end;
  }
}

/// The number of hanging nodes (other leaves' corners) inside r's edges, per edge, is > 1.
bool needs_split(const Lines& vertical, const Lines& horizontal, const Rect& r) {
  return inside(vertical, r.x0, r.y0, r.y1, 2).size() > 1 || inside(vertical, r.x1, r.y0, r.y1, 2).size() > 1 ||
         inside(horizontal, r.y0, r.x0, r.x1, 2).size() > 1 || inside(horizontal, r.y1, r.x0, r.x1, 2).size() > 1;
}

int bucket_of(double v, double lo, double width, int n) {
  return std::clamp(static_cast<int>((v - lo) / width), 0, n - 1);
}

}  // namespace

void Gouraud::LeafIndex::build(const std::vector<Rect>& rects, double min_w, double min_h) {
  // One bucket per narrowest leaf, at most 1024 per axis: a bucket meets O(1) leaves of a grid or
  // of a quadtree's finest level.
  const double w = bounds.x1 - bounds.x0, h = bounds.y1 - bounds.y0;
  nx = static_cast<int>(std::clamp(std::ceil(w / min_w), 1.0, 1024.0));
  ny = static_cast<int>(std::clamp(std::ceil(h / min_h), 1.0, 1024.0));
  const double bw = w / nx, bh = h / ny;
  // Each rectangle goes to every bucket its closed extent meets (bucket_of is monotonic, so a
  // point of the rectangle falls in one of them).
  auto range = [&](const Rect& r) {
    return std::array<int, 4>{bucket_of(r.x0, bounds.x0, bw, nx), bucket_of(r.x1, bounds.x0, bw, nx),
                              bucket_of(r.y0, bounds.y0, bh, ny), bucket_of(r.y1, bounds.y0, bh, ny)};
  };
  first.assign(static_cast<size_t>(nx) * ny + 1, 0);
  for (const Rect& r : rects) {
    const auto b = range(r);
    for (int j = b[2]; j <= b[3]; ++j)
      for (int i = b[0]; i <= b[1]; ++i) ++first[static_cast<size_t>(j) * nx + i + 1];
  }
  for (size_t k = 1; k < first.size(); ++k) first[k] += first[k - 1];
  items.assign(static_cast<size_t>(first.back()), 0);
  std::vector<int> fill(first.begin(), first.end() - 1);
  for (size_t k = 0; k < rects.size(); ++k) {
    const auto b = range(rects[k]);
    for (int j = b[2]; j <= b[3]; ++j)
      for (int i = b[0]; i <= b[1]; ++i) items[static_cast<size_t>(fill[static_cast<size_t>(j) * nx + i]++)] = static_cast<int>(k);
  }
}

int Gouraud::LeafIndex::bucket(const Vec2& p) const {
  return bucket_of(p.y(), bounds.y0, (bounds.y1 - bounds.y0) / ny, ny) * nx +
         bucket_of(p.x(), bounds.x0, (bounds.x1 - bounds.x0) / nx, nx);
}

namespace {

bool contains(const Rect& r, const Vec2& p) {
  return p.x() >= r.x0 && p.x() <= r.x1 && p.y() >= r.y0 && p.y() <= r.y1;
}

}  // namespace

Gouraud::Gouraud(const CellSamples& input) : channels_(input.channels) {
  const int C = channels_;
  RR_CHECK(C >= 1, "no channels");
  RR_CHECK_EQ(input.values.size(), input.cells.size() * static_cast<size_t>(C), "values do not match the cells");
  if (input.cells.empty()) throw ReconstructionError("gouraud needs at least one cell");
  for (const Rect& r : input.cells)
    if (!std::isfinite(r.x0) || !std::isfinite(r.x1) || !std::isfinite(r.y0) || !std::isfinite(r.y1) ||
        !(r.x1 > r.x0 && r.y1 > r.y0))
      throw ReconstructionError("a cell has no extent or a non-finite corner: [" + number(r.x0) + ", " + number(r.x1) +
                                "] x [" + number(r.y0) + ", " + number(r.y1) + "]");
  // A cell with a NaN value is a hole (no data: a region the caller excludes); infinities are
  // refused.
  std::vector<char> hole(input.cells.size(), 0);
  for (size_t k = 0; k < input.values.size(); ++k) {
    if (std::isinf(input.values[k])) throw ReconstructionError("gouraud needs finite cell values (or NaN for a hole)");
    if (std::isnan(input.values[k])) hole[k / static_cast<size_t>(C)] = 1;
  }

  // Snap the corners: equal up to round-off means equal, so that edges match exactly.
  Rect box = input.cells[0];
  for (const Rect& r : input.cells)
    box = {std::min(box.x0, r.x0), std::min(box.y0, r.y0), std::max(box.x1, r.x1), std::max(box.y1, r.y1)};
  const double tol = tol::kCellSnapRelative * std::max(box.x1 - box.x0, box.y1 - box.y0);
  Axis ax(tol), ay(tol);
  {
    std::vector<double> xs, ys;  // known in increasing order, so that snapping ignores cell order
    for (const Rect& r : input.cells) xs.push_back(r.x0), xs.push_back(r.x1), ys.push_back(r.y0), ys.push_back(r.y1);
    std::sort(xs.begin(), xs.end());
    std::sort(ys.begin(), ys.end());
    for (double x : xs) ax.snap(x);
    for (double y : ys) ay.snap(y);
  }
  std::vector<Rect> cells;
  double min_w = std::numeric_limits<double>::infinity(), min_h = min_w;
  for (const Rect& r : input.cells) {
    const Rect s{ax.snap(r.x0), ay.snap(r.y0), ax.snap(r.x1), ay.snap(r.y1)};
    if (!(s.x1 > s.x0 && s.y1 > s.y0))
      throw ReconstructionError("a cell is narrower than " + number(tol::kCellSnapRelative) + " of the domain: [" +
                                number(r.x0) + ", " + number(r.x1) + "] x [" + number(r.y0) + ", " + number(r.y1) + "]");
    cells.push_back(s);
    min_w = std::min(min_w, s.x1 - s.x0);
    min_h = std::min(min_h, s.y1 - s.y0);
  }
  bounds_ = {ax.snap(box.x0), ay.snap(box.y0), ax.snap(box.x1), ay.snap(box.y1)};
  check_tiling(cells, bounds_);

  // 1. Balance: split leaves with two or more hanging nodes on an edge until none has.
  Lines vertical, horizontal;
  for (const Rect& r : cells) add_corners(vertical, horizontal, r);
  std::vector<Rect> leaves = cells;
  std::vector<int> leaf_cell(cells.size());
  for (size_t k = 0; k < cells.size(); ++k) leaf_cell[k] = static_cast<int>(k);
  std::vector<char> alive(cells.size(), 1);
  for (bool changed = true; changed;) {
    changed = false;
    for (size_t k = 0; k < leaves.size(); ++k) {  // the children of a split are checked in the same pass
      if (!alive[k] || !needs_split(vertical, horizontal, leaves[k])) continue;
      const Rect r = leaves[k];
      const double mx = ax.snap(0.5 * (r.x0 + r.x1)), my = ay.snap(0.5 * (r.y0 + r.y1));
      if (std::min(mx - r.x0, r.x1 - mx) < 0.5 * min_w || std::min(my - r.y0, r.y1 - my) < 0.5 * min_h)
        throw ReconstructionError("the cells cannot be balanced (2:1) without splitting the leaf [" + number(r.x0) + ", " +
                                  number(r.x1) + "] x [" + number(r.y0) + ", " + number(r.y1) +
                                  "] below half the narrowest cell: they are not the leaves of a quadtree");
      alive[k] = 0;
      const int cell = leaf_cell[k];
      for (const Rect& child : {Rect{r.x0, r.y0, mx, my}, Rect{mx, r.y0, r.x1, my}, Rect{r.x0, my, mx, r.y1},
                                Rect{mx, my, r.x1, r.y1}}) {
        leaves.push_back(child);
        leaf_cell.push_back(cell);
        alive.push_back(1);
        add_corners(vertical, horizontal, child);
      }
      changed = true;
    }
  }
  for (size_t k = 0; k < leaves.size(); ++k)
    if (alive[k])
      leaves_.push_back(leaves[k]), leaf_cells_.push_back(leaf_cell[k]), leaf_holes_.push_back(hole[static_cast<size_t>(leaf_cell[k])]);

  // 2. Vertices: every leaf corner, valued by the mean of the input cells that contain it.
  index_.bounds = bounds_;
  index_.build(cells, min_w, min_h);
  std::map<double, std::pair<std::vector<double>, int>> ids;  // x -> (its corners' y, first id)
  for (const auto& [x, ys] : vertical) {
    ids[x] = {std::vector<double>(ys.begin(), ys.end()), static_cast<int>(vertices_.size())};
    for (double y : ys) vertices_.emplace_back(x, y);
  }
  corner_count_ = vertices_.size();
  vertex_values_.assign(corner_count_ * C, 0.0);
  for (size_t v = 0; v < corner_count_; ++v) {
    const int b = index_.bucket(vertices_[v]);
    int count = 0;
    for (int i = index_.first[static_cast<size_t>(b)]; i < index_.first[static_cast<size_t>(b) + 1]; ++i) {
      const int cell = index_.items[static_cast<size_t>(i)];
      if (hole[static_cast<size_t>(cell)] || !contains(cells[static_cast<size_t>(cell)], vertices_[v])) continue;
      ++count;
      for (int c = 0; c < C; ++c) vertex_values_[v * C + c] += input.values[static_cast<size_t>(cell) * C + c];
    }
    for (int c = 0; c < C; ++c)  // a corner of holes only: NaN (used by no triangle that is evaluated)
      vertex_values_[v * C + c] = count ? vertex_values_[v * C + c] / count : std::numeric_limits<double>::quiet_NaN();
  }
  auto id = [&](double x, double y) {
    const auto& [ys, first] = ids.at(x);
    const auto it = std::lower_bound(ys.begin(), ys.end(), y);
    RR_CHECK(it != ys.end() && *it == y, "a leaf corner is not a vertex");
    return first + static_cast<int>(it - ys.begin());
  };

  // 3. Triangles: two per leaf without hanging nodes, else a fan from the leaf's centre.
  leaf_triangles_.push_back(0);
  for (const Rect& r : leaves_) {
    std::vector<int> ring{id(r.x0, r.y0)};  // counter-clockwise from the lower left corner
    for (double x : inside(horizontal, r.y0, r.x0, r.x1)) ring.push_back(id(x, r.y0));
    ring.push_back(id(r.x1, r.y0));
    for (double y : inside(vertical, r.x1, r.y0, r.y1)) ring.push_back(id(r.x1, y));
    ring.push_back(id(r.x1, r.y1));
    const std::vector<double> top = inside(horizontal, r.y1, r.x0, r.x1), left = inside(vertical, r.x0, r.y0, r.y1);
    for (auto x = top.rbegin(); x != top.rend(); ++x) ring.push_back(id(*x, r.y1));
    ring.push_back(id(r.x0, r.y1));
    for (auto y = left.rbegin(); y != left.rend(); ++y) ring.push_back(id(r.x0, *y));
    if (ring.size() == 4) {
      triangles_.push_back({ring[0], ring[1], ring[2]});
      triangles_.push_back({ring[0], ring[2], ring[3]});
    } else {
      const int centre = static_cast<int>(vertices_.size());
      vertices_.push_back(r.center());
      for (int c = 0; c < C; ++c) {
        double sum = 0;
        for (int corner : {id(r.x0, r.y0), id(r.x1, r.y0), id(r.x1, r.y1), id(r.x0, r.y1)})
          sum += vertex_values_[static_cast<size_t>(corner) * C + c];
        vertex_values_.push_back(0.25 * sum);
      }
      for (size_t k = 0; k < ring.size(); ++k) triangles_.push_back({centre, ring[k], ring[(k + 1) % ring.size()]});
    }
    leaf_triangles_.push_back(static_cast<int>(triangles_.size()));
  }
  index_.build(leaves_, min_w * 0.5, min_h * 0.5);

  any_open_ = std::find(leaf_holes_.begin(), leaf_holes_.end(), 0) != leaf_holes_.end();
}

int Gouraud::nearest_open_leaf(const Vec2& p, Vec2& on) const {
  // Rings of buckets around p's, outwards: a leaf in ring r + 1 is at least r bucket widths
  // away, so the search ends once that exceeds the best distance found.
  const double bw = (index_.bounds.x1 - index_.bounds.x0) / index_.nx, bh = (index_.bounds.y1 - index_.bounds.y0) / index_.ny;
  const int b = index_.bucket(p), bx = b % index_.nx, by = b / index_.nx;
  double best_sq = std::numeric_limits<double>::infinity();
  int best = -1;
  for (int r = 0; r <= std::max(index_.nx, index_.ny); ++r) {
    const double reach = (r - 1) * std::min(bw, bh);  // the least distance to a bucket of ring r
    if (r > 0 && reach > 0 && reach * reach > best_sq) break;
    for (int j = by - r; j <= by + r; ++j) {
      if (j < 0 || j >= index_.ny) continue;
      const bool edge_row = j == by - r || j == by + r;
      for (int i = bx - r; i <= bx + r; i += edge_row ? 1 : 2 * r) {
        if (i >= 0 && i < index_.nx) {
          const size_t bucket = static_cast<size_t>(j) * index_.nx + i;
          for (int k = index_.first[bucket]; k < index_.first[bucket + 1]; ++k) {
            const int leaf = index_.items[static_cast<size_t>(k)];
            if (leaf_holes_[static_cast<size_t>(leaf)]) continue;
            const Rect& rect = leaves_[static_cast<size_t>(leaf)];
            const Vec2 q(std::clamp(p.x(), rect.x0, rect.x1), std::clamp(p.y(), rect.y0, rect.y1));
            const double d_sq = (q - p).squaredNorm();
            if (d_sq < best_sq || (d_sq == best_sq && leaf < best)) best_sq = d_sq, best = leaf, on = q;
          }
        }
        if (r == 0) break;
      }
    }
  }
  return best;
}

int Gouraud::locate(const Vec2& p) const {
  const size_t b = static_cast<size_t>(index_.bucket(p));
  int in_hole = -1;  // a point on a hole's outline takes the leaf outside it
  for (int i = index_.first[b]; i < index_.first[b + 1]; ++i) {
    const int leaf = index_.items[static_cast<size_t>(i)];
    if (!contains(leaves_[static_cast<size_t>(leaf)], p)) continue;
    if (!leaf_holes_[static_cast<size_t>(leaf)]) return leaf;
    if (in_hole < 0) in_hole = leaf;
  }
  return in_hole;
}

void Gouraud::evaluate(std::span<const Vec2> points, std::span<double> out) const {
  const int C = channels_;
  RR_CHECK(out.size() == points.size() * static_cast<size_t>(C), "output size does not match the query points");
  parallel_for(0, static_cast<std::int64_t>(points.size()), [&](std::int64_t k) {
    const Vec2& q = points[static_cast<size_t>(k)];
    double* o = &out[static_cast<size_t>(k) * C];
    if (!q.allFinite()) {
      for (int c = 0; c < C; ++c) o[c] = std::numeric_limits<double>::quiet_NaN();
      return;
    }
    Vec2 p(std::clamp(q.x(), bounds_.x0, bounds_.x1), std::clamp(q.y(), bounds_.y0, bounds_.y1));
    int leaf = locate(p);
    RR_CHECK_GE(leaf, 0, "a point of the domain is in no leaf");
    if (leaf_holes_[static_cast<size_t>(leaf)]) {
      if (!any_open_) {  // every leaf a hole
        for (int c = 0; c < C; ++c) o[c] = std::numeric_limits<double>::quiet_NaN();
        return;
      }
      Vec2 on = p;
      leaf = nearest_open_leaf(p, on);  // the value at the nearest point of the leaves outside the holes
      p = on;
    }
    // The leaf's triangle that contains p: the one whose smallest barycentric coordinate is
    // largest (>= 0 up to round-off; on a shared edge either triangle gives the same value).
    double best = -std::numeric_limits<double>::infinity(), weights[3] = {0, 0, 0};
    int best_triangle = -1;
    for (int t = leaf_triangles_[static_cast<size_t>(leaf)]; t < leaf_triangles_[static_cast<size_t>(leaf) + 1]; ++t) {
      const auto& tri = triangles_[static_cast<size_t>(t)];
      const Vec2 a = vertices_[static_cast<size_t>(tri[0])], ab = vertices_[static_cast<size_t>(tri[1])] - a,
                 ac = vertices_[static_cast<size_t>(tri[2])] - a, ap = p - a;
      const double area = cross(ab, ac);
      const double wb = cross(ap, ac) / area, wc = cross(ab, ap) / area;
      const double wa = 1 - wb - wc, least = std::min({wa, wb, wc});
      if (least > best) best = least, best_triangle = t, weights[0] = wa, weights[1] = wb, weights[2] = wc;
    }
    const auto& tri = triangles_[static_cast<size_t>(best_triangle)];
    for (int c = 0; c < C; ++c) {
      double sum = 0;
      for (int v = 0; v < 3; ++v) sum += weights[v] * vertex_values_[static_cast<size_t>(tri[v]) * C + c];
      o[c] = sum;
    }
  });
}

}  // namespace radrecon
