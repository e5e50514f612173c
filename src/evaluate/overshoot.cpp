// Overshoot (metrics.h): the range of a query's natural neighbours, or outside the hull of its
// nearest hull edge and nearest samples.

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "core/check.h"
#include "core/parallel.h"
#include "evaluate/metrics.h"
#include "reconstruct/interpolant.h"
#include "reconstruct/kdtree.h"
#include "reconstruct/natural_neighbour.h"

namespace radrecon {

namespace {

/// Samples nearest to a query outside the hull whose range counts beside its hull edge's.
constexpr int kOutsideNearest = 3;

/// The hull edge nearest to q (the first of equally near ones, in the order of `edges`).
std::pair<unsigned, unsigned> nearest_edge(const Vec2& q, const std::vector<Vec2>& points,
                                           const std::vector<std::pair<unsigned, unsigned>>& edges) {
  double best = std::numeric_limits<double>::infinity();
  std::pair<unsigned, unsigned> best_edge = edges.front();
  for (const auto& e : edges) {
    const Vec2 a = points[e.first], ab = points[e.second] - a;
    const double t = nearest_on_segment_t(q, a, points[e.second]);
    const double d = (a + t * ab - q).squaredNorm();
    if (d < best) best = d, best_edge = e;
  }
  return best_edge;
}

struct Scratch {
  std::vector<unsigned> neighbours;
  std::vector<unsigned> indices = std::vector<unsigned>(kOutsideNearest);
  std::vector<double> dist_sq = std::vector<double>(kOutsideNearest);
  VisibleNeighbours visible;
};

}  // namespace

std::optional<NeighbourRanges> neighbour_ranges(const ScatteredSamples& samples, std::span<const Vec2> points,
                                                const Barriers& barriers) {
  const int C = samples.channels;
  RR_CHECK_EQ(samples.values.size(), samples.points.size() * C, "overshoot: samples and values do not match");
  std::optional<NaturalNeighbour> nn;
  try {
    nn.emplace(samples, OutsideHull::none, barriers);
  } catch (const ReconstructionError&) {
    return std::nullopt;  // no natural neighbours: fewer than 3 samples, on one line, repeated
  }
  const std::vector<std::pair<unsigned, unsigned>>& edges = nn->hull_edges();
  const KdTree2 tree(samples.points);
  const int nearest = static_cast<int>(std::min<size_t>(kOutsideNearest, samples.points.size()));
  NeighbourRanges ranges;
  ranges.channels = C;
  ranges.lo.resize(points.size() * C);
  ranges.hi.resize(points.size() * C);
  auto set_range = [&](size_t p, const std::vector<unsigned>& neighbours) {
    for (int c = 0; c < C; ++c) {
      double lo = std::numeric_limits<double>::infinity(), hi = -lo;
      for (const unsigned k : neighbours) {
        lo = std::min(lo, samples.values[static_cast<size_t>(k) * C + c]);
        hi = std::max(hi, samples.values[static_cast<size_t>(k) * C + c]);
      }
      ranges.lo[p * C + c] = lo;
      ranges.hi[p * C + c] = hi;
    }
  };
  // Inside the hull, the natural neighbours (all queries at once, as the interpolant finds them);
  // the queries outside it afterwards.
  std::vector<char> outside(points.size(), 0);
  nn->visit_coordinates(points, [&](size_t p, std::span<const std::pair<unsigned, double>> coordinates) {
    thread_local std::vector<unsigned> neighbours;  // the visitor's buffers, one per thread
    thread_local VisibleNeighbours nearest_seen;
    neighbours.clear();
    for (const auto& [index, lambda] : coordinates)
      if (lambda != 0) neighbours.push_back(index);
    if (neighbours.empty()) {
      outside[p] = 1;
      return;
    }
    // With barriers, also the nearest sample q sees: on the hull of what it sees (a row of
    // samples beside a wall's foot, and one around the wall's end), q's natural neighbours are
    // that hull edge's two ends, which may leave out the sample next to it (a piecewise-constant
    // reconstruction, the nearest visible sample's value, scored an overshoot of 0.054).
    if (!barriers.empty() && nearest_visible(tree, samples.points, barriers, points[p], 1, nearest_seen) == 1)
      neighbours.push_back(nearest_seen.idx[0]);
    set_range(p, neighbours);
  });
  parallel_for_with_scratch<Scratch>(0, static_cast<std::int64_t>(points.size()), [&](std::int64_t p, Scratch& s) {
    if (!outside[static_cast<size_t>(p)]) return;
    const Vec2& q = points[p];
    s.neighbours.clear();
    // The hull edge's ends and the nearest samples that q sees: a sample behind a barrier is no
    // neighbour (the nearest ones overall, across a wall's foot from a point outside the hull of
    // what it sees, gave piecewise constant an overshoot of half the white point).
    const auto [e0, e1] = nearest_edge(q, samples.points, edges);
    for (const unsigned e : {e0, e1})
      if (barriers.empty() || !barriers.blocks(q, samples.points[e])) s.neighbours.push_back(e);
    if (barriers.empty()) {
      const size_t found = tree.nearest(q, nearest, s.indices, s.dist_sq);
      s.neighbours.insert(s.neighbours.end(), s.indices.begin(), s.indices.begin() + static_cast<std::ptrdiff_t>(found));
    } else {
      const size_t found = nearest_visible(tree, samples.points, barriers, q, static_cast<size_t>(nearest), s.visible);
      s.neighbours.insert(s.neighbours.end(), s.visible.idx.begin(), s.visible.idx.begin() + static_cast<std::ptrdiff_t>(found));
    }
    if (s.neighbours.empty()) {  // q sees no sample: no range (a method's NaN there is no overshoot)
      for (int c = 0; c < C; ++c) {
        ranges.lo[static_cast<size_t>(p) * C + c] = -std::numeric_limits<double>::infinity();
        ranges.hi[static_cast<size_t>(p) * C + c] = std::numeric_limits<double>::infinity();
      }
      return;
    }
    set_range(static_cast<size_t>(p), s.neighbours);
  });
  return ranges;
}

double overshoot(const NeighbourRanges& ranges, std::span<const double> approx) {
  RR_CHECK_EQ(approx.size(), ranges.lo.size(), "overshoot: points and values do not match");
  double result = 0;
  for (size_t k = 0; k < approx.size(); ++k) {
    const double v = approx[k];
    if (std::isnan(v)) {
      // A point that sees no sample has no range and, rightly, no value: it leaves nothing.
      if (ranges.lo[k] == -std::numeric_limits<double>::infinity() && ranges.hi[k] == std::numeric_limits<double>::infinity())
        continue;
      return std::numeric_limits<double>::quiet_NaN();
    }
    result = std::max({result, v - ranges.hi[k], ranges.lo[k] - v});
  }
  return result;
}

std::optional<double> overshoot(const ScatteredSamples& samples, std::span<const Vec2> points,
                                std::span<const double> approx) {
  RR_CHECK_EQ(approx.size(), points.size() * samples.channels, "overshoot: points and values do not match");
  const std::optional<NeighbourRanges> ranges = neighbour_ranges(samples, points);
  if (!ranges) return std::nullopt;
  return overshoot(*ranges, approx);
}

}  // namespace radrecon
