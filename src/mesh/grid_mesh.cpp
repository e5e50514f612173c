#include "mesh/grid_mesh.h"

#include <algorithm>
#include <cmath>

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

MeshElement make_element(const Surface& surface, bool back_side, double u0, double v0, double u1,
                         double v1) {
  MeshElement e;
  e.u0 = u0;
  e.v0 = v0;
  e.u1 = u1;
  e.v1 = v1;
  Vec3 p00 = surface.point(u0, v0), p10 = surface.point(u1, v0);
  Vec3 p11 = surface.point(u1, v1), p01 = surface.point(u0, v1);
  if (back_side)
    e.corners = {p00, p01, p11, p10};
  else
    e.corners = {p00, p10, p11, p01};
  e.center = surface.point(0.5 * (u0 + u1), 0.5 * (v0 + v1));
  e.area_m2 = 0.5 * (p11 - p00).cross(p01 - p10).norm();
  return e;
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
  m.nu = nu;
  m.nv = nv;
  m.patch_size = patch_size;
  m.elements.reserve(static_cast<size_t>(nu) * nv);
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i)
      m.elements.push_back(make_element(s, back, double(i) / nu, double(j) / nv, double(i + 1) / nu,
                                        double(j + 1) / nv));
  return m;
}

}  // namespace

std::pair<int, int> grid_divisions(const Scene& scene, const Surface& s, const GridMeshOptions& options) {
  RR_CHECK(options.divisions >= 1, "mesh divisions must be positive");
  double longest_m = 0;
  for (const Surface& t : scene.surfaces) longest_m = std::max({longest_m, t.length_u_m(), t.length_v_m()});
  const double element_m = longest_m / options.divisions;
  // In double first: a tiny element on a long edge must not overflow an int.
  auto count = [&](double length) { return std::clamp(std::round(length / element_m), 1.0, 1e9); };
  double nu = count(s.length_u_m()), nv = count(s.length_v_m());
  if (s.max_divisions && std::max(nu, nv) > *s.max_divisions) {
    const double scale = double(*s.max_divisions) / std::max(nu, nv);
    nu = std::max(1.0, std::round(nu * scale));
    nv = std::max(1.0, std::round(nv * scale));
  }
  return {static_cast<int>(nu), static_cast<int>(nv)};
}

size_t grid_element_count(const Scene& scene, const GridMeshOptions& options) {
  double total = 0;
  for (const Surface& s : scene.surfaces) {
    const auto [nu, nv] = grid_divisions(scene, s, options);
    total += double(nu) * nv * (s.two_sided ? 2 : 1);
  }
  return static_cast<size_t>(std::min(total, 1e18));
}

Mesh make_grid_mesh(const Scene& scene, const GridMeshOptions& options) {
  RR_CHECK(options.divisions >= 1 && options.max_patches >= 1, "mesh options out of range");
  const int patch_size = (options.divisions + options.max_patches - 1) / options.max_patches;

  Mesh mesh;
  for (size_t k = 0; k < scene.surfaces.size(); ++k) {
    const Surface& s = scene.surfaces[k];
    const auto [nu, nv] = grid_divisions(scene, s, options);
    mesh.surfaces.push_back(mesh_side(s, k, false, nu, nv, patch_size));
    if (s.two_sided) mesh.surfaces.push_back(mesh_side(s, k, true, nu, nv, patch_size));
  }
  return mesh;
}

}  // namespace radrecon
