#include "solver/shooting_patches.h"

#include <algorithm>

#include "core/parallel.h"

namespace radrecon {

ShootingPatches::ShootingPatches(const Mesh& mesh) : first(mesh.surfaces.size()) {
  for (size_t s = 0; s < mesh.surfaces.size(); ++s) {
    const MeshSurface& side = mesh.surfaces[s];
    first[s] = patches.size();
    for (int pj = 0; pj < side.patches_v(); ++pj)
      for (int pi = 0; pi < side.patches_u(); ++pi)
        patches.push_back({s, pi * side.patch_size, pj * side.patch_size, std::min(side.nu, (pi + 1) * side.patch_size),
                           std::min(side.nv, (pj + 1) * side.patch_size)});
  }
}

void ShootingPatches::sum_power(const Mesh& mesh, const std::vector<const std::vector<Rgb>*>& unshot,
                                const std::vector<size_t>& sides) {
  summing_.clear();
  for (const size_t s : sides)
    for (size_t k = 0; k < static_cast<size_t>(mesh.surfaces[s].patches_u()) * mesh.surfaces[s].patches_v(); ++k)
      summing_.push_back(first[s] + k);
  parallel_for_coarse(0, static_cast<std::int64_t>(summing_.size()), [&](std::int64_t k) {
    Patch& patch = patches[summing_[static_cast<size_t>(k)]];
    const MeshSurface& side = mesh.surfaces[patch.surface];
    const std::vector<Rgb>& radiosity = *unshot[patch.surface];
    patch.unshot_w = Rgb::Zero();
    for (int j = patch.j0; j < patch.j1; ++j)
      for (int i = patch.i0; i < patch.i1; ++i) {
        const auto [begin, end] = side.cell_elements(i, j);
        for (size_t e = begin; e < end; ++e) patch.unshot_w += side.elements[e].area_m2 * radiosity[e];
      }
  });
}

}  // namespace radrecon
