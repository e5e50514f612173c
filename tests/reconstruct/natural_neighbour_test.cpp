// Sibson's coordinates: the defining properties (after CGAL's own interpolation tests) and a
// brute-force computation of the Voronoi areas that the query point steals.

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/error.h"
#include "reconstruct/natural_neighbour.h"
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
