#include "reconstruct/sibson_c1.h"

#include <CGAL/natural_neighbor_coordinates_2.h>

#include <cmath>
#include <span>
#include <vector>

#include "core/parallel.h"
#include "core/tolerances.h"

namespace radrecon::nn {

std::vector<double> fit_gradients(const Delaunay& dt, std::span<const Delaunay::Vertex_handle> vertex_of,
                                  std::span<const Vec2> points, std::span<const double> values, int channels,
                                  const Barriers& barriers) {
  const size_t n = points.size();
  const size_t C = static_cast<size_t>(channels);
  std::vector<double> gradients(n * C * 2, 0.0);
  struct Scratch {
    std::vector<std::pair<unsigned, double>> weights;
    std::vector<std::pair<Point, unsigned>> offsets;
  };
  parallel_for_with_scratch<Scratch>(0, static_cast<std::int64_t>(n), [&](std::int64_t k, Scratch& scratch) {
    const size_t i = static_cast<size_t>(k);
    const Delaunay::Vertex_handle v = vertex_of[i];
    std::vector<std::pair<unsigned, double>>& weights = scratch.weights;
    weights.clear();
    // Everything below is in offsets from p_i divided by `scale`, the power of two at or above
    // the farthest neighbour's distance (exact): the normal matrix H grows like the fourth power
    // of the offsets, and Sibson's areas are products of four coordinates, so in the samples'
    // own units they overflowed or underflowed beyond 1e+-77 (the gradients then came from the
    // fallback below, results off by 3% of the data's range at 1e+-80).
    double farthest = 0;
    {
      auto vc = dt.incident_vertices(v), done = vc;
      do
        if (!dt.is_infinite(vc)) farthest = std::max(farthest, (points[vc->info()] - points[i]).norm());
      while (++vc != done);
    }
    if (!(farthest > 0) || !std::isfinite(farthest)) return;
    const double scale = std::ldexp(1.0, std::ilogb(farthest) + 1);
    const bool on_hull = dt.is_edge(v, dt.infinite_vertex());
    scratch.offsets.clear();
    {
      auto vc = dt.incident_vertices(v), done = vc;
      do
        if (!dt.is_infinite(vc)) {
          const Vec2 d = (points[vc->info()] - points[i]) / scale;
          scratch.offsets.emplace_back(Point(d.x(), d.y()), vc->info());
          if (on_hull) weights.emplace_back(vc->info(), 1.0);
        }
      while (++vc != done);
    }
    if (!on_hull) {
      // Sibson's coordinates of p_i among its neighbours: the areas its Voronoi cell takes from
      // theirs in the triangulation of the neighbours alone (what CGAL's
      // natural_neighbor_coordinates_2 for a vertex computes, here in the scaled offsets, where
      // p_i is the origin). Should rounding put the origin outside that triangulation's hull, the
      // neighbours count by distance alone, as on the hull.
      const Delaunay local(scratch.offsets.begin(), scratch.offsets.end());
      const bool found = local.dimension() == 2 &&
                         CGAL::natural_neighbor_coordinates_2(local, Point(0, 0), std::back_inserter(weights), VertexIndex()).third;
      if (!found || weights.empty()) {
        weights.clear();
        for (const auto& [point, j] : scratch.offsets) weights.emplace_back(j, 1.0);
      }
    }
    double h00 = 0, h01 = 0, h11 = 0;
    thread_local std::vector<double> r;
    // The normal equations H g = r of the weighted plane, per channel, in the scaled offsets
    // (the gradient divided back by the scale), with each neighbour weighted by its coordinate
    // lambda_j / d_j^2, or (`by_distance`) by 1 / d_j^2 alone.
    const auto normal_equations = [&](bool by_distance) {
      h00 = h01 = h11 = 0;
      r.assign(C * 2, 0.0);
      for (const auto& [j, lambda] : weights) {
        if (barriers.blocks(points[i], points[j])) continue;
        const Vec2 d = (points[j] - points[i]) / scale;
        const double w = (by_distance ? 1.0 : lambda) / d.squaredNorm();
        h00 += w * d.x() * d.x(), h01 += w * d.x() * d.y(), h11 += w * d.y() * d.y();
        for (size_t c = 0; c < C; ++c) {
          const double df = values[j * C + c] - values[i * C + c];
          r[2 * c] += w * df * d.x(), r[2 * c + 1] += w * df * d.y();
        }
      }
    };
    // The fitted plane's gradient (per channel, into g) with the weights of `by_distance`, or
    // false with no visible neighbour. Neighbours (nearly) on one line through p_i
    // (tol::kGradientFitSingularRelative): the plane is fitted along that line alone, H's larger
    // eigenvector e (eigenvalue lambda), g = (e . r / lambda) e, and nothing across it; a linear
    // function's gradient along the line is exact, and across it its component errs by at most
    // the spread's thickness times that component. `conditioning` gets det H / trace(H)^2.
    const auto fit = [&](bool by_distance, std::span<double> g, double& conditioning) {
      normal_equations(by_distance);
      const double det = h00 * h11 - h01 * h01, trace = h00 + h11;
      if (!(trace > 0)) return false;
      conditioning = det / (trace * trace);
      if (!(det > tol::kGradientFitSingularRelative * trace * trace)) {
        const double lambda = trace / 2 + std::sqrt(std::max(trace * trace / 4 - det, 0.0));
        const Vec2 a(h01, lambda - h00), b(lambda - h11, h01);  // each along e, or zero
        const Vec2 e = (a.squaredNorm() >= b.squaredNorm() ? a : b).normalized();
        if (!(e.squaredNorm() > 0)) return false;  // both candidates zero: not reached (H has a trace here)
        for (size_t c = 0; c < C; ++c) {
          const double along = (e.x() * r[2 * c] + e.y() * r[2 * c + 1]) / lambda / scale;
          g[2 * c] = along * e.x(), g[2 * c + 1] = along * e.y();
        }
        return true;
      }
      for (size_t c = 0; c < C; ++c) {
        g[2 * c] = (h11 * r[2 * c] - h01 * r[2 * c + 1]) / det / scale;
        g[2 * c + 1] = (h00 * r[2 * c + 1] - h01 * r[2 * c]) / det / scale;
      }
      return true;
    };
    const std::span<double> out(gradients.data() + i * C * 2, C * 2);
    double conditioning = 0;
    if (!fit(false, out, conditioning)) return;  // no visible neighbour: gradient 0
    // Ill-conditioned by the coordinates: the slope in one direction rests on neighbours of
    // tiny weight, and the data's curvature, which the heavy ones' differences carry, is
    // amplified by the condition number. A sample a few centimetres inside a hull edge
    // kilometres long gives the edge's far ends nearly all its coordinates: a slope across the
    // edge of 0.77 /m on data of slope 0.002 /m, values of -3.5 on data in [-1, 1] (found by an
    // outside-in trial; CGAL's fit gives the same). Below tol::kGradientFitConditionRelative the
    // neighbours count by their distance alone (a plane through the same neighbours, so linear
    // functions are still reproduced); up to tol::kGradientFitBlendRelative times that, the two
    // fits are blended by the conditioning's logarithm, so that no sample's gradient jumps when
    // its conditioning crosses a threshold (under a change of units, whose rounding moves it).
    // Near-singular, a neighbour off the line may hold a coordinate of 1e-16 (a sample a
    // rounding error inside the hull beside two on its edge, their three points collinear to
    // 3e-17), which the distance fit must not lose, or a linear function's gradient across the
    // line is lost (errors of 0.2 on survey tracks).
    const double lo = tol::kGradientFitConditionRelative, hi = lo * tol::kGradientFitBlendRelative;
    if (!(conditioning < hi)) return;
    thread_local std::vector<double> by_distance;
    by_distance.assign(C * 2, 0.0);
    double unused = 0;
    fit(true, by_distance, unused);  // the same visible neighbours: it has a trace too
    // The Sibson fit's share: 0 at or below lo, 1 at hi, smooth in log(conditioning) between.
    const double t = conditioning > lo ? std::log(conditioning / lo) / std::log(hi / lo) : 0.0;
    const double share = t * t * (3 - 2 * t);
    for (size_t k = 0; k < C * 2; ++k) out[k] = share * out[k] + (1 - share) * by_distance[k];
  });
  return gradients;
}

void farin_c1(std::span<const std::pair<unsigned, double>> coords, std::span<const Vec2> points,
              std::span<const double> values, std::span<const double> gradients, int channels, double* out) {
  // Farin's cubic in the coordinates l: sum_i f_i l_i^3 + 3 sum_{i != j} b_iij l_i^2 l_j
  // + 6 sum_{i < j < k} b_ijk l_i l_j l_k, with b_iij = f_i + g_i . (p_j - p_i) / 3 and b_ijk a
  // quarter of the sum of the six b_pq of the triple less a sixth of f_i + f_j + f_k. Summed over the triples
  // by their pairs and singles, in O(m^2): each ordered pair (p, q) lies in the triples {p, q, r},
  // r any other, whose l_r sum to S - l_p - l_q (S = sum l); each single p in the pairs {q, r} of
  // the others, whose l_q l_r sum to ((S - l_p)^2 - (Q - l_p^2)) / 2 (Q = sum l^2). The triple
  // loop was O(m^3): 26 s for 2000 samples on a circle, all of them natural neighbours.
  const size_t m = coords.size(), C = static_cast<size_t>(channels);
  double S = 0, Q = 0;
  for (const auto& [k, l] : coords) S += l, Q += l * l;
  for (size_t c = 0; c < C; ++c) {
    auto f = [&](size_t i) { return values[coords[i].first * C + c]; };
    double sum = 0;
    for (size_t i = 0; i < m; ++i) {
      const double li = coords[i].second, fi = f(i);
      const size_t gi = (coords[i].first * C + c) * 2;
      const Vec2& pi = points[coords[i].first];
      sum += fi * li * li * li - fi * li * ((S - li) * (S - li) - (Q - li * li)) / 2;
      for (size_t j = 0; j < m; ++j)
        if (j != i) {
          const double lj = coords[j].second;
          const Vec2 d = points[coords[j].first] - pi;
          const double bij = fi + (gradients[gi] * d.x() + gradients[gi + 1] * d.y()) / 3;
          sum += bij * li * lj * (3 * li + 1.5 * (S - li - lj));
        }
    }
    out[c] = sum;
  }
}

}  // namespace radrecon::nn
