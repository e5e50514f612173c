#pragma once
// What assimp 5.2 does not read from a glTF 2.0 file: the KHR_materials_emissive_strength of its
// materials. This reads the file's JSON (a .gltf, or the JSON chunk of a .glb) for the materials'
// factors, so that mesh import (io/mesh_import.h) can find each of assimp's materials in it.

#include <string>
#include <vector>

#include "core/vec.h"

namespace radrecon {

struct GltfMaterialFactors {
  std::string name;                 ///< "" if the material has none
  Rgb base_colour = Rgb::Ones();    ///< pbrMetallicRoughness.baseColorFactor (rgb), default 1
  Rgb emissive = Rgb::Zero();       ///< emissiveFactor, default 0
  double emissive_strength = 1.0;   ///< KHR_materials_emissive_strength.emissiveStrength, default 1
};

/// The factors of every entry of the file's "materials" array, in order. UserError naming the
/// file and the line or field if the JSON cannot be read (invalid JSON, a truncated .glb), is no
/// glTF 2.0 (asset.version), or a factor is not a finite number >= 0.
std::vector<GltfMaterialFactors> read_gltf_material_factors(const std::string& path);

}  // namespace radrecon
