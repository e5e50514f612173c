#pragma once
// From a solved surface to the samples a reconstruction starts from, in the surface's metric
// coordinates (s, t) (SurfaceFrame, scene/scene.h), metres.

#include "reconstruct/samples.h"
#include "solver/solution.h"

namespace radrecon {

/// The elements of a regular-grid surface (grid_nu x grid_nv > 0, as solution readers check)
/// as grid cells.
GridCells grid_cells(const SurfaceSolution& surface);

/// The elements of any surface (grid or quadtree) as cells of a piecewise-constant function (a
/// triangle's as triangles, CellSamples::triangles).
CellSamples element_cells(const SurfaceSolution& surface);

/// The centroids of the elements with their radiosity, as scattered samples.
ScatteredSamples element_centres(const SurfaceSolution& surface);

/// The surface with this name in the solution; UserError naming `source` if there is none.
const SurfaceSolution& require_surface(const Solution& solution, const std::string& name,
                                       const std::string& source);

}  // namespace radrecon
