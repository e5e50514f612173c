#pragma once
// A PLY file's completeness, which assimp 5.2 does not check: a file cut short is read by it as
// a model with fewer or shorter records. (Used by io/mesh_import.h.)

#include <cstddef>
#include <string>

namespace radrecon {

/// Reads the PLY file's header and walks its data (ASCII or binary, either byte order) record by
/// record; returns the number of faces the header declares. Throws UserError naming the file if
/// the header is malformed or the data ends before the last declared record.
size_t check_ply_size(const std::string& path);

}  // namespace radrecon
