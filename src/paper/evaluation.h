#pragma once
// Tables 1 and 2 measured: each method reconstructs the ground from a data set, is judged at the
// evaluation grid, and draws its ground figures (radiosity, difference x 2).

#include <filesystem>
#include <string>
#include <vector>

#include "evaluate/norms.h"
#include "paper/data_sets.h"
#include "reconstruct/methods.h"

namespace radrecon {

struct MethodResult {
  std::string name;  ///< the method's name
  ErrorNorms norms;
};

/// Table 1: every method on the grid data set's ground (cells; nodal values for bilinear and
/// bicubic, cell centres for the scattered methods). Writes figures/fig3_METHOD_{ground,difference}.png.
std::vector<MethodResult> evaluate_grid_data(const Solution& grid, const EvaluationGrid& at, const MethodParams& params,
                                             const std::filesystem::path& figures);

/// Table 2: the scattered methods on the quadtree data set's ground (constant: the leaf that
/// contains the point; the others: the leaf centres). Writes fig4_METHOD_{ground,difference}.png
/// and Fig. 1 (fig1_quadtree.png).
std::vector<MethodResult> evaluate_quadtree_data(const Solution& quadtree, const EvaluationGrid& at,
                                                 const MethodParams& params, const std::filesystem::path& figures);

}  // namespace radrecon
