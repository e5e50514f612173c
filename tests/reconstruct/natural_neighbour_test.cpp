// Sibson's coordinates: the defining properties (after CGAL's own interpolation tests) and a
// brute-force computation of the Voronoi areas that the query point steals.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/natural_neighbor_coordinates_2.h>

#include "core/error.h"
#include "reconstruct/natural_neighbour.h"
#include "reconstruct/nn_delaunay.h"
#include "support/voronoi.h"
#include "support/scattered.h"

namespace radrecon {
namespace natural_neighbour_test {

using testing::eval1;
using testing::random_samples;

using testing::area;
using testing::clip_closer;
using testing::Polygon;
using testing::voronoi_cell;

TEST(NaturalNeighbour, CoordinatesEqualStolenVoronoiAreas) {
  std::mt19937 rng(21);
  const ScatteredSamples s = random_samples(25, rng);
  const NaturalNeighbour nn(s, OutsideHull::none);
  std::uniform_real_distribution<double> inner(1.2, 2.8);
  for (int t = 0; t < 30; ++t) {
    const Vec2 q(inner(rng), inner(rng));
    const auto coords = nn.coordinates(q);
    ASSERT_FALSE(coords.empty());
    const Polygon cell_q = voronoi_cell(q, s.points);
    const double total = area(cell_q);
    std::vector<double> expected(s.points.size(), 0.0);
    for (size_t i = 0; i < s.points.size(); ++i) {
      // The part of q's cell that belonged to p_i: q's cell clipped to p_i's old cell.
      Polygon stolen = cell_q;
      for (const Vec2& o : s.points)
        if (o != s.points[i]) stolen = clip_closer(stolen, s.points[i], o);
      if (stolen.size() >= 3) expected[i] = area(stolen) / total;
    }
    std::vector<double> got(s.points.size(), 0.0);
    for (const auto& [i, w] : coords) got[i] = w;
    for (size_t i = 0; i < s.points.size(); ++i) EXPECT_NEAR(got[i], expected[i], 1e-10) << "sample " << i;
  }
}

TEST(NaturalNeighbour, SumToOneAndBarycentreIsTheQuery) {
  std::mt19937 rng(22);
  const ScatteredSamples s = random_samples(200, rng);
  const NaturalNeighbour nn(s, OutsideHull::none);
  std::uniform_real_distribution<double> inner(0.8, 3.2);
  for (int t = 0; t < 300; ++t) {
    const Vec2 q(inner(rng), inner(rng));
    const auto coords = nn.coordinates(q);
    ASSERT_FALSE(coords.empty());
    double sum = 0;
    Vec2 barycentre = Vec2::Zero();
    for (const auto& [i, w] : coords) {
      EXPECT_GE(w, 0.0);
      sum += w;
      barycentre += w * s.points[i];
    }
    EXPECT_NEAR(sum, 1.0, 1e-12);
    EXPECT_NEAR((barycentre - q).norm(), 0.0, 1e-12);
  }
}

TEST(NaturalNeighbour, ExactAtSamplesAndReproducesLinearFunctions) {
  std::mt19937 rng(23);
  ScatteredSamples s = random_samples(100, rng);
  auto f = [](const Vec2& p) { return 1.5 - 2 * p.x() + 0.75 * p.y(); };
  for (size_t i = 0; i < s.points.size(); ++i) s.values[i] = f(s.points[i]);
  const NaturalNeighbour nn(s, OutsideHull::none);
  for (size_t i = 0; i < s.points.size(); ++i) EXPECT_NEAR(eval1(nn, s.points[i]), s.values[i], 1e-12);
  std::uniform_real_distribution<double> inner(0.8, 3.2);
  for (int t = 0; t < 300; ++t) {
    const Vec2 q(inner(rng), inner(rng));
    EXPECT_NEAR(eval1(nn, q), f(q), 1e-11);
  }
}

TEST(NaturalNeighbour, SymmetricConfigurationGivesSymmetricWeights) {
  ScatteredSamples s;
  s.points = {Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1), Vec2(0.5, 2), Vec2(0.5, -1)};
  s.values = {1, 2, 3, 4, 5, 6};
  const NaturalNeighbour nn(s, OutsideHull::none);
  // On the vertical symmetry axis x = 0.5, mirrored samples get equal weights.
  const auto coords = nn.coordinates(Vec2(0.5, 0.3));
  std::vector<double> w(6, 0.0);
  for (const auto& [i, x] : coords) w[i] = x;
  EXPECT_NEAR(w[0], w[1], 1e-15);
  EXPECT_NEAR(w[2], w[3], 1e-15);
}

TEST(NaturalNeighbour, OutsideTheHull) {
  ScatteredSamples s;
  s.points = {Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1), Vec2(0.4, 0.6)};
  s.values = {0, 1, 2, 3, 7};
  const NaturalNeighbour none(s, OutsideHull::none), nearest(s, OutsideHull::nearest);
  EXPECT_TRUE(none.coordinates(Vec2(-1, 0.25)).empty());
  EXPECT_TRUE(std::isnan(eval1(none, Vec2(-1, 0.25))));
  // Nearest hull point of (-1, 0.25) is (0, 0.25) on the edge (0,0)-(0,1): 0.75 * 0 + 0.25 * 3.
  EXPECT_NEAR(eval1(nearest, Vec2(-1, 0.25)), 0.75, 1e-14);
  // Beyond a corner: the corner's value.
  EXPECT_NEAR(eval1(nearest, Vec2(2, 2)), 2.0, 1e-14);
}

TEST(NaturalNeighbour, AThinStripIsInterpolatedUpToItsHullEdges) {
  // 200 samples in a strip 1e-7 tall and 1 long: its long hull edges' triangles are flat, and
  // the coordinates change fast across the strip. A point 2e-10 inside a hull edge is no point
  // on it (within 1e-9 of the edge's length, but not of its triangle's height): its value is
  // Sibson's, against CGAL's coordinates over exact constructions (Epeck), not the linear
  // interpolation along the edge (which erred by 0.9 there).
  using Epeck = CGAL::Exact_predicates_exact_constructions_kernel;
  using ExactDt = CGAL::Delaunay_triangulation_2<Epeck>;
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> along(0, 1), across(0, 1e-7);
  ScatteredSamples s;
  for (int i = 0; i < 200; ++i) {
    s.points.emplace_back(along(rng), across(rng));
    s.values.push_back(std::sin(5 * s.points.back().x()));
  }
  const NaturalNeighbour nn(s, OutsideHull::none);
  ExactDt exact;
  std::map<std::pair<double, double>, double> value_at;
  for (size_t i = 0; i < s.points.size(); ++i) {
    exact.insert(Epeck::Point_2(s.points[i].x(), s.points[i].y()));
    value_at[{s.points[i].x(), s.points[i].y()}] = s.values[i];
  }
  // The lower hull edge under x = 0.35 and 0.6, and points 2e-10 to 2e-8 above it.
  size_t compared = 0;
  for (const double x : {0.35, 0.6}) {
    double edge_y = -1;
    for (const auto& [ia, ib] : nn.hull_edges()) {
      const Vec2 a = s.points[ia], b = s.points[ib];
      if ((a.x() - x) * (b.x() - x) >= 0 || a.x() < b.x()) continue;  // the lower chain runs to -x (clockwise)
      edge_y = a.y() + (x - a.x()) / (b.x() - a.x()) * (b.y() - a.y());
    }
    ASSERT_GE(edge_y, 0) << "no lower hull edge under x = " << x;
    for (const double above : {2e-10, 5e-10, 2e-9, 2e-8}) {
      const Vec2 q(x, edge_y + above);
      std::vector<std::pair<Epeck::Point_2, Epeck::FT>> coords;
      const auto result = CGAL::natural_neighbor_coordinates_2(exact, Epeck::Point_2(q.x(), q.y()), std::back_inserter(coords));
      ASSERT_TRUE(result.third) << "x " << x << ", " << above << " above the edge";
      double want = 0;
      for (const auto& [p, w] : coords)
        want += CGAL::to_double(w / result.second) * value_at.at({CGAL::to_double(p.x()), CGAL::to_double(p.y())});
      EXPECT_NEAR(eval1(nn, q), want, 1e-12) << "x " << x << ", " << above << " above the edge";
      ++compared;
    }
  }
  EXPECT_EQ(compared, 8u);
}

/// Every sample's coordinate at every query of a batch: the samples' values one-hot, one
/// channel per sample.
std::vector<double> batch_coordinates(const ScatteredSamples& s, const std::vector<Vec2>& queries) {
  ScatteredSamples one_hot;
  one_hot.points = s.points;
  one_hot.channels = static_cast<int>(s.points.size());
  one_hot.values.assign(s.points.size() * s.points.size(), 0.0);
  for (size_t i = 0; i < s.points.size(); ++i) one_hot.values[i * s.points.size() + i] = 1.0;
  const NaturalNeighbour nn(one_hot, OutsideHull::none);
  std::vector<double> out(queries.size() * s.points.size());
  nn.evaluate(queries, out);
  return out;
}

TEST(NaturalNeighbour, RasterBatchesReusingConflictZonesGiveCgalsCoordinates) {
  // A raster's queries, most of which reuse the conflict zone of the query before
  // (nn::ConflictZone), against CGAL's own natural_neighbor_coordinates_2 one query at a time;
  // some samples on raster nodes (queries on a vertex), some queries on Delaunay edges.
  std::mt19937 rng(24);
  ScatteredSamples s = random_samples(60, rng, 0, 1);
  for (const Vec2& node : {Vec2(0.25, 0.5), Vec2(0.5, 0.5), Vec2(0.75, 0.25)}) {
    s.points.push_back(node);
    s.values.push_back(0);
  }
  std::vector<Vec2> queries;
  const int side = 120;
  for (int j = 0; j <= side; ++j)
    for (int i = 0; i <= side; ++i) queries.emplace_back(double(i) / side, double(j) / side);
  for (int k = 0; k <= 50; ++k) queries.push_back(s.points[0] + (k / 50.0) * (s.points[60] - s.points[0]));
  const std::vector<double> got = batch_coordinates(s, queries);

  nn::Delaunay dt;
  for (size_t i = 0; i < s.points.size(); ++i) dt.insert(nn::Point(s.points[i].x(), s.points[i].y()))->info() = static_cast<unsigned>(i);
  const size_t n = s.points.size();
  size_t compared = 0;
  double worst = 0;
  for (size_t q = 0; q < queries.size(); ++q) {
    std::vector<std::pair<unsigned, double>> expected;
    const auto result = CGAL::natural_neighbor_coordinates_2(dt, nn::Point(queries[q].x(), queries[q].y()),
                                                             std::back_inserter(expected), nn::VertexIndex());
    if (!result.third) {  // outside the hull: no value
      EXPECT_TRUE(std::isnan(got[q * n])) << "query " << q;
      continue;
    }
    std::vector<double> want(n, 0.0);
    for (const auto& [i, w] : expected) want[i] += w / result.second;
    double sum = 0;
    for (size_t i = 0; i < n; ++i) sum += got[q * n + i];
    ASSERT_NEAR(sum, 1.0, 1e-12) << "query " << q;
    for (size_t i = 0; i < n; ++i) {
      worst = std::max(worst, std::abs(got[q * n + i] - want[i]));
      ASSERT_NEAR(got[q * n + i], want[i], 1e-12) << "query " << q << " (" << queries[q].transpose() << "), sample " << i;
    }
    ++compared;
  }
  EXPECT_GT(compared, queries.size() / 2);
  std::printf("natural neighbour: %zu queries within %.2g of CGAL's coordinates\n", compared, worst);
}

TEST(ConflictZone, AwayFromTheHullItIsBuiltHoldsForItsQueryAndGivesCgalsAreas) {
  // Guards the reuse itself: a zone that silently failed to build or to hold would still give
  // right values (through CGAL), only slowly.
  std::mt19937 rng(26);
  const ScatteredSamples s = random_samples(200, rng, 0, 1);
  nn::Delaunay dt;
  for (size_t i = 0; i < s.points.size(); ++i) dt.insert(nn::Point(s.points[i].x(), s.points[i].y()))->info() = static_cast<unsigned>(i);
  std::vector<bool> on_hull(s.points.size(), false);
  auto circulator = dt.incident_vertices(dt.infinite_vertex()), done = circulator;
  do on_hull[circulator->info()] = true;
  while (++circulator != done);
  std::uniform_real_distribution<double> inner(0.3, 0.7);
  int reusable = 0;
  for (int t = 0; t < 100; ++t) {
    const Vec2 q(inner(rng), inner(rng));
    const nn::Point p(q.x(), q.y());
    std::vector<nn::Delaunay::Face_handle> conflicts;
    std::vector<nn::Delaunay::Edge> hole;
    dt.get_conflicts_and_boundary(p, std::back_inserter(conflicts), std::back_inserter(hole), dt.locate(p));
    nn::ConflictZone zone;
    ASSERT_TRUE(zone.build(dt, conflicts, hole, [&](unsigned i) { return bool(on_hull[i]); })) << "query " << t;
    if (zone.reusable()) {
      ++reusable;
      EXPECT_TRUE(zone.holds(q)) << "query " << t;
    }
    std::vector<std::pair<unsigned, double>> ours, cgal;
    const double sum = zone.sibson(q, ours);  // areas in the zone's own (scaled) units
    const auto result = CGAL::natural_neighbor_coordinates_2(dt, p, std::back_inserter(cgal), nn::VertexIndex());
    ASSERT_TRUE(result.third);
    ASSERT_GT(sum, 0);
    std::sort(ours.begin(), ours.end());
    std::sort(cgal.begin(), cgal.end());
    ASSERT_EQ(ours.size(), cgal.size());
    for (size_t k = 0; k < ours.size(); ++k) {
      EXPECT_EQ(ours[k].first, cgal[k].first);
      EXPECT_NEAR(ours[k].second / sum, cgal[k].second / result.second, 1e-13);
    }
  }
  EXPECT_GE(reusable, 95);
}

TEST(NaturalNeighbour, CoordinatesDoNotDependOnTheScale) {
  // Scaling samples and queries by a power of two (exact) leaves every coordinate unchanged, bit
  // for bit, at 2^-300 (about 5e-91, inside the samples' accepted extent) and 2^300 as at 1:
  // the conflict zones' tests and areas are computed in coordinates scaled to the zone.
  std::mt19937 rng(27);
  const ScatteredSamples base = random_samples(40, rng, 0, 1);
  std::vector<Vec2> queries;
  for (int j = 0; j < 60; ++j)
    for (int i = 0; i < 60; ++i) queries.emplace_back((i + 0.5) / 60, (j + 0.5) / 60);
  const std::vector<double> reference = batch_coordinates(base, queries);
  for (const int power : {-300, 300}) {
    ScatteredSamples scaled = base;
    for (Vec2& p : scaled.points) p *= std::ldexp(1.0, power);
    std::vector<Vec2> scaled_queries = queries;
    for (Vec2& q : scaled_queries) q *= std::ldexp(1.0, power);
    const std::vector<double> got = batch_coordinates(scaled, scaled_queries);
    for (size_t k = 0; k < got.size(); ++k) {
      if (std::isnan(reference[k])) {
        ASSERT_TRUE(std::isnan(got[k])) << "2^" << power << ", value " << k;
      } else {
        ASSERT_EQ(got[k], reference[k]) << "2^" << power << ", value " << k;
      }
    }
  }
}

TEST(NaturalNeighbour, ABatchGivesWhatEachPointGivesAlone) {
  // Bit for bit: a reused conflict zone computes what the zone built for the point alone does.
  std::mt19937 rng(25);
  const ScatteredSamples s = random_samples(200, rng, 0, 1);
  const NaturalNeighbour nn(s, OutsideHull::none);
  std::vector<Vec2> queries;
  for (int j = 0; j < 150; ++j)
    for (int i = 0; i < 150; ++i) queries.emplace_back((i + 0.5) / 150, (j + 0.5) / 150);
  // Points on Delaunay edges: the midpoints of every sample's nearest-neighbour segment.
  for (size_t i = 0; i < s.points.size(); ++i) {
    size_t nearest = i == 0 ? 1 : 0;
    for (size_t j = 0; j < s.points.size(); ++j)
      if (j != i && (s.points[j] - s.points[i]).squaredNorm() < (s.points[nearest] - s.points[i]).squaredNorm()) nearest = j;
    queries.push_back(0.5 * (s.points[i] + s.points[nearest]));
  }
  std::vector<double> batch(queries.size());
  nn.evaluate(queries, batch);
  for (size_t q = 0; q < queries.size(); q += q < 150 * 150 ? 7 : 1) {  // every 7th node, every midpoint
    double alone = 0;
    nn.evaluate(std::span<const Vec2>(&queries[q], 1), std::span<double>(&alone, 1));
    if (std::isnan(alone)) {
      EXPECT_TRUE(std::isnan(batch[q]));
    } else {
      ASSERT_EQ(batch[q], alone) << "query " << q;
    }
  }
}

TEST(NaturalNeighbour, VisitedCoordinatesAreEachPointsCoordinates) {
  // visit_coordinates() (a raster's queries sharing walks and conflict zones, on both threads)
  // against coordinates() one point at a time, without and with barriers: the same samples, the
  // same nonzero coordinates to round-off, none outside the hull; without barriers against
  // CGAL's natural_neighbor_coordinates_2 as well.
  std::mt19937 rng(26);
  const ScatteredSamples s = random_samples(150, rng, 0, 1);
  std::vector<Vec2> queries;
  for (int j = 0; j <= 90; ++j)
    for (int i = 0; i <= 90; ++i) queries.emplace_back(-0.05 + 1.1 * i / 90, -0.05 + 1.1 * j / 90);
  const std::vector<Polyline> walls = {{{0.3, 0.2}, {0.3, 0.8}}, {{0.5, 0.5}, {0.9, 0.5}}};
  nn::Delaunay dt;
  for (size_t i = 0; i < s.points.size(); ++i) dt.insert(nn::Point(s.points[i].x(), s.points[i].y()))->info() = static_cast<unsigned>(i);
  for (const bool walled : {false, true}) {
    const NaturalNeighbour nn(s, OutsideHull::none, walled ? Barriers::from_polylines(walls).value() : Barriers{});
    std::vector<std::vector<std::pair<unsigned, double>>> visited(queries.size());
    std::vector<int> visits(queries.size(), 0);
    nn.visit_coordinates(queries, [&](size_t q, std::span<const std::pair<unsigned, double>> c) {
      visited[q].assign(c.begin(), c.end());
      ++visits[q];
    });
    size_t inside = 0;
    for (size_t q = 0; q < queries.size(); ++q) {
      ASSERT_EQ(visits[q], 1) << "query " << q;
      auto sorted = [](std::vector<std::pair<unsigned, double>> c) {
        std::sort(c.begin(), c.end());
        return c;
      };
      const auto alone = sorted(nn.coordinates(queries[q])), got = sorted(visited[q]);
      ASSERT_EQ(got.size(), alone.size()) << "query " << q << (walled ? ", walled" : "");
      for (size_t k = 0; k < got.size(); ++k) {
        ASSERT_EQ(got[k].first, alone[k].first) << "query " << q;
        ASSERT_NEAR(got[k].second, alone[k].second, 1e-12) << "query " << q;
      }
      inside += !got.empty();
      if (walled) continue;
      // Without barriers, an independent answer too: CGAL's coordinates.
      std::vector<std::pair<unsigned, double>> expected;
      const auto result = CGAL::natural_neighbor_coordinates_2(dt, nn::Point(queries[q].x(), queries[q].y()),
                                                               std::back_inserter(expected), nn::VertexIndex());
      if (!result.third) {
        EXPECT_TRUE(got.empty()) << "query " << q << " is outside the hull";
        continue;
      }
      std::vector<double> want(s.points.size(), 0.0), have(s.points.size(), 0.0);
      for (const auto& [i, w] : expected) want[i] += w / result.second;
      for (const auto& [i, w] : got) have[i] += w;
      for (size_t i = 0; i < want.size(); ++i) ASSERT_NEAR(have[i], want[i], 1e-12) << "query " << q << ", sample " << i;
    }
    EXPECT_GT(inside, queries.size() / 2);
    EXPECT_LT(inside, queries.size());  // the raster reaches past the hull
  }
}

TEST(NaturalNeighbour, RefusesTooFewCollinearOrDuplicateSamples) {
  ScatteredSamples two;
  two.points = {Vec2(0, 0), Vec2(1, 1)};
  two.values = {1, 2};
  EXPECT_THROW(NaturalNeighbour(two, OutsideHull::none), ReconstructionError);
  ScatteredSamples line;
  line.points = {Vec2(0, 0), Vec2(1, 1), Vec2(2, 2), Vec2(3, 3)};
  line.values = {1, 2, 3, 4};
  EXPECT_THROW(NaturalNeighbour(line, OutsideHull::none), ReconstructionError);
  ScatteredSamples dup;
  dup.points = {Vec2(0, 0), Vec2(1, 0), Vec2(0, 1), Vec2(1, 0)};
  dup.values = {1, 2, 3, 4};
  EXPECT_THROW(NaturalNeighbour(dup, OutsideHull::none), ReconstructionError);
}

}  // namespace natural_neighbour_test
}  // namespace radrecon
