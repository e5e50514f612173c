#pragma once
// Progressive refinement radiosity (Cohen, Chen, Wallace and Greenberg 1988) with
// substructuring (Cohen et al. 1986): elements receive, patches of elements shoot.
//
// Each step shoots the patch with the largest unshot power (summed over channels). A receiving
// element's irradiance gain is sum over the shooter's parts of (unshot radiosity of the part) x
// F(dA_receiver -> part), with F the exact visible point-to-polygon form factor at the element
// centre (visibility.h). Parts: the patch as a whole when it is far from the receiver (or its
// unshot radiosity is uniform, which is exact), else recursively its quarters, down to single
// elements; "far" by an error bound (ProgressiveOptions::far_field_error), or as a fixed
// multiple of the block's diagonal (tolerances.h, kFarFieldDiagonals).

#include <string>

#include "mesh/grid_mesh.h"
#include "solver/solution.h"

namespace radrecon {

/// Progressive refinement stops by default when the unshot power falls below this fraction of
/// the emitted power: 1e-4 keeps the paper's reference within 0.1% of converged.
inline constexpr double kDefaultResidual = 1e-4;
/// The residuals a user may ask for: below 1e-12 round-off dominates; above 0.5 half the light
/// is never distributed.
inline constexpr double kMinResidual = 1e-12, kMaxResidual = 0.5;
/// The far field's default error bound (ProgressiveOptions::far_field_error): measured against a
/// solve with a bound of 1e-3, it keeps the paper reference's wall fronts within 0.04%, its
/// ground within 0.31% and its umbra within 0.08% (the back sides' 0.34% is the same at bounds
/// of 2e-2 to 4e-2), and each side of the Cornell box at grid:32 within 0.14% on average of a
/// bound 20 times finer (docs/benchmarks.md, twenty-eighth session). 3e-2 took 12% less
/// processor time on the Cornell box at grid:128, for 1.5 times the error.
inline constexpr double kDefaultFarFieldError = 2e-2;
/// The far-field error bounds a user may ask for, besides 0 (the distance rule).
inline constexpr double kMinFarFieldError = 1e-6, kMaxFarFieldError = 0.5;

struct ProgressiveOptions {
  /// Stop when the unshot power falls below this fraction of the emitted power, in (0, 1).
  double residual = kDefaultResidual;
  /// Stop after this many shots at the latest (0: no limit).
  size_t max_shots = 0;
  /// The far field's error bound in each shot, at each receiving element's centre, as a fraction
  /// of its irradiance (gathered so far plus this shot's); the errors of successive shots add
  /// up, and the element's mean (its power) is estimated rather than bounded. 0: blocks shoot as
  /// one beyond tol::kFarFieldDiagonals of their diagonal instead, with no bound. See gather()
  /// in solver/gather.h.
  double far_field_error = kDefaultFarFieldError;
  /// Whether a mesh's many sides of a single element (a model's triangles) shoot in clusters
  /// (solver/shooter_clusters.h), with a point source's shadows far from each cluster; false:
  /// each alone, with exact shadows.
  bool clusters = true;
  /// Whether a patch keeps, for its later shots, what each receiving element behind many shadows
  /// saw of its blocks (solver/gather.h BlockView); false: every shot finds them again. The same
  /// values either way (to round-off, and a seen-in-part flag by the per-block test, where a shot
  /// reaches a block without a view from the shot before), only slower without (for the tests,
  /// and for measuring).
  bool keep_block_views = true;
  /// Name printed in progress messages on stderr; empty: quiet.
  std::string progress_label;
};

/// Solves the radiosity of the meshed scene. `mesh_spec` is recorded in the solution. The mesh is
/// taken by value: the solver weighs the area of an element partly enclosed by surfaces standing
/// on its side by its exposed fraction (solver/enclosed.h); the solution keeps the whole areas.
Solution solve_progressive(const Scene& scene, Mesh mesh, const ProgressiveOptions& options,
                           const std::string& mesh_spec);

}  // namespace radrecon
