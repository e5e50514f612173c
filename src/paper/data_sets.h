#pragma once
// The paper's three data sets of the built-in scene, and the points where they are compared.

#include <string>
#include <vector>

#include "paper/paper.h"
#include "scene/scene.h"
#include "solver/solution.h"

namespace radrecon {

struct PaperDataSets {
  Solution reference;  ///< grid:reference_divisions, progressive refinement
  Solution grid;       ///< grid:grid_divisions (Table 1)
  Solution quadtree;   ///< quadtree:quadtree_leaves on the ground, hierarchical (Table 2)
  double reference_s = 0, grid_s = 0, quadtree_s = 0;  ///< wall-clock seconds of each solve
};

/// Solves one data set of `scene` on the mesh `spec` (progress on stderr under `label` if
/// options.progress); `seconds` gets the solve's wall-clock time.
Solution solve_data_set(const Scene& scene, const PaperOptions& options, const std::string& spec,
                        const std::string& label, double& seconds);

/// Where every method is judged: the reference's cell centres on the ground, (s, t) metres,
/// row by row from t = 0, with the reference's cell values there (3 channels each).
struct EvaluationGrid {
  int width = 0, height = 0;
  std::vector<Vec2> points;
  std::vector<double> reference_w_m2;
  double dx_m = 1, dy_m = 1;  ///< the spacing of the points
  double white_w_m2 = 1;  ///< the largest reference value: white in every figure
  /// display_values(reference_w_m2, white_w_m2) (evaluate/metrics.h): SSIM's reference, made once.
  std::vector<double> reference_display;
};
EvaluationGrid evaluation_grid(const Solution& reference);

}  // namespace radrecon
