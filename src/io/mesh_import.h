#pragma once
// Mesh import through assimp (Debian's libassimp-dev): OBJ with MTL, glTF 2.0 (.gltf, .glb) and
// PLY, each face a radrecon Surface (docs/formats.md, "Meshes"). The reader itself
// (io/assimp_import.h) is the plugin libradrecon_assimp.so (io/plugin.h), loaded by the first
// import.

#include <optional>
#include <string>
#include <vector>

#include "core/parse.h"
#include "scene/scene.h"

namespace radrecon {

enum class MeshFormat { kObj, kGltf, kPly };

/// The model format import_mesh() reads `path` as, by its extension (.obj; .gltf and .glb; .ply;
/// any case), if any.
inline std::optional<MeshFormat> mesh_format(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext == ".obj") return MeshFormat::kObj;
  if (ext == ".gltf" || ext == ".glb") return MeshFormat::kGltf;
  if (ext == ".ply") return MeshFormat::kPly;
  return std::nullopt;
}

/// Whether `path` names a model file import_mesh() reads.
inline bool is_mesh_file(const std::string& path) { return mesh_format(path).has_value(); }

/// How a model's faces are placed and what overrides their materials. A point p of the file
/// (after its node transforms) lands at translate_m + scale * R_x(rotate_x_deg) p: the file's
/// units are read as metres, scaled, rotated about the x axis (90 turns glTF's Y-up into Z-up),
/// then moved.
struct MeshPlacement {
  double scale = 1.0;                    ///< > 0
  double rotate_x_deg = 0.0;             ///< right-handed, about +x
  Vec3 translate_m = Vec3::Zero();
  std::optional<Rgb> reflectance;        ///< replaces every face's reflectance
  std::optional<Rgb> emission_w_m2;      ///< replaces every face's emission
  std::optional<bool> two_sided;         ///< default false
  std::optional<int> max_divisions;      ///< Surface::max_divisions of every face
  bool merge_triangles = true;           ///< merge_coplanar_triangle_pairs() (io/mesh_polygons.h)
};

struct MeshImport {
  std::vector<Surface> surfaces;
  std::vector<std::string> warnings;  ///< one line each, naming the file
  size_t faces_read = 0;              ///< faces in the file (each instance of a mesh counted)
  size_t degenerate_skipped = 0;      ///< faces of fewer than 3 corners or of zero area
  size_t polygons_triangulated = 0;   ///< faces of more than 4 corners, cut into triangles
  size_t self_crossing_skipped = 0;   ///< faces of more than 4 corners that cross themselves
  size_t triangle_pairs_merged = 0;   ///< pairs of triangles made quads
};

/// Reads a model file into surfaces named "MESH:FACE" (MESH: the mesh's name, or the file's stem
/// if it has none, with '/', control characters and bytes not valid UTF-8 made '_'; "#2", "#3"... on later instances of the same name; FACE:
/// the face's index in its mesh, ".tK" for the K-th triangle of a larger polygon). Materials: OBJ
/// Kd, glTF baseColorFactor, else PLY vertex colours averaged over the face, else 0.5 grey;
/// clamped into [0, 0.999] with a warning. Emission (W/m^2, as stored): OBJ Ke, glTF
/// emissiveFactor x KHR_materials_emissive_strength. Faces of zero area are skipped with one
/// warning. Warped or concave quads are left to regularise_surfaces().
/// Throws UserError naming `path` and what is wrong for any file it cannot read whole: unknown
/// extension, empty, truncated, malformed, indices out of range, non-finite numbers, no faces.
/// Loads the plugin on first use (a UserError naming `path` if it cannot be).
MeshImport import_mesh(const std::string& path, const MeshPlacement& placement = {});

/// The function import_mesh() calls: the plugin's by default. A program linked with the reader
/// itself (the fuzz harnesses, io/assimp_import.h) sets it to import_mesh_assimp, so that the
/// reader is instrumented with the program.
using MeshImporter = MeshImport (*)(const std::string& path, const MeshPlacement& placement);
void set_mesh_importer(MeshImporter importer);

/// Prints `warnings` on stderr ("radrecon: warning: ..."), at most `limit` of them and then a
/// line counting the rest.
void print_warnings(const std::vector<std::string>& warnings, size_t limit = 10);

}  // namespace radrecon
