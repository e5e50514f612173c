#include "reconstruct/nodal.h"

#include <algorithm>

#include "core/check.h"

namespace radrecon {

CellSamples to_cells(const GridCells& grid) {
  CellSamples out;
  out.channels = grid.channels;
  out.values = grid.values;
  out.cells.reserve(static_cast<size_t>(grid.nx) * grid.ny);
  for (int j = 0; j < grid.ny; ++j)
    for (int i = 0; i < grid.nx; ++i)
      out.cells.push_back({grid.x0 + i * grid.dx, grid.y0 + j * grid.dy, grid.x0 + (i + 1) * grid.dx,
                           grid.y0 + (j + 1) * grid.dy});
  return out;
}

ScatteredSamples GridCells::centres() const {
  ScatteredSamples out;
  out.channels = channels;
  out.values = values;
  out.points.reserve(static_cast<size_t>(nx) * ny);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) out.points.push_back(center(i, j));
  return out;
}

GridNodes nodal_average(const GridCells& cells) {
  RR_CHECK(cells.nx >= 1 && cells.ny >= 1, "a grid needs at least one cell");
  RR_CHECK(cells.values.size() == static_cast<size_t>(cells.nx) * cells.ny * cells.channels,
           "grid values do not match its size");
  GridNodes nodes;
  nodes.nx = cells.nx + 1;
  nodes.ny = cells.ny + 1;
  nodes.x0 = cells.x0;
  nodes.y0 = cells.y0;
  nodes.dx = cells.dx;
  nodes.dy = cells.dy;
  nodes.channels = cells.channels;
  const int C = cells.channels;
  nodes.values.assign(static_cast<size_t>(nodes.nx) * nodes.ny * C, 0.0);
  for (int j = 0; j < nodes.ny; ++j)
    for (int i = 0; i < nodes.nx; ++i) {
      int count = 0;
      double* node = &nodes.values[(static_cast<size_t>(j) * nodes.nx + i) * C];
      for (int cj = std::max(0, j - 1); cj <= std::min(cells.ny - 1, j); ++cj)
        for (int ci = std::max(0, i - 1); ci <= std::min(cells.nx - 1, i); ++ci) {
          const double* cell = &cells.values[(static_cast<size_t>(cj) * cells.nx + ci) * C];
          for (int c = 0; c < C; ++c) node[c] += cell[c];
          ++count;
        }
      for (int c = 0; c < C; ++c) node[c] /= count;
    }
  return nodes;
}

}  // namespace radrecon
