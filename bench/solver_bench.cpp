// Hot paths of the solver: form factors with and without occluders, and whole solves.

#include <benchmark/benchmark.h>

#include <random>

#include "keep_freed_memory.h"
#include "mesh/grid_mesh.h"
#include "solver/bvh.h"
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

/// A room 10 x 10 x 3 m with an N x N grid of boxes (5 quads each) on the floor, as
/// bench/make_scenes.py writes it: 6 + 5 N^2 surfaces, the light (surface 0) under the ceiling,
/// the floor surface 1.
Scene boxes_scene(int n) {
  Scene scene;
  auto quad = [&](const std::string& name, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    Surface s;
    s.name = name;
    s.corners = {a, b, c, d};
    s.reflectance = Rgb::Constant(0.5);
    scene.surfaces.push_back(s);
  };
  quad("light", {4, 4, 2.99}, {4, 6, 2.99}, {6, 6, 2.99}, {6, 4, 2.99});
  scene.surfaces[0].emission_w_m2 = Rgb::Constant(40);
  quad("floor", {0, 0, 0}, {10, 0, 0}, {10, 10, 0}, {0, 10, 0});
  const double pitch = 9.0 / n;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double cx = 0.5 + (i + 0.5) * pitch, cy = 0.5 + (j + 0.5) * pitch, h = 0.3 + 0.12 * ((i * 7 + j * 13) % 10);
      const double r = 0.3 * pitch, a = 0.3 * ((i + j) % 3), ca = std::cos(a), sa = std::sin(a);
      auto p = [&](double x, double y, double z) { return Vec3(cx + ca * x - sa * y, cy + sa * x + ca * y, z); };
      const std::array<Vec3, 4> b = {p(-r, -r, 0), p(r, -r, 0), p(r, r, 0), p(-r, r, 0)};
      const std::array<Vec3, 4> t = {p(-r, -r, h), p(r, -r, h), p(r, r, h), p(-r, r, h)};
      const std::string id = std::to_string(i) + "_" + std::to_string(j);
      quad("top" + id, t[0], t[1], t[2], t[3]);
      for (int k = 0; k < 4; ++k) quad("side" + id + "_" + std::to_string(k), b[k], b[(k + 1) % 4], t[(k + 1) % 4], t[k]);
    }
  return scene;
}

/// The direct light's form factor at random floor points among N x N boxes: candidates from the
/// box scan of the whole floor-light pair (the code before the BVH; range(1) == 0) or from the
/// BVH with a shaft per point (range(1) == 1). Items: receiver points.
void BM_VisibilityBoxes(benchmark::State& state) {
  const Scene scene = boxes_scene(static_cast<int>(state.range(0)));
  const std::vector<Occluder> occ = make_occluders(scene);
  const OccluderBvh bvh(occ);
  const bool shaft = state.range(1) != 0;
  ConvexPolygon light;
  for (const Vec3& c : scene.surfaces[0].corners) light.push(c);
  const std::vector<const Occluder*> pair = occluders_between(occ, scene.surfaces[1].corners, scene.surfaces[0].corners, 1, 0);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> xy(0, 10);
  std::vector<Vec3> points(1024);
  for (Vec3& p : points) p = Vec3(xy(rng), xy(rng), 0);
  std::vector<const Occluder*> near;
  size_t k = 0, candidates = 0;
  for (auto _ : state) {
    const Vec3& p = points[k++ & 1023];
    const std::vector<const Occluder*>* list = &pair;
    if (shaft) {
      near.clear();
      bvh.collect(Shaft({&p, 1}, scene.surfaces[0].corners), 1, 0, near);
      list = &near;
    }
    candidates += list->size();
    benchmark::DoNotOptimize(visible_form_factor(p, Vec3::UnitZ(), light, -Vec3::UnitZ(), *list));
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["surfaces"] = static_cast<double>(scene.surfaces.size());
  state.counters["candidates"] = static_cast<double>(candidates) / static_cast<double>(state.iterations());
}
BENCHMARK(BM_VisibilityBoxes)->ArgsProduct({{10, 20, 40}, {0, 1}});

void BM_SolvePaperGrid(benchmark::State& state) {
  const Scene scene = paper_scene();
  const int n = static_cast<int>(state.range(0));
  const Mesh mesh = make_grid_mesh(scene, {n, GridMeshOptions{}.max_patches});
  for (auto _ : state) {
    ProgressiveOptions po;
    state.PauseTiming();
    Mesh copy = mesh;  // the solver takes its mesh by value: the copy is not what is timed
    state.ResumeTiming();
    benchmark::DoNotOptimize(solve_progressive(scene, std::move(copy), po, "grid"));
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
