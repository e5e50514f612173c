#include "solver/shooting_patches.h"

#include <algorithm>
#include <functional>

#include "core/check.h"
#include "core/parallel.h"

namespace radrecon {

namespace {

/// Calls f(begin, end) for the elements [begin, end) of each cell of the patch, row by row.
template <typename F>
void for_each_cell(const MeshSurface& side, const ShootingPatch& patch, F&& f) {
  for (int j = patch.j0; j < patch.j1; ++j)
    for (int i = patch.i0; i < patch.i1; ++i) {
      const auto [begin, end] = side.cell_elements(i, j);
      f(begin, end);
    }
}

}  // namespace

ShootingPatches::ShootingPatches(const Mesh& mesh) : first_of_side_(mesh.surfaces.size()) {
  for (size_t s = 0; s < mesh.surfaces.size(); ++s) {
    const MeshSurface& side = mesh.surfaces[s];
    first_of_side_[s] = patches_.size();
    for (int pj = 0; pj < side.patches_v(); ++pj)
      for (int pi = 0; pi < side.patches_u(); ++pi)
        patches_.push_back({s, pi * side.patch_size, pj * side.patch_size, std::min(side.nu, (pi + 1) * side.patch_size),
                            std::min(side.nv, (pj + 1) * side.patch_size)});
  }
}

void ShootingPatches::sum_power(const Mesh& mesh, std::span<const std::vector<Rgb>* const> unshot_w_m2,
                                std::span<const size_t> sides) {
  // Each patch summed by one thread alone: a side listed twice would have two at it.
  RR_CHECK(std::adjacent_find(sides.begin(), sides.end(), std::greater_equal<>()) == sides.end(),
           "patch powers: the sides must be distinct and ascending");
  summing_.clear();
  for (const size_t s : sides)
    for (size_t k = 0; k < static_cast<size_t>(mesh.surfaces[s].patches_u()) * mesh.surfaces[s].patches_v(); ++k)
      summing_.push_back(first_of_side_[s] + k);
  parallel_for_coarse(0, static_cast<std::int64_t>(summing_.size()), [&](std::int64_t k) {
    ShootingPatch& patch = patches_[summing_[static_cast<size_t>(k)]];
    const MeshSurface& side = mesh.surfaces[patch.surface];
    const std::vector<Rgb>& unshot = *unshot_w_m2[patch.surface];
    patch.unshot_w = Rgb::Zero();
    for_each_cell(side, patch, [&](size_t begin, size_t end) {
      for (size_t e = begin; e < end; ++e) patch.unshot_w += side.elements[e].area_m2 * unshot[e];
    });
  });
}

void ShootingPatches::shoot(const Mesh& mesh, size_t k, std::vector<Rgb>& side_unshot_w_m2) {
  ShootingPatch& patch = patches_[k];
  for_each_cell(mesh.surfaces[patch.surface], patch, [&](size_t begin, size_t end) {
    std::fill(side_unshot_w_m2.begin() + static_cast<std::ptrdiff_t>(begin),
              side_unshot_w_m2.begin() + static_cast<std::ptrdiff_t>(end), Rgb::Zero());
  });
  patch.unshot_w = Rgb::Zero();
}

}  // namespace radrecon
