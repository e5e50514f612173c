// Reconstruction on the paper's evaluation grid: 16 x 16 cells onto 400 x 400 points.

#include <benchmark/benchmark.h>

#include <random>

#include "reconstruct/methods.h"

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
  const auto interpolant = make_grid_interpolant(method, cells);
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
