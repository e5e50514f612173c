// Reconstruction on the paper's evaluation grid: 16 x 16 cells onto 400 x 400 points.

#include <benchmark/benchmark.h>

#include <cmath>
#include <map>
#include <random>

#include "keep_freed_memory.h"
#include "reconstruct/kdtree.h"
#include "reconstruct/methods.h"
#include "reconstruct/multiquadric_basis.h"

namespace radrecon {
namespace {

void BM_GridReconstruct(benchmark::State& state) {
  const Method method = static_cast<Method>(state.range(0));
  GridCells cells;
  cells.nx = cells.ny = 16;
  cells.dx = cells.dy = 0.25;
  cells.channels = 3;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> value(0, 1);
  cells.values.resize(16 * 16 * 3);
  for (double& v : cells.values) v = value(rng);
  std::vector<Vec2> points;
  for (int j = 0; j < 400; ++j)
    for (int i = 0; i < 400; ++i) points.emplace_back((i + 0.5) * 0.01, (j + 0.5) * 0.01);
  std::vector<double> out(points.size() * 3);
  const auto interpolant = make_grid_interpolant(method, cells).value();
  for (auto _ : state) {
    interpolant->evaluate(points, out);
    benchmark::DoNotOptimize(out.data());
  }
  state.SetLabel(method_name(method));
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(points.size()));
}
BENCHMARK(BM_GridReconstruct)->DenseRange(0, static_cast<int>(all_methods().size()) - 1)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace radrecon

namespace radrecon {
namespace {

/// The workloads: W1 = 286 random points onto a 400 x 400 raster of the unit square's
/// cell centres, W3 = 100,000 random points onto 2000 x 2000. Values: a smooth function.
struct Workload {
  ScatteredSamples samples;
  std::vector<Vec2> raster;
};

const Workload& workload(int points, int side) {
  static std::map<std::pair<int, int>, Workload> cache;
  auto it = cache.find({points, side});
  if (it != cache.end()) return it->second;
  Workload w;
  std::mt19937 rng(2024);
  std::uniform_real_distribution<double> u(0, 1);
  for (int i = 0; i < points; ++i) {
    const Vec2 p(u(rng), u(rng));
    w.samples.points.push_back(p);
    w.samples.values.push_back(std::sin(6 * p.x()) * std::cos(4 * p.y()));
  }
  w.raster.reserve(static_cast<size_t>(side) * side);
  for (int j = 0; j < side; ++j)
    for (int i = 0; i < side; ++i) w.raster.emplace_back((i + 0.5) / side, (j + 0.5) / side);
  return cache.emplace(std::make_pair(points, side), std::move(w)).first->second;
}

/// Build and evaluate, as `radrecon interpolate` does (file I/O excluded).
void run_scattered(benchmark::State& state, Method method, int points, int side, const MethodParams& params) {
  const Workload& w = workload(points, side);
  std::vector<double> out(w.raster.size());
  for (auto _ : state) {
    const auto f = make_scattered_interpolant(method, w.samples, params).value();
    f->evaluate(w.raster, out);
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(w.raster.size()));
}

void BM_W1_Shepard(benchmark::State& s) { run_scattered(s, Method::shepard, 286, 400, {}); }
void BM_W1_Multiquadric(benchmark::State& s) { run_scattered(s, Method::multiquadric, 286, 400, {}); }
void BM_W1_NaturalNeighbour(benchmark::State& s) { run_scattered(s, Method::natural_neighbour, 286, 400, {}); }
void BM_W3_NaturalNeighbour(benchmark::State& s) { run_scattered(s, Method::natural_neighbour, 100000, 2000, {}); }
void BM_W3_ShepardK32(benchmark::State& s) {
  MethodParams p;
  p.shepard_k = 32;
  run_scattered(s, Method::shepard, 100000, 2000, p);
}
/// One RBF fit through 140 of 286 random points (3 channels): what the paper's barrier data sets
/// solve some 2,400 times per method (a query's fit through the samples it sees).
void BM_RbfFitSubset(benchmark::State& state) {
  const RbfKernel kernel = state.range(0) ? RbfKernel::thin_plate() : RbfKernel::multiquadric(0.5);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Vec2> points(286);
  for (Vec2& p : points) p = Vec2(u(rng), u(rng));
  std::vector<double> values(points.size() * 3);
  for (double& v : values) v = u(rng);
  const std::vector<double> r_sq = kernel.is_thin_plate() ? std::vector<double>(points.size(), 0.0)
                                                          : eck_radii_sq(points, KdTree2(points));
  std::vector<unsigned> subset;
  for (unsigned i = 0; i < points.size(); i += 2) subset.push_back(i);
  for (auto _ : state) {
    RbfFit fit = fit_rbf(points, r_sq, values, 3, kernel, subset);
    benchmark::DoNotOptimize(fit.alpha_by_channel.data());
  }
  state.SetLabel(kernel.name());
}
BENCHMARK(BM_RbfFitSubset)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

BENCHMARK(BM_W1_Shepard)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_W1_Multiquadric)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_W1_NaturalNeighbour)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_W3_NaturalNeighbour)->Unit(benchmark::kMillisecond)->Iterations(2);
BENCHMARK(BM_W3_ShepardK32)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace
}  // namespace radrecon
