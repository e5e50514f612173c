#pragma once
// What assimp 5.2 does not read or check in a glTF 2.0 file: the KHR_materials_emissive_strength
// of its materials (dropped), and faces whose vertex indices are out of range (silently dropped).
// This reads the file's JSON (a .gltf, or the JSON chunk of a .glb) for the materials' factors,
// and makes the copy assimp reads, whose materials are named by their index, so that mesh import
// (io/mesh_import.h) finds each of assimp's materials in the file; and counts the faces its
// primitives declare, to compare with the number assimp read.

#include <string>
#include <vector>

#include "core/vec.h"

namespace radrecon {

struct GltfMaterialFactors {
  std::string name;                 ///< "" if the material has none
  /// pbrMetallicRoughness.baseColorFactor (rgb), default 1; or, where the material has the
  /// (archived) KHR_materials_pbrSpecularGlossiness, its diffuseFactor (rgb), default 1, which
  /// that extension puts in the core's place
  Rgb base_colour = Rgb::Ones();
  std::string base_colour_field;    ///< where base_colour comes from, for messages
  Rgb emissive = Rgb::Zero();       ///< emissiveFactor, default 0
  double emissive_strength = 1.0;   ///< KHR_materials_emissive_strength.emissiveStrength, default 1
};

struct GltfExtras {
  /// The factors of every entry of the file's "materials" array, in order.
  std::vector<GltfMaterialFactors> materials;
  /// Faces (points, lines or triangles) its meshes' primitives declare: by the count of their
  /// indices accessor (or else of their POSITION accessor) and their mode, as assimp makes them.
  size_t faces = 0;
  /// The file as assimp is to read it (GltfIOSystem): the same, but every material named
  /// gltf_material_tag(its index), so that each of assimp's materials is found by index (assimp
  /// 5.2 loads only the materials the default scene uses, in the order it meets them, and names
  /// an unnamed one ""), and every strided buffer view holding count x byteStride bytes
  /// (pad_strided_views(), io/gltf_indices.h). A .gltf's JSON, or a .glb with its JSON chunk so
  /// rewritten (and its BIN chunk padded).
  std::string assimp_copy;
};

/// The name a glTF material has in GltfExtras::assimp_copy.
std::string gltf_material_tag(size_t index);
/// The index of a material named by gltf_material_tag(), or -1 for another name (assimp's
/// default material, for a primitive without one).
long long gltf_material_index(const std::string& name);

/// Reads the extras of a .gltf or .glb. UserError naming the file and the line or field if the
/// JSON cannot be read (invalid JSON, a truncated .glb), is no glTF 2.0 (asset.version), or a
/// factor is not a finite number >= 0. (The rest of the schema is assimp's to check.)
GltfExtras read_gltf_extras(const std::string& path);

}  // namespace radrecon
