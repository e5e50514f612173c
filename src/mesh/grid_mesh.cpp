#include "mesh/grid_mesh.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/check.h"

namespace radrecon {

size_t Mesh::element_count() const {
  size_t n = 0;
  for (const MeshSurface& s : surfaces) n += s.elements.size();
  return n;
}

std::optional<size_t> Mesh::find(const std::string& name) const {
  for (size_t i = 0; i < surfaces.size(); ++i)
    if (surfaces[i].name == name) return i;
  return std::nullopt;
}

MeshElement make_element(const Surface& surface, bool back_side, const ParamCell& cell) {
  MeshElement e;
  static_cast<ParamCell&>(e) = cell;
  const auto uv = cell.vertices();
  std::array<Vec3, 4> p;
  for (int k = 0; k < 4; ++k) p[k] = surface.point(uv[k].x(), uv[k].y());
  const int n = cell.vertex_count();
  if (back_side) {
    e.corners[0] = p[0];
    for (int k = 1; k < n; ++k) e.corners[k] = p[n - k];
    if (n == 3) e.corners[3] = e.corners[2];
  } else {
    e.corners = p;
  }
  const Vec2 c = cell.centroid();
  e.center = surface.point(c.x(), c.y());
  e.area_m2 = 0.5 * (p[2] - p[0]).cross(p[3] - p[1]).norm();
  return e;
}

void grid_cell_parts(const ParamCell& domain, int nu, int nv, int i, int j, std::vector<ParamCell>& out) {
  const double u0 = double(i) / nu, v0 = double(j) / nv, u1 = double(i + 1) / nu, v1 = double(j + 1) / nv;
  if (!domain.is_triangle()) {
    out.push_back({u0, v0, u1, v1, CellShape::box});
    return;
  }
  RR_CHECK(nu == nv, "a triangle's grid has as many cells along u as along v");
  if (i + j <= nu - 1) out.push_back({u0, v0, u1, v1, CellShape::lower});
  if (i + j <= nu - 2) out.push_back({u0, v0, u1, v1, CellShape::upper});
}

namespace {

MeshSurface mesh_side(const Surface& s, size_t index, bool back, int nu, int nv, int patch_size) {
  MeshSurface m;
  m.name = side_name(s, back);
  m.scene_surface = index;
  m.back_side = back;
  m.normal = side_normal(s, back);
  m.reflectance = s.reflectance;
  m.emission_w_m2 = side_emission(s, back);
  m.domain = s.domain();
  m.nu = nu;
  m.nv = nv;
  m.patch_size = patch_size;
  m.elements.reserve(static_cast<size_t>(nu) * nv);
  m.cell_first.reserve(static_cast<size_t>(nu) * nv + 1);
  std::vector<ParamCell> parts;
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      m.cell_first.push_back(static_cast<std::uint32_t>(m.elements.size()));
      parts.clear();
      grid_cell_parts(s.domain(), nu, nv, i, j, parts);
      for (const ParamCell& cell : parts) m.elements.push_back(make_element(s, back, cell));
    }
  m.cell_first.push_back(static_cast<std::uint32_t>(m.elements.size()));
  return m;
}

}  // namespace

double longest_edge_m(const Scene& scene) {
  double longest_m = 0;
  for (const Surface& t : scene.surfaces) longest_m = std::max(longest_m, t.extent_m());
  return longest_m;
}

std::pair<int, int> grid_divisions(double longest_m, const Surface& s, const GridMeshOptions& options) {
  RR_CHECK(options.divisions >= 1, "mesh divisions must be positive");
  const double element_m = longest_m / options.divisions;
  // In double first: a tiny element on a long edge must not overflow an int.
  auto count = [&](double length) { return std::clamp(std::round(length / element_m), 1.0, 1e9); };
  double nu = count(s.length_u_m()), nv = count(s.length_v_m());
  if (s.is_triangle()) {
    // The regular subdivision, n cells along every edge: its cells' longest edge about the square
    // element's diagonal, so a square cut along its diagonal meshes as the square's grid, each
    // cell cut in two.
    nu = nv = count(s.extent_m() / std::numbers::sqrt2);  // its longest edge
  }
  if (s.max_divisions && std::max(nu, nv) > *s.max_divisions) {
    const double scale = double(*s.max_divisions) / std::max(nu, nv);
    nu = std::max(1.0, std::round(nu * scale));
    nv = s.is_triangle() ? nu : std::max(1.0, std::round(nv * scale));
  }
  return {static_cast<int>(nu), static_cast<int>(nv)};
}

size_t grid_element_count(const Scene& scene, const GridMeshOptions& options) {
  double total = 0;
  const double longest_m = longest_edge_m(scene);
  for (const Surface& s : scene.surfaces) {
    const auto [nu, nv] = grid_divisions(longest_m, s, options);
    total += double(nu) * nv * (s.two_sided ? 2 : 1);
  }
  return static_cast<size_t>(std::min(total, 1e18));
}

Mesh make_grid_mesh(const Scene& scene, const GridMeshOptions& options) {
  RR_CHECK(options.divisions >= 1 && options.max_patches >= 1, "mesh options out of range");
  const int patch_size = (options.divisions + options.max_patches - 1) / options.max_patches;

  Mesh mesh;
  const double longest_m = longest_edge_m(scene);
  for (size_t k = 0; k < scene.surfaces.size(); ++k) {
    const Surface& s = scene.surfaces[k];
    const auto [nu, nv] = grid_divisions(longest_m, s, options);
    mesh.surfaces.push_back(mesh_side(s, k, false, nu, nv, patch_size));
    if (s.two_sided) mesh.surfaces.push_back(mesh_side(s, k, true, nu, nv, patch_size));
  }
  return mesh;
}

}  // namespace radrecon
