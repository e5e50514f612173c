#pragma once
// What assimp 5.2 does not read or check in a glTF 2.0 file: the KHR_materials_emissive_strength
// of its materials (dropped), and faces whose vertex indices are out of range (silently dropped).
// This reads the file's JSON (a .gltf, or the JSON chunk of a .glb) for the materials' factors,
// so that mesh import (io/mesh_import.h) can find each of assimp's materials in it, and for the
// number of faces its primitives declare, to compare with the number assimp read.

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

struct GltfExtras {
  /// The factors of every entry of the file's "materials" array, in order.
  std::vector<GltfMaterialFactors> materials;
  /// Faces (points, lines or triangles) its meshes' primitives declare: by the count of their
  /// indices accessor (or else of their POSITION accessor) and their mode, as assimp makes them.
  size_t faces = 0;
};

/// Reads the extras of a .gltf or .glb. UserError naming the file and the line or field if the
/// JSON cannot be read (invalid JSON, a truncated .glb), is no glTF 2.0 (asset.version), or a
/// factor is not a finite number >= 0. (The rest of the schema is assimp's to check.)
GltfExtras read_gltf_extras(const std::string& path);

}  // namespace radrecon
