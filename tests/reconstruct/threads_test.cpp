// Results do not depend on the number of threads: every scattered method, 1 thread against 2,
// bit for bit, on queries that include points on Delaunay edges and at samples.

#include <gtest/gtest.h>
#include <omp.h>

#include <random>

#include "reconstruct/methods.h"

namespace radrecon {
namespace {

TEST(Threads, ScatteredMethodsGiveIdenticalResultsOnOneAndTwoThreads) {
  // Samples on a grid (many queries then lie on Delaunay edges) plus random ones.
  ScatteredSamples s;
  s.channels = 3;
  std::mt19937 rng(41);
  std::uniform_real_distribution<double> u(0, 4);
  for (int j = 0; j < 16; ++j)
    for (int i = 0; i < 16; ++i) s.points.emplace_back(0.125 + 0.25 * i, 0.125 + 0.25 * j);
  for (int k = 0; k < 300; ++k) s.points.emplace_back(u(rng), u(rng));
  for (const Vec2& p : s.points)
    for (int c = 0; c < 3; ++c) s.values.push_back(std::sin(p.x() + c) * std::cos(p.y()));
  std::vector<Vec2> q;
  for (int j = 0; j < 120; ++j)
    for (int i = 0; i < 120; ++i) q.emplace_back(-0.2 + 4.4 * i / 119.0, -0.2 + 4.4 * j / 119.0);
  for (int k = 0; k < 50; ++k) q.push_back(s.points[static_cast<size_t>(k) * 7]);
  std::vector<std::pair<Method, MethodParams>> cases = {{Method::constant, {}}, {Method::shepard, {}},
                                                        {Method::multiquadric, {}}, {Method::natural_neighbour, {}}};
  MethodParams shepard_k;
  shepard_k.shepard_k = 12;
  MethodParams local_mq;
  local_mq.multiquadric_k = 24;
  cases.emplace_back(Method::shepard, shepard_k);
  cases.emplace_back(Method::multiquadric, local_mq);
  const int threads = omp_get_max_threads();
  for (const auto& [method, params] : cases) {
    const auto f = make_scattered_interpolant(method, s, params).value();
    std::vector<double> one(q.size() * 3), two(q.size() * 3);
    omp_set_num_threads(1);
    f->evaluate(q, one);
    omp_set_num_threads(2);
    f->evaluate(q, two);
    omp_set_num_threads(threads);
    for (size_t k = 0; k < one.size(); ++k) ASSERT_EQ(one[k], two[k]) << method_name(method) << " at value " << k;
  }
}

}  // namespace
}  // namespace radrecon
