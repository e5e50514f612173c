#pragma once
// Checks on output paths, made before any work: a refusal costs the user nothing, and no input
// is ever overwritten.

#include <string>
#include <vector>

namespace radrecon {

/// Refuses (UserError naming `where` and both paths) an output path that is, or resolves to,
/// one of the `inputs` files: symbolic links and ".." are resolved, and an existing output is
/// compared by identity too (a hard link to an input is the input).
void refuse_overwriting_inputs(const std::string& output, const std::string& where,
                               const std::vector<std::string>& inputs);

/// Refuses (UserError naming `where`) an output file path that cannot be written: an empty path
/// or one ending in '/', an existing folder or non-regular file, or a path whose nearest existing ancestor is not a writable
/// folder. Creates nothing.
void check_output_file(const std::string& path, const std::string& where);

/// A name (a scene's, a camera's) made fit to be part of a file name: every character but ASCII
/// letters, digits, '-', '_' and '.' made '_' (no '/', no "..": nothing leaves its folder), a
/// leading '.' too, and cut to `most` bytes; "_" if empty.
std::string file_name_part(const std::string& name, size_t most = 60);

/// Refuses (UserError naming `where`) an output folder that cannot be used: an empty path, an
/// existing path that is not a folder, or one whose nearest existing ancestor is not a writable folder.
/// Creates nothing.
void check_output_folder(const std::string& path, const std::string& where);

}  // namespace radrecon
