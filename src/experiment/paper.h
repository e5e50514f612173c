#pragma once
// The paper experiment (design brief): solve the built-in scene as the 400 x 400 reference, as
// the 16 x 16 grid data and as the 286-leaf quadtree data, reconstruct the ground by every
// method, and write the solutions, the error tables and the figures.

#include <filesystem>

namespace radrecon {

struct PaperOptions {
  std::filesystem::path out_dir = "out/paper";
  int reference_divisions = 400;  ///< reference grid on the ground (elements per edge)
  int grid_divisions = 16;        ///< the grid data set of Table 1
  int quadtree_leaves = 286;      ///< ground leaves of the quadtree data set of Table 2
  double residual = 1e-4;         ///< progressive refinement stops below this unshot fraction
  int view_width = 480, view_height = 360;  ///< views into the scene (Fig. 2-4), pixels
  int view_samples = 2;                     ///< rays per pixel along each axis
  bool progress = true;           ///< stage messages on stderr
};

void run_paper(const PaperOptions& options);

}  // namespace radrecon
