#include "io/paths.h"

#include <unistd.h>

#include <filesystem>
#include <system_error>

#include "core/error.h"

namespace radrecon {

namespace fs = std::filesystem;

namespace {

/// The absolute path with every symbolic link of its existing part and every "." and ".."
/// resolved.
fs::path resolved(const std::string& path) {
  std::error_code ec;
  fs::path p = fs::weakly_canonical(fs::absolute(path, ec), ec);
  return ec ? fs::absolute(path).lexically_normal() : p;
}

/// The path's nearest ancestor that exists must be a folder we may write into.
void check_writable_ancestor(const fs::path& path, const std::string& where) {
  std::error_code ec;
  fs::path dir = fs::absolute(path, ec).parent_path();
  while (!dir.empty() && !fs::exists(dir, ec)) {
    if (dir == dir.parent_path()) break;
    dir = dir.parent_path();
  }
  if (!fs::is_directory(dir, ec))
    throw UserError(where, "'" + path.string() + "' cannot be created: '" + dir.string() + "' is not a folder");
  if (::access(dir.c_str(), W_OK | X_OK) != 0)
    throw UserError(where, "'" + path.string() + "' cannot be written: no permission to write in '" + dir.string() + "'");
}

}  // namespace

void refuse_overwriting_inputs(const std::string& output, const std::string& where,
                               const std::vector<std::string>& inputs) {
  const fs::path out = resolved(output);
  for (const std::string& input : inputs) {
    std::error_code ec;
    const bool same = out == resolved(input) || (fs::exists(output, ec) && fs::equivalent(output, input, ec));
    if (same) throw UserError(where, "'" + output + "' is the input file '" + input + "'; refusing to overwrite it");
  }
}

void check_output_file(const std::string& path, const std::string& where) {
  if (path.empty()) throw UserError(where, "the output file name is empty");
  if (fs::path(path).filename().empty())
    throw UserError(where, "'" + path + "' names a folder (it ends in '/'); give a file name");
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (fs::is_directory(status)) throw UserError(where, "'" + path + "' is a folder, not a file");
  if (fs::exists(status) && !fs::is_regular_file(status))
    throw UserError(where, "'" + path + "' is not a regular file; refusing to replace it");
  check_writable_ancestor(path, where);
}

void check_output_folder(const std::string& path, const std::string& where) {
  if (path.empty()) throw UserError(where, "the output folder name is empty");
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (fs::exists(status) && !fs::is_directory(status))
    throw UserError(where, "'" + path + "' exists and is not a folder");
  if (fs::is_directory(status)) {
    if (::access(path.c_str(), W_OK | X_OK) != 0) throw UserError(where, "no permission to write in '" + path + "'");
    return;
  }
  check_writable_ancestor(path, where);
}

}  // namespace radrecon
