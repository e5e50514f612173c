#pragma once
// The shooting patches of progressive refinement (solver/progressive.h): each side's cells in
// boxes of MeshSurface::patch_size, each shooting its unshot power as one in a shot.

#include <cstddef>
#include <span>
#include <vector>

#include "mesh/grid_mesh.h"

namespace radrecon {

/// The cells [i0,i1) x [j0,j1) of side `surface` (an index into Mesh::surfaces).
struct ShootingPatch {
  size_t surface;
  int i0, j0, i1, j1;
  Rgb unshot_w = Rgb::Zero();  ///< unshot power per channel, W
};

/// Every side's patches, side after side, each side's patch grid row by row, empty ones beyond a
/// triangle's hypotenuse included (they never shoot: no power), so that patch (pi, pj) of side s
/// is patches()[first_of_side(s) + pj * patches_u + pi]; and their unshot power.
class ShootingPatches {
 public:
  explicit ShootingPatches(const Mesh& mesh);
  const std::vector<ShootingPatch>& patches() const { return patches_; }
  size_t first_of_side(size_t s) const { return first_of_side_[s]; }
  /// Sums again the unshot power of every patch of `sides` (indices into mesh.surfaces, distinct
  /// and ascending) from its elements' unshot radiosity (unshot_w_m2[s][e], W/m^2): each patch's
  /// elements row by row, the same sums however many threads; the patches side by side.
  void sum_power(const Mesh& mesh, std::span<const std::vector<Rgb>* const> unshot_w_m2, std::span<const size_t> sides);
  /// Patch k shoots: its elements' unshot radiosity (in `side_unshot_w_m2`, its side's, by
  /// element) and its power set to zero. Its side's other patches keep theirs: a side never
  /// receives from a patch of its own surface (nor the surface's other side).
  void shoot(const Mesh& mesh, size_t k, std::vector<Rgb>& side_unshot_w_m2);

 private:
  std::vector<ShootingPatch> patches_;
  std::vector<size_t> first_of_side_;
  std::vector<size_t> summing_;  ///< the patches of the last sum_power()
};

}  // namespace radrecon
