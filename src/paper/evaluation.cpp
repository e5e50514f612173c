#include "paper/evaluation.h"

#include <algorithm>
#include <stdexcept>

#include "core/parallel.h"
#include "io/image_io.h"
#include "render/ground_map.h"
#include "render/quadtree_figure.h"
#include "sampling/surface_samples.h"

namespace radrecon {

namespace {

/// The method's figures at the evaluation grid (`ranges`: its data's natural neighbours' ranges
/// there), and its ground figures FIGURE_METHOD_*.png.
MethodResult evaluate(const InterpolantResult& built, const std::string& name, const EvaluationGrid& at,
                      const std::optional<NeighbourRanges>& ranges, const std::filesystem::path& figures,
                      const std::string& figure) {
  // The paper's data sets are fixed: every method builds from them; one that did not is a bug.
  if (!built) throw std::runtime_error("paper: " + name + " cannot reconstruct the " + figure + " data: " + built.reason());
  std::vector<double> values(at.reference_w_m2.size());
  built.value()->evaluate(at.points, values);
  // The two figures at once, each PNG's compression on a thread of its own.
  parallel_for_coarse(0, 2, [&](std::int64_t k) {
    if (k == 0)
      write_png(figures / (figure + "_" + name + "_ground.png"), radiosity_map(values, at.width, at.height, at.white_w_m2), true);
    else
      write_png(figures / (figure + "_" + name + "_difference.png"),
                difference_map(values, at.reference_w_m2, at.width, at.height, at.white_w_m2), false);
  });
  MethodResult r{name, {}};
  r.figures.norms = error_norms(values, at.reference_w_m2);
  const ImageShape shape{at.width, at.height, 3};
  r.figures.ssim = ssim(display_values(values, at.white_w_m2), at.reference_display, shape);
  r.figures.gradient_l2 = gradient_l2(values, at.reference_w_m2, shape, at.dx_m, at.dy_m);
  if (ranges) r.figures.overshoot = overshoot(*ranges, values);
  return r;
}

}  // namespace

DataSetView prepare_data_set(const Solution& data, const EvaluationGrid& at, const SideSampling& sampling) {
  DataSetView view;
  view.ground = &require_surface(data, "ground", "solution " + data.mesh);
  view.sampling = sampling;
  const SurfaceSolution& ground = *view.ground;
  const bool grid = ground.grid_nu > 0 && ground.grid_nv > 0;
  Barriers barriers;
  if (sampling.barriers) barriers = Barriers::from_polylines(ground.barriers).value();
  view.ranges = neighbour_ranges(grid ? grid_cells(ground).centres() : element_centres(ground), at.points, barriers);
  return view;
}

MethodResult evaluate_method(const DataSetView& data, Method method, const EvaluationGrid& at,
                             const MethodParams& params, const std::filesystem::path& figures,
                             const std::string& figure) {
  return evaluate(reconstruct_side(*data.ground, method, params, data.sampling), method_name(method), at, data.ranges,
                  figures, figure);
}

void write_quadtree_figure(const Solution& quadtree, const EvaluationGrid& at, const std::filesystem::path& figures) {
  const SurfaceSolution& ground = require_surface(quadtree, "ground", "quadtree solution");
  write_png(figures / "fig1_quadtree.png",
            quadtree_figure(element_cells(ground), 0, 0, std::max(ground.length_u_m, ground.length_v_m), at.white_w_m2),
            false);
}

}  // namespace radrecon
