#include "sampling/solution_reconstruction.h"

#include <cmath>

#include "core/error.h"
#include "core/parse.h"
#include "core/tolerances.h"
#include "reconstruct/border_samples.h"
#include "sampling/surface_samples.h"

namespace radrecon {

InterpolantResult reconstruct_side(const SurfaceSolution& s, Method method, const MethodParams& plain,
                                   const SideSampling& sampling) {
  MethodParams params = plain;
  if (sampling.barriers && !s.barriers.empty()) {
    Result<Barriers> barriers = Barriers::from_polylines(s.barriers);
    if (!barriers) return Failure{"its barriers: " + barriers.reason()};
    params.barriers = std::move(barriers).value();
  }
  const bool grid = s.grid_nu > 0 && s.grid_nv > 0;
  if (sampling.border_samples && method != Method::constant && !is_grid_method(method)) {
    ScatteredSamples samples = grid ? grid_cells(s).centres() : element_centres(s);
    Result<ScatteredSamples> bordered =
        with_border_samples(samples, Rect{0, 0, s.length_u_m, s.length_v_m}, params.barriers);
    if (!bordered) return Failure{"its border samples: " + bordered.reason()};
    return make_scattered_interpolant(method, bordered.value(), params);
  }
  if (grid) return make_grid_interpolant(method, grid_cells(s), params);
  if (method == Method::constant && params.barriers.empty()) return make_cell_interpolant(element_cells(s));
  if (is_grid_method(method))
    return Failure{method_name(method) + " needs grid data; this side is an adaptive subdivision"};
  return make_scattered_interpolant(method, element_centres(s), params);
}

SolutionReconstruction::SolutionReconstruction(const Scene& scene, const Solution& solution, Method method,
                                               const MethodParams& params, const std::string& source,
                                               const SideSampling& sampling) {
  sides_.resize(side_slots(scene));
  for (const SurfaceSolution& side : solution.surfaces) {
    const std::optional<SideRef> ref = find_side(scene, side.name);
    if (!ref)
      throw UserError(source, "surface '" + side.name + "' is not a side of the scene's surfaces (" + side_names(scene) + ")");
    // The scene's edge lengths, so that (s, t) match the renderer's; a solution of another scene
    // whose sides have the same names has other lengths.
    const Surface& surface = scene.surfaces[ref->surface];
    const auto differs = [](double a, double b) { return std::abs(a - b) > tol::kSolutionLengthRelative * b; };
    if (differs(side.length_u_m, surface.length_u_m()) || differs(side.length_v_m, surface.length_v_m()))
      throw UserError(source, "surface '" + side.name + "' is " + format_number(side.length_u_m) + " m x " +
                                  format_number(side.length_v_m) + " m in the solution but " +
                                  format_number(surface.length_u_m()) + " m x " + format_number(surface.length_v_m()) +
                                  " m in the scene: the solution belongs to another scene");
    SurfaceSolution s = side;
    s.length_u_m = surface.length_u_m();
    s.length_v_m = surface.length_v_m();
    InterpolantResult built = reconstruct_side(s, method, params, sampling);
    if (!built) {
      fallbacks_.push_back({side.name, built.reason()});
      built = reconstruct_side(s, Method::constant, params, SideSampling{.barriers = false});
      if (!built) throw UserError(source, "surface '" + side.name + "': " + built.reason());
    }
    sides_[ref->slot()] = std::move(built).value();
  }
}

SolutionReconstruction::~SolutionReconstruction() = default;

const Interpolant* SolutionReconstruction::side(SideRef side) const { return sides_[side.slot()].get(); }

}  // namespace radrecon
