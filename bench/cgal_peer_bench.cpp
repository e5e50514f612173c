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

void BM_W3_CgalSibsonC1(benchmark::State& state) {
  const Data& d = data();
  std::vector<double> out(d.raster.size());
  for (auto _ : state) {
    std::vector<std::pair<K::Point_2, unsigned>> input;
    for (unsigned i = 0; i < d.points.size(); ++i) input.emplace_back(d.points[i], i);
    Delaunay dt(input.begin(), input.end());
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
    using Coords = std::vector<std::pair<Delaunay::Vertex_handle, double>>;
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
              dt, d.raster[q], std::back_inserter(coords),
              CGAL::Identity<std::pair<Delaunay::Vertex_handle, double>>(), hint);
          if (!r.third) {
            out[q] = NAN;
            continue;
          }
          const auto c1 = CGAL::sibson_c1_interpolation(coords.begin(), coords.end(), r.second, d.raster[q],
                                                        value_by_vertex, gradient_by_vertex, Traits());
          if (c1.second) {
            out[q] = c1.first;
          } else {  // a hull vertex among the neighbours: Sibson's C0 value
            double v = 0;
            for (const auto& [vh, w] : coords) v += w * d.values[vh->info()];
            out[q] = v / r.second;
          }
        }
    }
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(d.raster.size()));
}

void BM_W3_RadreconSibsonC1(benchmark::State& state) {
  using namespace radrecon;
  const Data& d = data();
  ScatteredSamples samples;
  for (const auto& p : d.points) samples.points.emplace_back(p.x(), p.y());
  samples.values = d.values;
  std::vector<Vec2> raster;
  for (const auto& p : d.raster) raster.emplace_back(p.x(), p.y());
  std::vector<double> out(raster.size());
  for (auto _ : state) {
    const auto f = make_scattered_interpolant(Method::sibson_c1, samples).value();
    f->evaluate(raster, out);
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(raster.size()));
}

void BM_W3_CgalNaturalNeighbour(benchmark::State& state) {
  const Data& d = data();
  std::vector<double> out(d.raster.size());
  for (auto _ : state) {
    std::vector<std::pair<K::Point_2, unsigned>> input;
    for (unsigned i = 0; i < d.points.size(); ++i) input.emplace_back(d.points[i], i);
    Delaunay dt(input.begin(), input.end());
    using Coords = std::vector<std::pair<Delaunay::Vertex_handle, double>>;
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
              dt, d.raster[q], std::back_inserter(coords),
              CGAL::Identity<std::pair<Delaunay::Vertex_handle, double>>(), hint);
          if (!r.third) {
            out[q] = NAN;
            continue;
          }
          double v = 0;
          for (const auto& [vh, w] : coords) v += w * d.values[vh->info()];
          out[q] = v / r.second;
        }
    }
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(d.raster.size()));
}

void BM_W3_RadreconNaturalNeighbour(benchmark::State& state) {
  using namespace radrecon;
  const Data& d = data();
  ScatteredSamples samples;
  for (const auto& p : d.points) samples.points.emplace_back(p.x(), p.y());
  samples.values = d.values;
  std::vector<Vec2> raster;
  for (const auto& p : d.raster) raster.emplace_back(p.x(), p.y());
  std::vector<double> out(raster.size());
  for (auto _ : state) {
    MethodParams params;
    params.outside = OutsideHull::none;  // as CGAL: no value outside the hull
    const auto f = make_scattered_interpolant(Method::natural_neighbour, samples, params).value();
    f->evaluate(raster, out);
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(raster.size()));
}

BENCHMARK(BM_W3_CgalNaturalNeighbour)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_W3_RadreconNaturalNeighbour)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_W3_CgalSibsonC1)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_W3_RadreconSibsonC1)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace
