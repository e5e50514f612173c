#include "sampling/surface_samples.h"

#include "core/check.h"
#include "core/error.h"

namespace radrecon {

GridCells grid_cells(const SurfaceSolution& s) {
  RR_CHECK(s.grid_nu > 0 && s.grid_nv > 0, "grid_cells() of an adaptive subdivision");
  RR_CHECK_EQ(static_cast<size_t>(s.grid_nu) * s.grid_nv, s.elements.size(), "grid size does not match the elements");
  GridCells g;
  g.nx = s.grid_nu;
  g.ny = s.grid_nv;
  g.x0 = 0;
  g.y0 = 0;
  g.dx = s.length_u_m / s.grid_nu;
  g.dy = s.length_v_m / s.grid_nv;
  g.channels = 3;
  g.values.reserve(s.elements.size() * 3);
  for (const SolutionElement& e : s.elements)
    for (int c = 0; c < 3; ++c) g.values.push_back(e.radiosity_w_m2[c]);
  return g;
}

CellSamples element_cells(const SurfaceSolution& s) {
  CellSamples out;
  out.channels = 3;
  for (const SolutionElement& e : s.elements) {
    out.cells.push_back({e.u0 * s.length_u_m, e.v0 * s.length_v_m, e.u1 * s.length_u_m, e.v1 * s.length_v_m});
    for (int c = 0; c < 3; ++c) out.values.push_back(e.radiosity_w_m2[c]);
  }
  return out;
}

ScatteredSamples element_centres(const SurfaceSolution& s) {
  ScatteredSamples out;
  out.channels = 3;
  for (const SolutionElement& e : s.elements) {
    out.points.emplace_back(0.5 * (e.u0 + e.u1) * s.length_u_m, 0.5 * (e.v0 + e.v1) * s.length_v_m);
    for (int c = 0; c < 3; ++c) out.values.push_back(e.radiosity_w_m2[c]);
  }
  return out;
}

const SurfaceSolution& require_surface(const Solution& solution, const std::string& name,
                                       const std::string& source) {
  const SurfaceSolution* s = solution.find(name);
  if (!s) throw UserError(source, "has no surface named '" + name + "'");
  return *s;
}

}  // namespace radrecon
