#pragma once
// What radrecon reads of an OBJ file and its MTL files itself, before and beside assimp 5.2 (used
// by io/assimp_import.cpp): the lines assimp misreads or refuses without naming them, the
// materials (assimp never sees the MTL files), and the copy of the OBJ that assimp reads.

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/vec.h"

namespace radrecon {

/// A material an MTL file defines (`newmtl`): its `Kd` and `Ke` if given.
struct ObjMaterial {
  std::optional<Rgb> kd, ke;
};

/// The materials of an OBJ's MTL files (`mtllib`), by name, and a warning for each MTL file not
/// beside the OBJ. radrecon reads them itself: assimp 5.2 read `Kd 0.5` as red only, the second
/// file of `mtllib a.mtl b.mtl` not at all, a file named with a space as two, and refused
/// Blender's `aniso` and `anisor` lines naming neither file nor line.
struct ObjMaterials {
  std::map<std::string, ObjMaterial> defined;
  std::vector<std::string> warnings;
};

/// The OBJ as assimp is given it (ReadFileFromMemory): a UTF-8 byte-order mark dropped (assimp
/// 5.2 read `\xEF\xBB\xBFmtllib` as an unknown line), `mtllib` lines made comments (radrecon reads
/// the materials: ObjMaterials), and, for a model far from the origin against its size, every
/// vertex moved by -offset_m, so that assimp's single-precision floats keep its detail (a lamp
/// 5 cm wide at x = 300000 m came out 3.1 cm wide); the importer adds offset_m back in double.
struct ObjForAssimp {
  std::string text;
  Vec3 offset_m = Vec3::Zero();
};

/// Reads and checks the OBJ, and makes its copy for assimp. Refuses (UserError naming
/// "path:line") a vertex (`v`) that is not x y z, x y z w with w = 1 (assimp 5.2 divides by w) or
/// x y z r g b, all finite numbers; a face (`f`) of fewer than 3 corners, and a face (or line, or
/// point) whose vertex index is 0 or names a vertex the file does not have (a negative one
/// counting back from the vertices before it). A line ending in '\' is joined to the next as
/// assimp 5.2 joins it (the statement named by its first line), and assimp is given it joined.
/// assimp 5.2 reads a coordinate it cannot parse as a smaller vertex count, and refuses an index
/// out of range without the line, leaking memory doing so (LeakSanitizer, found by fuzzing).
ObjForAssimp check_obj(const std::string& path);

/// The OBJ's MTL files read for ObjMaterials, each within the input size limit
/// (core/limits.h check_input_file_size()). `mtllib` names one file per word, or one named by
/// the whole rest of its line where such a file exists (Blender writes `mtllib my mats.mtl`).
/// Refuses (UserError naming "file.mtl:line") a `Kd` or `Ke` that is not one number (grey) or
/// three finite ones (`Kd spectral`, `Kd xyz` included). Other MTL statements are passed over.
ObjMaterials obj_materials(const std::string& path);

}  // namespace radrecon
