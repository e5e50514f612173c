#pragma once
// Checks on output paths, made before any work: a refusal costs the user nothing, and no input
// is ever overwritten.

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace radrecon {

/// Refuses (UserError naming `where` and both paths) an output path that is, or resolves to,
/// one of the `inputs` files: symbolic links and ".." are resolved, and an existing output is
/// compared by identity too (a hard link to an input is the input). An input that does not exist
/// is passed over: its reader refuses it as missing.
void refuse_overwriting_inputs(const std::string& output, const std::string& where,
                               const std::vector<std::string>& inputs);

/// Refuses (UserError naming both) two outputs of one run that are, or resolve to, the same file:
/// `outputs` holds (where, path) pairs, an empty path skipped. Symbolic links are followed as the
/// writing follows them (file_written_at(): to a file not yet made too), "." and ".." resolved,
/// and existing files compared by identity (hard links).
void refuse_shared_outputs(const std::vector<std::pair<std::string, std::string>>& outputs);

/// The file that writing `path` replaces: `path` with the symbolic links of its last part
/// followed, to a target that does not exist yet too (write_file_atomically() writes there);
/// `path` itself when it is no link. UserError naming `path` for a link that cannot be read, or
/// after 40 of them.
std::filesystem::path file_written_at(const std::filesystem::path& path);

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
