#pragma once
// The paper experiment (design brief), a client of the library: solve the built-in scene as the
// 400 x 400 reference, as the 16 x 16 grid data and as the 286-leaf quadtree data, reconstruct
// the ground by every method, and write the solutions, Tables 1 and 2, the figures and the
// report. Its parts: data_sets.h (the solutions and where they are compared), evaluation.h
// (norms and ground figures per method), views.h (views into the scene), tables.h (the tables
// and errors.json beside the paper's published figures), report.h (report.html).

#include <filesystem>

#include "solver/progressive.h"

namespace radrecon {

/// The file of an output folder that lists the files its run wrote (io/output_folder.h).
inline constexpr const char* kPaperManifest = ".radrecon-paper-files";

struct PaperOptions {
  std::filesystem::path out_dir = "out/paper";
  int reference_divisions = 400;  ///< reference grid on the ground (elements per edge)
  int grid_divisions = 16;        ///< the grid data set of Table 1
  int quadtree_leaves = 286;      ///< ground leaves of the quadtree data set of Table 2
  double residual = kDefaultResidual;       ///< progressive refinement stops below this unshot fraction
  int view_width = 480, view_height = 360;  ///< views into the scene (Fig. 2-4), pixels
  int view_samples = 2;                     ///< rays per pixel along each axis
  bool progress = true;                     ///< stage messages on stderr
  /// Also the data sets with the scene's barriers (grid+barriers, quadtree+barriers: Table 3,
  /// Fig. 5 and 6).
  bool barriers = true;
  /// And with border samples too (grid+barriers+border, quadtree+barriers+border: Table 3,
  /// Fig. 7 and 8).
  bool border_samples = false;
  /// Solve the data sets with the direct light's D1/D2 lines among the barriers too (an
  /// experiment: SolveSettings::shadow_barriers).
  bool shadow_barriers = false;
};

/// Runs the experiment into options.out_dir. The output folder is checked before any work
/// (UserError naming `out_where` if it cannot be used).
void run_paper(const PaperOptions& options, const std::string& out_where);

}  // namespace radrecon
