#pragma once
// The Delaunay triangulation of the natural-neighbour methods (natural_neighbour.h) and the
// coordinates of a query over the boundary of its conflict zone: Sibson's (the areas the query's
// Voronoi cell steals, by CGAL) or Laplace's (the lengths of its Voronoi edges over the distances).
// Internal to reconstruct/: the CGAL types stay out of the public headers.

#include <utility>
#include <vector>

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include "reconstruct/natural_neighbour.h"

namespace radrecon::nn {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<unsigned, K>;  ///< info: the sample index
using Tds = CGAL::Triangulation_data_structure_2<Vb>;
using Delaunay = CGAL::Delaunay_triangulation_2<K, Tds>;
using Point = K::Point_2;

/// Turns CGAL's (vertex, weight) pairs into (sample index, weight): the output functor of CGAL's
/// coordinate functions.
struct VertexIndex {
  using argument_type = std::pair<Delaunay::Vertex_handle, K::FT>;
  using result_type = std::pair<unsigned, double>;
  result_type operator()(const argument_type& p) const { return {p.first->info(), p.second}; }
};

/// The natural-neighbour coordinates of p, a point strictly inside the triangulation's hull and on
/// no vertex, over the boundary `hole` of its conflict zone (as get_boundary_of_conflicts() gives
/// it, counterclockwise), into `out` as (sample index, weight) pairs, unnormalised. Returns the
/// sum of the weights, or 0 when they are not defined (a degenerate hole).
///   Sibson:  weight_i = the area of p's Voronoi cell taken from sample i's (CGAL's
///            natural_neighbor_coordinates_2).
///   Laplace: weight_i = |e_i| / |p - x_i|, e_i the edge of p's Voronoi cell facing sample i
///            (Belikov & Semenov 1997; Sugihara 1999: non-Sibsonian coordinates). Its ends are the
///            circumcentres of the triangles (p, a, b) over the two boundary edges at x_i.
double hole_coordinates(const Delaunay& dt, const Point& p, const std::vector<Delaunay::Edge>& hole,
                        NeighbourRule rule, std::vector<std::pair<unsigned, double>>& out);

}  // namespace radrecon::nn
