#pragma once
// Tables 1 and 2 measured: each method reconstructs the ground from a data set, is judged at the
// evaluation grid, and draws its ground figures (radiosity, difference x 2).

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "evaluate/metrics.h"
#include "paper/data_sets.h"
#include "reconstruct/methods.h"
#include "sampling/solution_reconstruction.h"

namespace radrecon {

struct MethodResult {
  std::string name;  ///< the method's name
  Figures figures;   ///< norms, SSIM, gradient_L2, overshoot (evaluate/metrics.h)
};

/// A data set as every method sees it: the ground of a solution, with or without its barriers,
/// and the range of the data's natural neighbours (its cell or leaf centres) at each point of the
/// evaluation grid, over the samples each point sees (for the overshoot).
struct DataSetView {
  const SurfaceSolution* ground = nullptr;
  SideSampling sampling;
  std::optional<NeighbourRanges> ranges;
};

/// Prepares `data`'s ground for evaluate_method() (the ranges: the costly part shared by methods).
DataSetView prepare_data_set(const Solution& data, const EvaluationGrid& at, const SideSampling& sampling);

/// One method on a prepared data set, reconstructed as the renderer does (reconstruct_side():
/// grid data as cells, nodal values for bilinear and bicubic and cell centres for the scattered
/// methods; quadtree data as leaves for constant and leaf centres otherwise), with the ground's
/// barriers if the data set's sampling says so. Judged by the norms, SSIM of the ground figures
/// against the reference's, the gradient error at the grid's spacing, and the overshoot past the
/// range of the data's natural neighbours. Writes figures/FIGURE_METHOD_{ground,difference}.png.
MethodResult evaluate_method(const DataSetView& data, Method method, const EvaluationGrid& at,
                             const MethodParams& params, const std::filesystem::path& figures,
                             const std::string& figure);

/// Fig. 1: the quadtree data set's ground leaves, figures/fig1_quadtree.png.
void write_quadtree_figure(const Solution& quadtree, const EvaluationGrid& at, const std::filesystem::path& figures);

}  // namespace radrecon
