#include "solver/link_form_factor.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <span>

#include "core/parallel.h"
#include "solver/visibility.h"

namespace radrecon {

LinkFormFactor measure_link(const LinkEnd& receiver, const LinkEnd& source, const OccluderBvh& bvh,
                            bool may_be_occluded) {
  const QuadNode& r = receiver.node;
  const QuadNode& s = source.node;
  // The occluders in the shaft between the two nodes (solver/bvh.h).
  std::vector<const Occluder*> occluders;
  if (may_be_occluded)
    bvh.collect(Shaft(std::span<const Vec3>(r.corners.data(), static_cast<size_t>(r.vertex_count())),
                      std::span<const Vec3>(s.corners.data(), static_cast<size_t>(s.vertex_count()))),
                receiver.scene_surface, source.scene_surface, occluders);
  ConvexPolygon polygon;
  for (int k = 0; k < s.vertex_count(); ++k) polygon.push(s.corners[k]);
  double lo = std::numeric_limits<double>::infinity(), hi = 0;
  // The point form factors at (u, v) parameters of the receiver, four at a time
  // (visible_form_factors()).
  const auto point_form_factors = [&](std::span<const Vec2> uv, std::span<double> f) {
    std::array<Vec3, kLinkQuadratureFine * kLinkQuadratureFine> points;
    for (size_t k = 0; k < uv.size(); ++k) points[k] = receiver.surface->point(uv[k].x(), uv[k].y());
    visible_form_factors({points.data(), uv.size()}, receiver.normal, polygon, source.normal, occluders, f);
    for (const double v : f) {
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  };
  constexpr int kCells = kLinkQuadrature * kLinkQuadrature;
  static_assert(kLinkQuadratureFine >= kLinkQuadrature, "the points buffer holds the finer rule's");
  std::array<double, kCells> cell_f;
  std::array<Vec2, kCells> midpoint;  // the cells' centroids (ParamCell::for_each_subcell())
  int k = 0;
  r.for_each_midpoint(kLinkQuadrature, [&](const Vec2& uv) { midpoint[static_cast<size_t>(k++)] = uv; });
  point_form_factors(midpoint, cell_f);
  double sum = 0;
  for (const double f : cell_f) sum += f;
  LinkFormFactor link{sum / kCells, hi - lo};
  // A discontinuity makes the coarse rule's error of order 1 / kLinkQuadrature of the jump:
  // refine the cells beside it, those whose value differs from a neighbour's by a share of the
  // spread (neighbours: cells whose centroids are at most one cell apart in u and in v).
  if (!(link.f_spread > kDiscontinuousSpread * (link.f + link.f_spread))) return link;
  const double du = (r.u1 - r.u0) / kLinkQuadrature, dv = (r.v1 - r.v0) / kLinkQuadrature;
  constexpr double kNeighbour = 1.01;  // one cell apart, with room for rounding
  std::array<bool, kCells> beside_jump{};
  for (int a = 0; a < kCells; ++a)
    for (int b = a + 1; b < kCells; ++b) {
      const Vec2 d = midpoint[static_cast<size_t>(a)] - midpoint[static_cast<size_t>(b)];
      if (std::abs(d.x()) > kNeighbour * du || std::abs(d.y()) > kNeighbour * dv) continue;
      if (std::abs(cell_f[static_cast<size_t>(a)] - cell_f[static_cast<size_t>(b)]) > kJumpShare * link.f_spread)
        beside_jump[static_cast<size_t>(a)] = beside_jump[static_cast<size_t>(b)] = true;
    }
  std::array<ParamCell, kCells> cells;
  k = 0;
  r.for_each_subcell(kLinkQuadrature, [&](const ParamCell& c) { cells[static_cast<size_t>(k++)] = c; });
  sum = 0;
  for (int a = 0; a < kCells; ++a) {
    if (!beside_jump[static_cast<size_t>(a)]) {
      sum += cell_f[static_cast<size_t>(a)];
      continue;
    }
    constexpr int kFine = kLinkQuadratureFine * kLinkQuadratureFine;
    std::array<Vec2, kFine> uv;
    std::array<double, kFine> f;
    int m = 0;
    cells[static_cast<size_t>(a)].for_each_midpoint(kLinkQuadratureFine, [&](const Vec2& p) { uv[static_cast<size_t>(m++)] = p; });
    point_form_factors(uv, f);
    double fine = 0;
    for (const double v : f) fine += v;
    sum += fine / kFine;
  }
  return {sum / kCells, hi - lo};
}

std::vector<const LinkFormFactor*> measure_into_cache(LinkFormFactorCache& cache, const std::vector<LinkRequest>& requests,
                                                      Progress* progress,
                                                      const std::function<LinkFormFactor(const LinkRequest&)>& measure) {
  std::vector<const LinkFormFactor*> out(requests.size());
  std::vector<size_t> missing;
  for (size_t k = 0; k < requests.size(); ++k) {
    const LinkRequest& q = requests[k];
    out[k] = cache.find({q.receiver_tree, *q.receiver}, {q.source_tree, *q.source});
    if (out[k] == nullptr) missing.push_back(k);
  }
  std::vector<LinkFormFactor> measured(missing.size());
  // In batches, between which the solve's progress hears the share measured (the final
  // gather's millions of links took 10 s without a word).
  const auto total = static_cast<std::int64_t>(missing.size());
  const auto stage_start = std::chrono::steady_clock::now();
  for (std::int64_t first = 0; first < total; first += kMeasureBatch) {
    parallel_for_coarse(first, std::min(total, first + kMeasureBatch), [&](std::int64_t k) {
      measured[static_cast<size_t>(k)] = measure(requests[missing[static_cast<size_t>(k)]]);
    });
    if (progress != nullptr)
      progress->update(static_cast<double>(std::min(total, first + kMeasureBatch)) / static_cast<double>(total),
                       "the " + std::to_string(total) + " new links' form factors measured", stage_start);
  }
  for (size_t k = 0; k < missing.size(); ++k) {
    const LinkRequest& q = requests[missing[k]];
    // A request made twice is measured twice and kept once: the first, as the cache keeps it.
    out[missing[k]] = cache.insert({q.receiver_tree, *q.receiver}, {q.source_tree, *q.source}, measured[k]);
  }
  return out;
}

}  // namespace radrecon
