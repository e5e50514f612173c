#include "sampling/surface_samples.h"

#include <algorithm>

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
  const SurfaceFrame frame = s.frame();
  for (const SolutionElement& e : s.elements) {
    if (s.triangle) {
      const auto uv = e.vertices();
      const std::array<Vec2, 3> t = {frame.st(uv[0]), frame.st(uv[1]), frame.st(uv[2])};
      out.triangles.push_back(t);
      out.cells.push_back({std::min({t[0].x(), t[1].x(), t[2].x()}), std::min({t[0].y(), t[1].y(), t[2].y()}),
                           std::max({t[0].x(), t[1].x(), t[2].x()}), std::max({t[0].y(), t[1].y(), t[2].y()})});
    } else {
      out.cells.push_back({e.u0 * s.length_u_m, e.v0 * s.length_v_m, e.u1 * s.length_u_m, e.v1 * s.length_v_m});
    }
    for (int c = 0; c < 3; ++c) out.values.push_back(e.radiosity_w_m2[c]);
  }
  return out;
}

ScatteredSamples element_centres(const SurfaceSolution& s) {
  ScatteredSamples out;
  out.channels = 3;
  for (const SolutionElement& e : s.elements) {
    out.points.push_back(s.centroid_st(e));
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
