#pragma once
// One entry to the solvers by mesh specification, for the command line and the experiments:
//   grid:N            progressive refinement on regular grids (mesh/grid_mesh.h)
//   quadtree-eps:E    hierarchical radiosity refined to epsilon E watts
//   quadtree:LEAVES   hierarchical radiosity with exactly LEAVES leaves on one surface side

#include <string>
#include <vector>

#include "mesh/grid_mesh.h"
#include "scene/scene.h"
#include "solver/progressive.h"
#include "solver/solution.h"

namespace radrecon {

/// The shooting patches along the longest edge when none are asked for
/// (GridMeshOptions::max_patches): 4, the fastest for the Cornell box at grid:128 (against 2, 3,
/// 6 and 8) and the Wuson scene (45-48 s against 71-75 s with 2), and within the noise of the
/// fastest (3) for the paper's reference (docs/benchmarks.md, twenty-sixth session). Smaller
/// patches give smaller trees to visit from each receiver, in more shots.
int default_patches();
/// The most shooting patches along the longest edge one may ask for (SolveSettings::patches).
inline constexpr int kMostPatches = 100000;

struct SolveSettings {
  double residual = kDefaultResidual;  ///< progressive: stop below this unshot fraction of the emitted power
  /// progressive: shooting patches along the longest edge; 0: default_patches()
  int patches = 0;
  /// progressive: the far field's error bound as a fraction of irradiance; 0: the distance rule
  /// (ProgressiveOptions::far_field_error)
  double far_field_error = kDefaultFarFieldError;
  /// Many sides of one element shoot in clusters (ProgressiveOptions::clusters).
  bool clusters = true;
  /// quadtree:LEAVES: the side that gets LEAVES leaves; empty: "ground" if the scene has such a
  /// side, else "floor", else the side of the largest surface.
  std::string leaves_on;
  /// Where leaves_on came from (an option or field), named if it is refused.
  std::string leaves_on_where = "leaves_on";
  std::string progress_label;  ///< empty: quiet
  /// Also list the direct light's D1/D2 lines (scene/shadow_lines.h) among each side's barriers,
  /// after its contact lines. Off by default: measured on the paper scene, as barriers they cut
  /// off regions that hold no sample (docs/method.md).
  bool shadow_barriers = false;
};

/// Why `residual` cannot be SolveSettings::residual (a number in [kMinResidual, kMaxResidual]),
/// e.g. "must be a number in [1e-12, 0.5], got 2"; empty if it can.
std::string residual_problem(double residual);
/// Why `far_field_error` cannot be SolveSettings::far_field_error (0, or a number in
/// [kMinFarFieldError, kMaxFarFieldError]); empty if it can.
std::string far_field_error_problem(double far_field_error);
/// Why `patches` cannot be SolveSettings::patches (0, the default, or a count up to
/// kMostPatches); empty if it can.
std::string patches_problem(long long patches);
/// Refuses settings out of range (UserError naming the field: residual, far_field_error,
/// patches), whoever filled them in; solve_scene() calls it first. The command line checks its
/// options as it parses them, before any work.
void check_settings(const SolveSettings& settings);

/// Refuses an option that the kind of mesh `mesh_spec` names does not use, rather than ignoring
/// it: `grid_only_given`, the names of the grid-only options given (residual, patches, far-field
/// error, clusters), with any mesh but grid:N; `leaves_on_given`, the leaves-on option's name if
/// given, with any but quadtree:LEAVES. Throws UserError naming the first.
void refuse_unused_options(const std::string& mesh_spec, const std::vector<std::string>& grid_only_given,
                           const std::string& leaves_on_given);

/// Solves `scene` as `mesh_spec` says. Throws UserError naming `where` (the caller's location
/// of the specification, e.g. an option) for a malformed or
/// impossible specification.
Solution solve_scene(const Scene& scene, const std::string& mesh_spec, const SolveSettings& settings,
                     const std::string& where);

}  // namespace radrecon
