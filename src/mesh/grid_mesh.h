#pragma once
// Regular-grid meshing: every side of every surface becomes a grid of nu x nv cells over its
// parameter domain (scene/param_cell.h), grouped into square shooting patches for the progressive
// solver. A quad's cell is one quad element; a triangle's (nu = nv) holds the parts of the cell's
// box inside the triangle: its lower half, and its upper half unless the cell lies on the
// hypotenuse (or nothing beyond it): the regular subdivision of the triangle into nu^2 triangles.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "scene/scene.h"
#include "scene/side.h"

namespace radrecon {

/// One element: the image of a cell of its surface's parameter domain.
struct MeshElement : ParamCell {
  /// Counter-clockwise seen from the front of this side; a triangle repeats its last corner.
  std::array<Vec3, 4> corners;
  Vec3 center;  ///< the surface point at the cell's (u,v) centroid
  double area_m2 = 0;
  int corner_count() const { return vertex_count(); }
};

/// One side of a scene surface as a grid of nu x nv cells, stored row by row (cell (i, j) at
/// index j * nu + i, i along u, j along v), each holding the elements
/// [cell_first[c], cell_first[c + 1]) (one per cell of a quad: element (i, j) at j * nu + i).
struct MeshSurface {
  /// The surface name, or "NAME/front" and "NAME/back" for the sides of a two-sided surface.
  std::string name;
  size_t scene_surface = 0;  ///< index into Scene::surfaces
  bool back_side = false;
  Vec3 normal;               ///< unit normal of this side
  Rgb reflectance;
  Rgb emission_w_m2;         ///< zero on a back side: only fronts emit
  ParamCell domain;  ///< the surface's parameter domain (a triangle's is a half-box)
  int nu = 0, nv = 0;
  /// Elements per edge of a square shooting patch (the last row/column may be narrower).
  int patch_size = 1;
  std::vector<MeshElement> elements;
  std::vector<std::uint32_t> cell_first;  ///< nu * nv + 1 offsets into elements

  /// Element (i, j) of a quad's side.
  const MeshElement& element(int i, int j) const { return elements[static_cast<size_t>(j) * nu + i]; }
  /// The elements of cell (i, j): [first, last).
  std::pair<size_t, size_t> cell_elements(int i, int j) const {
    const size_t c = static_cast<size_t>(j) * nu + i;
    return {cell_first[c], cell_first[c + 1]};
  }
  int patches_u() const { return (nu + patch_size - 1) / patch_size; }
  int patches_v() const { return (nv + patch_size - 1) / patch_size; }
};

struct Mesh {
  std::vector<MeshSurface> surfaces;
  size_t element_count() const;
  /// Index of the mesh surface with this name, if any.
  std::optional<size_t> find(const std::string& name) const;
};

struct GridMeshOptions {
  /// >= 1: elements of 1/divisions of the scene's longest quad edge or triangle edge
  /// (longest_edge_m()). Every surface gets elements of (about) that size: a quad
  /// round(edge length / element size) along each edge, a triangle round(longest edge / (sqrt 2 x
  /// element size)) along every edge (its cells about as wide as a square element's diagonal);
  /// at least 1, and at most the surface's own `max_divisions` along its longer edge.
  int divisions = 16;
  /// Shooting patches along the longest edge, >= 1: patches are square groups of
  /// ceil(divisions / max_patches) elements per edge on every surface. The default is the
  /// fastest measured for the Cornell box and a model's triangles, and as fast as any for the
  /// paper scene (solver/solve.h default_patches()).
  int max_patches = 4;
};

/// The largest extent_m() of the scene's surfaces (a quad's longer mean edge, a triangle's
/// longest edge), metres: grid:N's elements are 1/N of it.
double longest_edge_m(const Scene& scene);

/// Elements along u and v of one surface under `options` (the rule of GridMeshOptions), given
/// longest_m = longest_edge_m() of its scene (found once for all its surfaces).
std::pair<int, int> grid_divisions(double longest_m, const Surface& surface, const GridMeshOptions& options);

/// Elements of the whole mesh (both sides of two-sided surfaces), without building it.
size_t grid_element_count(const Scene& scene, const GridMeshOptions& options);

/// Meshes every surface (both sides of a two-sided one) into a regular grid.
Mesh make_grid_mesh(const Scene& scene, const GridMeshOptions& options);

/// The element on one side of a surface for a cell of its parameter domain.
MeshElement make_element(const Surface& surface, bool back_side, const ParamCell& cell);

/// The cells of the regular nu x nv subdivision of a parameter domain that cell (i, j) holds, in
/// order: the box of a quad; the lower and (off the hypotenuse) upper halves of a triangle's.
/// Appends them to `out`.
void grid_cell_parts(const ParamCell& domain, int nu, int nv, int i, int j, std::vector<ParamCell>& out);

}  // namespace radrecon
