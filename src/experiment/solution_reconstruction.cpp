#include "experiment/solution_reconstruction.h"

#include "core/error.h"
#include "experiment/surface_data.h"
#include "mesh/grid_mesh.h"
#include "reconstruct/constant.h"

namespace radrecon {

SolutionReconstruction::SolutionReconstruction(const Scene& scene, const Solution& solution, Method method,
                                               const MethodParams& params, const std::string& source) {
  sides_.resize(2 * scene.surfaces.size());
  for (const SurfaceSolution& side : solution.surfaces) {
    const std::optional<SideRef> ref = find_side(scene, side.name);
    if (!ref) throw UserError(source, "surface '" + side.name + "' is not a side of the scene's surfaces (" + side_names(scene) + ")");
    const size_t index = ref->surface;
    const bool back = ref->back_side;
    // The scene's edge lengths, so that (s, t) match the renderer's.
    SurfaceSolution s = side;
    s.length_u_m = scene.surfaces[index].length_u_m();
    s.length_v_m = scene.surfaces[index].length_v_m();
    const bool grid = s.grid_nu > 0 && s.grid_nv > 0;
    InterpolantResult built = Failure{method_name(method) + " needs grid data; the side is an adaptive subdivision"};
    if (grid) built = make_grid_interpolant(method, grid_cells(s), params);
    else if (method == Method::constant) built = std::unique_ptr<Interpolant>(std::make_unique<PiecewiseConstant>(element_cells(s)));
    else if (!is_grid_method(method)) built = make_scattered_interpolant(method, element_centres(s), params);
    std::unique_ptr<Interpolant> f;
    if (built) {
      f = std::move(built).value();
    } else {
      fallbacks_.push_back(side.name);
      f = grid ? make_grid_interpolant(Method::constant, grid_cells(s)).value() : std::make_unique<PiecewiseConstant>(element_cells(s));
    }
    sides_[2 * index + (back ? 1 : 0)] = std::move(f);
  }
}

SolutionReconstruction::~SolutionReconstruction() = default;

const Interpolant* SolutionReconstruction::side(size_t surface, bool back_side) const {
  return sides_[2 * surface + (back_side ? 1 : 0)].get();
}

}  // namespace radrecon
