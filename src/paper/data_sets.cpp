#include "paper/data_sets.h"

#include <algorithm>
#include <chrono>
#include <cstdio>

#include "evaluate/metrics.h"
#include "sampling/surface_samples.h"
#include "solver/solve.h"

namespace radrecon {

Solution solve_data_set(const Scene& scene, const PaperOptions& opt, const std::string& spec, const std::string& label,
                        double& seconds) {
  SolveSettings settings;
  settings.residual = opt.residual;
  settings.shadow_barriers = opt.shadow_barriers;
  if (opt.progress) std::fprintf(stderr, "paper: solving %s (%s)\n", label.c_str(), spec.c_str());
  settings.progress_label = opt.progress ? label : "";
  const auto start = std::chrono::steady_clock::now();
  Solution s = solve_scene(scene, spec, settings, "paper data set " + label);
  seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return s;
}

EvaluationGrid evaluation_grid(const Solution& reference) {
  const GridCells cells = grid_cells(require_surface(reference, "ground", "reference solution"));
  EvaluationGrid e;
  e.width = cells.nx;
  e.height = cells.ny;
  e.points.reserve(static_cast<size_t>(e.width) * e.height);
  for (int j = 0; j < e.height; ++j)
    for (int i = 0; i < e.width; ++i) e.points.push_back(cells.center(i, j));
  e.reference_w_m2 = cells.values;
  e.dx_m = cells.dx;
  e.dy_m = cells.dy;
  e.white_w_m2 = 0;
  for (double v : e.reference_w_m2) e.white_w_m2 = std::max(e.white_w_m2, v);
  e.reference_display = display_values(e.reference_w_m2, e.white_w_m2);
  return e;
}

}  // namespace radrecon
