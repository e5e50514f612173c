#pragma once
// From cell values to nodal (vertex) values, for the grid interpolants.

#include "reconstruct/samples.h"

namespace radrecon {

/// Nodal values of a grid of cells: every node gets the mean of the cells that share it, four
/// in the interior, two on an edge of the patch and one at a corner (Cohen and Wallace 1993,
/// sec. 9.2, "nodal averaging"). The nodes are the (nx + 1) x (ny + 1) cell corners, so on the
/// patch border the value is the mean of the border cells only (no extrapolation).
GridNodes nodal_average(const GridCells& cells);

}  // namespace radrecon
