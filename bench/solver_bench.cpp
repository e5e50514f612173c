// Hot paths of the solver: form factors with and without occluders, and whole solves.

#include <benchmark/benchmark.h>

#include <random>

#include "mesh/grid_mesh.h"
#include "solver/form_factor.h"
#include "solver/hierarchical.h"
#include "solver/progressive.h"
#include "solver/visibility.h"

namespace radrecon {
namespace {

ConvexPolygon unit_light() {
  ConvexPolygon p;
  for (const Vec3& c : {Vec3(1, 1, 2.5), Vec3(1, 2, 2.5), Vec3(2, 2, 2.5), Vec3(2, 1, 2.5)}) p.push(c);
  return p;
}

void BM_LambertFormFactor(benchmark::State& state) {
  const ConvexPolygon light = unit_light();
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> xy(0, 4);
  std::vector<Vec3> points(4096);
  for (Vec3& p : points) p = Vec3(xy(rng), xy(rng), 0);
  size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(lambert_form_factor(points[k++ & 4095], Vec3::UnitZ(), light));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_LambertFormFactor);

/// Ground points behind the paper scene's walls: the exact-clipping path.
void BM_VisibleFormFactorPaperWalls(benchmark::State& state) {
  const Scene scene = paper_scene();
  const std::vector<Occluder> occ = make_occluders(scene);
  const std::vector<const Occluder*> walls = {&occ[2], &occ[3]};
  const ConvexPolygon light = unit_light();
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> xy(2.6, 4);
  std::vector<Vec3> points(4096);
  for (Vec3& p : points) p = Vec3(xy(rng), xy(rng), 0);
  size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(visible_form_factor(points[k++ & 4095], Vec3::UnitZ(), light, -Vec3::UnitZ(), walls));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_VisibleFormFactorPaperWalls);

void BM_SolvePaperGrid(benchmark::State& state) {
  const Scene scene = paper_scene();
  const int n = static_cast<int>(state.range(0));
  const Mesh mesh = make_grid_mesh(scene, {n, GridMeshOptions{}.max_patches});
  for (auto _ : state) {
    ProgressiveOptions po;
    benchmark::DoNotOptimize(solve_progressive(scene, mesh, po, "grid"));
  }
  state.counters["elements"] = static_cast<double>(mesh.element_count());
}
BENCHMARK(BM_SolvePaperGrid)->Arg(16)->Arg(100)->Arg(400)->Unit(benchmark::kMillisecond)->Iterations(3);

/// quadtree:LEAVES on the paper scene: the epsilon search (about 15 solves) and the final solve.
void BM_SolvePaperQuadtreeLeaves(benchmark::State& state) {
  const Scene scene = paper_scene();
  const int leaves = static_cast<int>(state.range(0));
  Solution sol;
  for (auto _ : state) sol = solve_hierarchical_leaves(scene, "ground", leaves, HierarchicalOptions{}, "bench");
  state.counters["links"] = static_cast<double>(sol.stats.links);
  state.counters["leaves_all"] = static_cast<double>(sol.stats.elements);
  state.counters["epsilon_w"] = sol.stats.epsilon_w;
}
BENCHMARK(BM_SolvePaperQuadtreeLeaves)->Arg(100)->Arg(286)->Arg(1000)->Arg(4000)->Unit(benchmark::kMillisecond)->Iterations(1);

/// One hierarchical solve at a fixed epsilon (the cost per solve, without the search).
void BM_SolvePaperQuadtreeEpsilon(benchmark::State& state) {
  const Scene scene = paper_scene();
  HierarchicalOptions options;
  options.epsilon_w = 1.0 / static_cast<double>(state.range(0));
  Solution sol;
  for (auto _ : state) sol = solve_hierarchical(scene, options, "bench");
  state.counters["links"] = static_cast<double>(sol.stats.links);
  state.counters["ground_leaves"] = static_cast<double>(leaf_count(sol, "ground"));
}
BENCHMARK(BM_SolvePaperQuadtreeEpsilon)->Arg(20)->Arg(60)->Arg(250)->Arg(1000)->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace
}  // namespace radrecon
