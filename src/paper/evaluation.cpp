#include "paper/evaluation.h"

#include <algorithm>
#include <stdexcept>

#include "io/image_io.h"
#include "render/ground_map.h"
#include "render/quadtree_figure.h"
#include "sampling/surface_samples.h"

namespace radrecon {

namespace {

/// The method's norms at the evaluation grid, and its ground figures FIGURE_METHOD_*.png.
MethodResult evaluate(const InterpolantResult& built, const std::string& name, const EvaluationGrid& at,
                      const std::filesystem::path& figures, const std::string& figure) {
  // The paper's data sets are fixed: every method builds from them; one that did not is a bug.
  if (!built) throw std::runtime_error("paper: " + name + " cannot reconstruct the " + figure + " data: " + built.reason());
  std::vector<double> values(at.reference_w_m2.size());
  built.value()->evaluate(at.points, values);
  write_png(figures / (figure + "_" + name + "_ground.png"), radiosity_map(values, at.width, at.height, at.white_w_m2), true);
  write_png(figures / (figure + "_" + name + "_difference.png"),
            difference_map(values, at.reference_w_m2, at.width, at.height, at.white_w_m2), false);
  return MethodResult{name, error_norms(values, at.reference_w_m2)};
}

}  // namespace

std::vector<MethodResult> evaluate_grid_data(const Solution& grid, const EvaluationGrid& at, const MethodParams& params,
                                             const std::filesystem::path& figures) {
  const GridCells cells = grid_cells(require_surface(grid, "ground", "grid solution"));
  std::vector<MethodResult> table;
  for (Method m : all_methods())
    table.push_back(evaluate(make_grid_interpolant(m, cells, params), method_name(m), at, figures, "fig3"));
  return table;
}

std::vector<MethodResult> evaluate_quadtree_data(const Solution& quadtree, const EvaluationGrid& at,
                                                 const MethodParams& params, const std::filesystem::path& figures) {
  const SurfaceSolution& ground = require_surface(quadtree, "ground", "quadtree solution");
  const CellSamples leaves = element_cells(ground);
  const ScatteredSamples centres = element_centres(ground);
  std::vector<MethodResult> table;
  for (Method m : scattered_methods()) {
    const InterpolantResult built =
        m == Method::constant ? make_cell_interpolant(leaves) : make_scattered_interpolant(m, centres, params);
    table.push_back(evaluate(built, method_name(m), at, figures, "fig4"));
  }
  write_png(figures / "fig1_quadtree.png",
            quadtree_figure(leaves, 0, 0, std::max(ground.length_u_m, ground.length_v_m), at.white_w_m2), false);
  return table;
}

}  // namespace radrecon
