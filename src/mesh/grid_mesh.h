#pragma once
// Regular-grid meshing: every side of every surface becomes a grid of quad elements, grouped
// into square shooting patches for the progressive solver.

#include <array>
#include <string>
#include <vector>

#include "scene/scene.h"
#include "scene/side.h"

namespace radrecon {

/// One element: the image of the (u,v) rectangle [u0,u1] x [v0,v1] of its surface.
struct MeshElement {
  double u0, v0, u1, v1;
  std::array<Vec3, 4> corners;  ///< counter-clockwise seen from the front of this side
  Vec3 center;                  ///< the surface point at the (u,v) centre of the element
  double area_m2;
};

/// One side of a scene surface as a grid of nu x nv elements, stored row by row
/// (element (i, j) at index j * nu + i, i along u, j along v).
struct MeshSurface {
  /// The surface name, or "NAME/front" and "NAME/back" for the sides of a two-sided surface.
  std::string name;
  size_t scene_surface = 0;  ///< index into Scene::surfaces
  bool back_side = false;
  Vec3 normal;               ///< unit normal of this side
  Rgb reflectance;
  Rgb emission_w_m2;         ///< zero on a back side: only fronts emit
  int nu = 0, nv = 0;
  /// Elements per edge of a square shooting patch (the last row/column may be narrower).
  int patch_size = 1;
  std::vector<MeshElement> elements;

  const MeshElement& element(int i, int j) const { return elements[static_cast<size_t>(j) * nu + i]; }
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
  /// Elements along the longest surface edge of the scene, >= 1. Every surface gets elements of
  /// (about) the same size: round(edge length / element size) along each edge, at least 1, and
  /// at most the surface's own `max_divisions` along its longer edge.
  int divisions = 16;
  /// Shooting patches along the longest edge, >= 1: patches are square groups of
  /// ceil(divisions / max_patches) elements per edge on every surface.
  int max_patches = 2;
};

/// Elements along u and v of one surface under `options` (the rule of GridMeshOptions).
std::pair<int, int> grid_divisions(const Scene& scene, const Surface& surface, const GridMeshOptions& options);

/// Elements of the whole mesh (both sides of two-sided surfaces), without building it.
size_t grid_element_count(const Scene& scene, const GridMeshOptions& options);

/// Meshes every surface (both sides of a two-sided one) into a regular grid.
Mesh make_grid_mesh(const Scene& scene, const GridMeshOptions& options);

/// The element on one side of a surface for the (u,v) rectangle [u0,u1] x [v0,v1].
MeshElement make_element(const Surface& surface, bool back_side, double u0, double v0, double u1,
                         double v1);

}  // namespace radrecon
