#pragma once
// What radrecon reads of an OBJ file and its MTL files itself, before and beside assimp 5.2 (used
// by io/assimp_import.cpp): the lines assimp misreads or refuses without naming them, and the
// material facts it drops.

#include <map>
#include <set>
#include <string>
#include <vector>

#include "core/vec.h"

namespace radrecon {

/// The materials an OBJ's MTL files (`mtllib`) define (`newmtl`), their colours given as one
/// value (`Kd 0.5`: grey, by the MTL format; assimp 5.2 reads it as red only), and a warning for
/// each MTL file not beside the OBJ. assimp reads on without it, giving a material named by
/// `usemtl` but defined nowhere Kd 0.6: radrecon gives such faces the default instead.
struct ObjMaterials {
  std::set<std::string> defined;
  std::map<std::string, Rgb> grey_kd, grey_ke;  ///< material name -> its one-value Kd, Ke
  std::vector<std::string> warnings;
};

/// Refuses (UserError naming "path:line") an OBJ vertex (`v`) whose first three coordinates are
/// not finite numbers, a face (`f`) of fewer than 3 corners, and a face (or line, or point) whose vertex index is 0 or names a vertex
/// the file does not have (a negative one counting back from the vertices before it). assimp 5.2
/// reads a coordinate it cannot parse as a smaller vertex count, and refuses an index out of
/// range without the line, leaking memory doing so (LeakSanitizer, found by fuzzing).
void check_obj_lines(const std::string& path);

/// The OBJ's MTL files read for ObjMaterials, each within the input size limit
/// (core/limits.h check_input_file_size()).
ObjMaterials obj_materials(const std::string& path);

}  // namespace radrecon
