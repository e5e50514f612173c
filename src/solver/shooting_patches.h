#pragma once
// The shooting patches of progressive refinement (solver/progressive.h): each side's cells in
// boxes of MeshSurface::patch_size, each shooting its unshot power as one in a shot.

#include <cstddef>
#include <vector>

#include "mesh/grid_mesh.h"

namespace radrecon {

/// The cells [i0,i1) x [j0,j1) of side `surface` (an index into Mesh::surfaces).
struct Patch {
  size_t surface;
  int i0, j0, i1, j1;
  Rgb unshot_w = Rgb::Zero();  ///< unshot power per channel, W
};

/// Every side's patches, side after side, each side's patch grid row by row, empty ones beyond a
/// triangle's hypotenuse included (they never shoot: no power), so that patch (pi, pj) of side s
/// is patches[first[s] + pj * patches_u + pi].
struct ShootingPatches {
  std::vector<Patch> patches;
  std::vector<size_t> first;

  explicit ShootingPatches(const Mesh& mesh);
  /// Sums again the unshot power of every patch of `sides` (indices into mesh.surfaces) from its
  /// elements' unshot radiosity (unshot[s][e], W/m^2): each patch's elements row by row, the
  /// same sums however many threads; the patches side by side.
  void sum_power(const Mesh& mesh, const std::vector<const std::vector<Rgb>*>& unshot, const std::vector<size_t>& sides);

 private:
  std::vector<size_t> summing_;  ///< the patches of the last sum_power()
};

}  // namespace radrecon
