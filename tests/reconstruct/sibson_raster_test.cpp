// Sibson's interpolation over a raster, face by face (reconstruct/sibson_raster.h), against
// CGAL's natural_neighbor_coordinates_2 one query at a time (an independent computation of the
// same coordinates), and its defining properties: linear functions reproduced, values at the
// samples, and values that depend neither on the threads nor on how the raster is cut.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include <CGAL/natural_neighbor_coordinates_2.h>

#include "core/thread_pool.h"
#include "reconstruct/natural_neighbour.h"
#include "reconstruct/nn_delaunay.h"
#include "reconstruct/sibson_raster.h"
#include "support/scattered.h"

namespace radrecon {
namespace sibson_raster_test {

using testing::random_samples;

/// The samples' triangulation, as NaturalNeighbour makes it, and their hull's edges.
struct Triangulated {
  nn::Delaunay dt;
  std::vector<std::pair<unsigned, unsigned>> hull;
  explicit Triangulated(const ScatteredSamples& s) : hull(NaturalNeighbour(s, OutsideHull::none).hull_edges()) {
    std::vector<std::pair<nn::Point, unsigned>> input;
    for (size_t i = 0; i < s.points.size(); ++i) input.emplace_back(nn::Point(s.points[i].x(), s.points[i].y()), static_cast<unsigned>(i));
    dt.insert(input.begin(), input.end());
  }
};

/// One value column per sample, 1 at it and 0 elsewhere: the interpolant's values are the
/// coordinates themselves.
std::vector<double> one_hot(size_t n) {
  std::vector<double> v(n * n, 0.0);
  for (size_t i = 0; i < n; ++i) v[i * n + i] = 1;
  return v;
}

TEST(SibsonRaster, GivesCgalsCoordinatesWhereItServesAndServesMostOfTheHull) {
  // 60 random samples, three of them on raster points (queries on a vertex), a raster reaching
  // beyond their hull: each served point's coordinates against CGAL's.
  std::mt19937 rng(31);
  ScatteredSamples s = random_samples(60, rng, 0, 1);
  const Raster raster{97, 83, Rect{-0.05, -0.02, 1.03, 1.01}};
  for (const auto& [i, j] : {std::pair<size_t, size_t>{40, 41}, {20, 60}, {71, 12}}) s.points.push_back(raster.point(i, j));
  const size_t n = s.points.size();
  const Triangulated t(s);
  const std::vector<double> values = one_hot(n);
  const SibsonRaster sibson(t.dt, s.points, values, static_cast<int>(n), t.hull);
  const size_t count = static_cast<size_t>(raster.width) * raster.height;
  std::vector<double> got(count * n, -1.0);
  std::vector<size_t> unserved;
  sibson.evaluate(raster, 0, count, got, unserved);

  std::vector<char> served(count, 1);
  for (const size_t k : unserved) served[k] = 0;
  size_t inside = 0, compared = 0;
  double worst = 0;
  for (size_t k = 0; k < count; ++k) {
    const Vec2 q = raster.point(k % raster.width, k / raster.width);
    std::vector<std::pair<unsigned, double>> expected;
    const auto result = CGAL::natural_neighbor_coordinates_2(t.dt, nn::Point(q.x(), q.y()), std::back_inserter(expected),
                                                             nn::VertexIndex());
    if (!result.third) {
      EXPECT_FALSE(served[k]) << "a point outside the hull was served: " << q.transpose();
      continue;
    }
    ++inside;
    if (!served[k]) continue;
    std::vector<double> want(n, 0.0);
    for (const auto& [i, w] : expected) want[i] += w / result.second;
    for (size_t i = 0; i < n; ++i) {
      worst = std::max(worst, std::abs(got[k * n + i] - want[i]));
      ASSERT_NEAR(got[k * n + i], want[i], 1e-12) << "point " << q.transpose() << ", sample " << i;
    }
    ++compared;
  }
  // The three points on samples are left (the sums vanish there), and few others.
  EXPECT_GE(compared, inside - inside / 50) << "of " << inside << " points inside the hull";
  std::printf("sibson raster: %zu of %zu points inside the hull served, within %.2g of CGAL's coordinates\n", compared,
              inside, worst);
}

TEST(SibsonRaster, ReproducesLinearFunctionsAndTheSamplesThroughNaturalNeighbour) {
  // Through the interpolant: inside the hull a linear function is reproduced (the coordinates
  // sum to one and their barycentre is the query); points on samples get the sample's value.
  std::mt19937 rng(5);
  ScatteredSamples s = random_samples(400, rng, 0, 1);
  const Raster raster{160, 140, Rect{0, 0, 1, 1}};
  s.points.push_back(raster.point(80, 70));
  s.values.assign(s.points.size(), 0.0);
  for (size_t i = 0; i < s.points.size(); ++i) s.values[i] = 2.5 + 3 * s.points[i].x() - 1.25 * s.points[i].y();
  const NaturalNeighbour nn(s, OutsideHull::none);
  const size_t count = static_cast<size_t>(raster.width) * raster.height;
  std::vector<double> got(count);
  nn.evaluate_raster(raster, 0, count, got);
  size_t inside = 0;
  for (size_t k = 0; k < count; ++k) {
    const Vec2 q = raster.point(k % raster.width, k / raster.width);
    if (std::isnan(got[k])) continue;
    ++inside;
    ASSERT_NEAR(got[k], 2.5 + 3 * q.x() - 1.25 * q.y(), 1e-12) << q.transpose();
  }
  EXPECT_GT(inside, count * 9 / 10);
  EXPECT_DOUBLE_EQ(got[70 * 160 + 80], s.values.back());
}

TEST(SibsonRaster, ThreeChannelsAndBothHullRulesAgreeWithTheQueryByQueryPath) {
  // A raster reaching past the hull, colour values: the same NaN pattern (outside=none) and the
  // same values to round-off as evaluate() at the same points, the points left by the faces
  // included (by the hull, outside it).
  std::mt19937 rng(9);
  ScatteredSamples s = random_samples(300, rng, 0, 1);
  s.channels = 3;
  s.values.clear();
  for (const Vec2& p : s.points) s.values.insert(s.values.end(), {std::sin(5 * p.x()), p.y() * p.y(), 1 + p.x() * p.y()});
  const Raster raster{123, 77, Rect{-0.1, -0.2, 1.1, 1.05}};
  const std::vector<Vec2> points = raster_points(raster);
  for (const OutsideHull outside : {OutsideHull::none, OutsideHull::nearest}) {
    const NaturalNeighbour nn(s, outside);
    std::vector<double> by_faces(points.size() * 3), by_queries(points.size() * 3);
    nn.evaluate_raster(raster, 0, points.size(), by_faces);
    nn.evaluate(points, by_queries);
    size_t nan = 0;
    for (size_t k = 0; k < by_faces.size(); ++k) {
      ASSERT_EQ(std::isnan(by_faces[k]), std::isnan(by_queries[k])) << "value " << k;
      if (std::isnan(by_faces[k])) {
        ++nan;
        continue;
      }
      ASSERT_NEAR(by_faces[k], by_queries[k], 1e-12) << "value " << k;
    }
    EXPECT_EQ(nan > 0, outside == OutsideHull::none);
  }
}

TEST(SibsonRaster, ValuesDependNeitherOnTheThreadsNorOnTheCuts) {
  std::mt19937 rng(77);
  const ScatteredSamples s = random_samples(2000, rng, 0, 1);
  const NaturalNeighbour nn(s, OutsideHull::nearest);
  // A raster of many rows (a call's rows shared among the threads), and one of a few wide rows
  // (each row cut into pieces that the threads share, as many as the threads want).
  for (const Raster& raster : {Raster{301, 257, Rect{0, 0, 1, 1}}, Raster{5003, 3, Rect{0, 0.2, 1, 0.21}}}) {
    SCOPED_TRACE(std::to_string(raster.width) + " x " + std::to_string(raster.height));
    const size_t count = static_cast<size_t>(raster.width) * raster.height;
    const int threads = worker_thread_count();
    std::vector<double> one(count), many(count), cut(count);
    set_worker_thread_count(1);
    nn.evaluate_raster(raster, 0, count, one);
    set_worker_thread_count(std::max(2, threads));
    nn.evaluate_raster(raster, 0, count, many);
    // Cut at odd places, mid-row.
    for (size_t first = 0, step = 977; first < count; first += step, step = step * 7 % 5003 + 1) {
      const size_t m = std::min(step, count - first);
      nn.evaluate_raster(raster, first, m, std::span(cut).subspan(first, m));
    }
    set_worker_thread_count(threads);
    for (size_t k = 0; k < count; ++k) {
      ASSERT_EQ(one[k], many[k]) << "point " << k;
      ASSERT_EQ(one[k], cut[k]) << "point " << k;
    }
  }
}

TEST(SibsonRaster, WideRowsCutIntoPiecesLeaveTheSamePointsInOrder) {
  // Rows of 5,003 points reaching past the hull: on 2 or more threads each row is cut into
  // pieces; the values and the points left must be those of one thread (whole rows), the points
  // left in increasing order.
  std::mt19937 rng(41);
  const ScatteredSamples s = random_samples(500, rng, 0, 1);
  const Triangulated t(s);
  const SibsonRaster sibson(t.dt, s.points, s.values, 1, t.hull);
  const Raster raster{5003, 3, Rect{-0.1, 0.4, 1.1, 0.41}};
  const size_t count = static_cast<size_t>(raster.width) * raster.height;
  const int threads = worker_thread_count();
  std::vector<double> one(count, -1.0), many(count, -1.0);
  std::vector<size_t> left_one, left_many;
  set_worker_thread_count(1);
  sibson.evaluate(raster, 0, count, one, left_one);
  set_worker_thread_count(std::max(2, threads));
  sibson.evaluate(raster, 0, count, many, left_many);
  set_worker_thread_count(threads);
  ASSERT_FALSE(left_one.empty());  // the points past the hull
  EXPECT_TRUE(std::is_sorted(left_many.begin(), left_many.end()));
  ASSERT_EQ(left_one, left_many);
  std::vector<char> left(count, 0);
  for (const size_t k : left_one) left[k] = 1;
  for (size_t k = 0; k < count; ++k) {
    if (left[k]) continue;
    ASSERT_EQ(one[k], many[k]) << "point " << k;
  }
}

}  // namespace sibson_raster_test
}  // namespace radrecon
