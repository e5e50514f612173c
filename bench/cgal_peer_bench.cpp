// The peer for sibson-c1 (issue 10): CGAL's own Sibson C1 interpolation on W3 (100,000 random
// points onto a 2000 x 2000 raster), as a CGAL user writes it: a Delaunay triangulation,
// sibson_gradient_fitting_nn_2, then per query natural_neighbor_coordinates_2 and
// sibson_c1_interpolation, on both cores (OpenMP, rows in parallel, the walk starting from the
// previous query's face). Values and gradients are looked up by vertex index (vectors, not the
// documented std::map), so the peer is not slowed down by its data access. CGAL fits no gradient
// on the hull; queries whose neighbours include a hull vertex fall back to Sibson's C0 value.
// Beside it, radrecon's sibson-c1 on the same data (build and evaluate, as BM_W3_* in
// reconstruct_bench.cpp). And the peer for natural neighbour (issue 13): CGAL's
// natural_neighbor_coordinates_2 and the linear combination of the values, written the same way,
// beside radrecon's natural-neighbour.

#include <benchmark/benchmark.h>
#include <omp.h>

#include <cmath>
#include <random>
#include <vector>

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Interpolation_gradient_fitting_traits_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/interpolation_functions.h>
#include <CGAL/natural_neighbor_coordinates_2.h>
#include <CGAL/sibson_gradient_fitting.h>

#include "keep_freed_memory.h"
#include "reconstruct/methods.h"

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<unsigned, K>;
using Delaunay = CGAL::Delaunay_triangulation_2<K, CGAL::Triangulation_data_structure_2<Vb>>;
using Traits = CGAL::Interpolation_gradient_fitting_traits_2<K>;

constexpr int kPoints = 100000, kSide = 2000;

struct Data {
  std::vector<K::Point_2> points;
  std::vector<double> values;
  std::vector<K::Point_2> raster;
};

const Data& data() {
  static const Data d = [] {
    Data d;
    std::mt19937 rng(2024);
    std::uniform_real_distribution<double> u(0, 1);
    for (int i = 0; i < kPoints; ++i) {
      const double x = u(rng), y = u(rng);
      d.points.emplace_back(x, y);
      d.values.push_back(std::sin(6 * x) * std::cos(4 * y));
    }
    for (int j = 0; j < kSide; ++j)
      for (int i = 0; i < kSide; ++i) d.raster.emplace_back((i + 0.5) / kSide, (j + 0.5) / kSide);
    return d;
  }();
  return d;
}

/// The Delaunay triangulation of the samples, each vertex's info its sample index.
Delaunay triangulate(const Data& d) {
  std::vector<std::pair<K::Point_2, unsigned>> input;
  for (unsigned i = 0; i < d.points.size(); ++i) input.emplace_back(d.points[i], i);
  return Delaunay(input.begin(), input.end());
}

using Coords = std::vector<std::pair<Delaunay::Vertex_handle, double>>;

/// out[q] = value(coords, their sum, q) at every raster point q inside the hull, NaN outside, as
/// a CGAL user writes it: rows in parallel (OpenMP), each walk from the previous query's face.
template <typename Value>
void evaluate_raster(const Delaunay& dt, const Data& d, std::vector<double>& out, Value value) {
#pragma omp parallel
  {
    Coords coords;
    Delaunay::Face_handle hint;
#pragma omp for schedule(static)
    for (int row = 0; row < kSide; ++row)
      for (int col = 0; col < kSide; ++col) {
        const size_t q = static_cast<size_t>(row) * kSide + col;
        coords.clear();
        hint = dt.locate(d.raster[q], hint);
        const auto r = CGAL::natural_neighbor_coordinates_2(
            dt, d.raster[q], std::back_inserter(coords), CGAL::Identity<std::pair<Delaunay::Vertex_handle, double>>(),
            hint);
        out[q] = r.third ? value(coords, r.second, d.raster[q]) : NAN;
      }
  }
}

/// Sibson's C0 value from the coordinates.
double sibson_c0(const Data& d, const Coords& coords, double norm) {
  double v = 0;
  for (const auto& [vh, w] : coords) v += w * d.values[vh->info()];
  return v / norm;
}

void BM_W3_CgalSibsonC1(benchmark::State& state) {
  const Data& d = data();
  std::vector<double> out(d.raster.size());
  for (auto _ : state) {
    const Delaunay dt = triangulate(d);
    // Gradients by vertex index; hull vertices get none.
    std::vector<K::Vector_2> gradient(d.points.size(), K::Vector_2(0, 0));
    std::vector<char> has_gradient(d.points.size(), 0);
    auto value_by_vertex = [&](Delaunay::Vertex_handle v) { return std::make_pair(d.values[v->info()], true); };
    auto fitted = [&](const std::pair<Delaunay::Vertex_handle, K::Vector_2>& p) {
      gradient[p.first->info()] = p.second;
      has_gradient[p.first->info()] = 1;
      return 0;
    };
    std::vector<int> sink;
    CGAL::sibson_gradient_fitting_nn_2(dt, std::back_inserter(sink), fitted, value_by_vertex, Traits());
    auto gradient_by_vertex = [&](Delaunay::Vertex_handle v) {
      return std::make_pair(gradient[v->info()], has_gradient[v->info()] != 0);
    };
    evaluate_raster(dt, d, out, [&](const Coords& coords, double norm, const K::Point_2& p) {
      const auto c1 =
          CGAL::sibson_c1_interpolation(coords.begin(), coords.end(), norm, p, value_by_vertex, gradient_by_vertex, Traits());
      return c1.second ? c1.first : sibson_c0(d, coords, norm);  // a hull vertex among the neighbours: C0
    });
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(d.raster.size()));
}

void BM_W3_CgalNaturalNeighbour(benchmark::State& state) {
  const Data& d = data();
  std::vector<double> out(d.raster.size());
  for (auto _ : state) {
    const Delaunay dt = triangulate(d);
    evaluate_raster(dt, d, out, [&](const Coords& coords, double norm, const K::Point_2&) { return sibson_c0(d, coords, norm); });
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(d.raster.size()));
}

/// radrecon's `method` on the same data: build and evaluate, no value outside the hull (as CGAL).
void run_radrecon(benchmark::State& state, radrecon::Method method) {
  using namespace radrecon;
  const Data& d = data();
  ScatteredSamples samples;
  for (const auto& p : d.points) samples.points.emplace_back(p.x(), p.y());
  samples.values = d.values;
  std::vector<Vec2> raster;
  for (const auto& p : d.raster) raster.emplace_back(p.x(), p.y());
  std::vector<double> out(raster.size());
  MethodParams params;
  params.outside = OutsideHull::none;
  // The same points as a Raster ((i + 0.5) / kSide, ...), evaluated as `interpolate --raster`
  // does: in batches through evaluate_raster().
  const Raster grid{kSide, kSide, Rect{0, 0, 1, 1}};
  for (auto _ : state) {
    const auto f = make_scattered_interpolant(method, samples, params).value();
    for (size_t first = 0; first < raster.size(); first += kEvaluateBatch) {
      const size_t count = std::min(kEvaluateBatch, raster.size() - first);
      f->evaluate_raster(grid, first, count, std::span(out).subspan(first, count));
    }
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(raster.size()));
}

void BM_W3_RadreconSibsonC1(benchmark::State& state) { run_radrecon(state, radrecon::Method::sibson_c1); }
void BM_W3_RadreconNaturalNeighbour(benchmark::State& state) { run_radrecon(state, radrecon::Method::natural_neighbour); }

BENCHMARK(BM_W3_CgalNaturalNeighbour)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_W3_RadreconNaturalNeighbour)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_W3_CgalSibsonC1)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_W3_RadreconSibsonC1)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace
