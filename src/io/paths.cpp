#include "io/paths.h"

#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "core/error.h"

namespace radrecon {

namespace fs = std::filesystem;

namespace {

/// The absolute path with every symbolic link of its existing part and every "." and ".."
/// resolved, spelt two ways: as written, and with "." and ".." removed first. The system
/// resolves "missing/.." only once "missing" exists, and writing an output creates its folders,
/// so "missing/../input.csv" must be caught as the input too.
std::array<fs::path, 2> spellings(const std::string& path) {
  std::error_code ec;
  const fs::path absolute = fs::absolute(path, ec).lexically_normal();
  std::array<fs::path, 2> out;
  out[0] = fs::weakly_canonical(fs::absolute(path, ec), ec);
  if (ec) out[0] = absolute;
  out[1] = fs::weakly_canonical(absolute, ec);
  if (ec) out[1] = absolute;
  return out;
}

/// A file can be made in `dir`: one is made and removed. access() alone passes for root where
/// none can be (/proc, /sys), and the refusal would then come only after the work.
void probe_writable(const fs::path& dir, const fs::path& path, const std::string& where) {
  std::string probe = (dir / ".radrecon-probe-XXXXXX").string();
  const int fd = ::mkstemp(probe.data());
  if (fd < 0)
    throw UserError(where, "'" + path.string() + "' cannot be written: cannot create a file in '" + dir.string() +
                               "': " + std::strerror(errno));
  ::close(fd);
  ::unlink(probe.c_str());
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
  probe_writable(dir, path, where);
}

}  // namespace

void refuse_overwriting_inputs(const std::string& output, const std::string& where,
                               const std::vector<std::string>& inputs) {
  const std::array<fs::path, 2> out = spellings(output);
  for (const std::string& input : inputs) {
    // An input that is not there is refused by its reader, as missing (it was said to be
    // overwritten).
    std::error_code missing;
    if (!fs::exists(fs::symlink_status(input, missing))) continue;
    const std::array<fs::path, 2> in = spellings(input);
    bool same = false;
    for (const fs::path& o : out) {
      std::error_code ec;
      same = same || o == in[0] || o == in[1] || (fs::exists(o, ec) && fs::equivalent(o, input, ec));
    }
    if (same) throw UserError(where, "'" + output + "' is the input file '" + input + "'; refusing to overwrite it");
  }
}

fs::path file_written_at(const fs::path& requested) {
  std::error_code ec;
  fs::path path = requested;
  for (int hops = 0; fs::is_symlink(path, ec); ++hops) {
    if (hops == 40) throw UserError(requested.string(), "too many levels of symbolic links");
    const fs::path target = fs::read_symlink(path, ec);
    if (ec) throw UserError(requested.string(), "cannot read the symbolic link: " + ec.message());
    path = target.is_absolute() ? target : path.parent_path() / target;
  }
  return path;
}

void refuse_shared_outputs(const std::vector<std::pair<std::string, std::string>>& outputs) {
  struct Output {
    const std::string *where, *path;
    fs::path written;
    std::array<fs::path, 2> spelt;
  };
  std::vector<Output> seen;
  for (const auto& [where, path] : outputs) {
    if (path.empty()) continue;
    Output o{&where, &path, file_written_at(path), {}};
    o.spelt = spellings(o.written.string());
    for (const Output& other : seen) {
      std::error_code ec;
      bool same = fs::exists(o.written, ec) && fs::exists(other.written, ec) && fs::equivalent(o.written, other.written, ec);
      for (const fs::path& a : o.spelt)
        for (const fs::path& b : other.spelt) same = same || a == b;
      if (same)
        throw UserError(where, "'" + path + "' is the same file as " + *other.where + " '" + *other.path +
                                   "'; give each output its own file");
    }
    seen.push_back(std::move(o));
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
    probe_writable(path, path, where);
    return;
  }
  check_writable_ancestor(path, where);
}

std::string file_name_part(const std::string& name, size_t most) {
  std::string out;
  for (const char c : name.substr(0, most)) {
    const bool plain = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' ||
                       c == '_' || (c == '.' && !out.empty());
    out += plain ? c : '_';
  }
  return out.empty() ? "_" : out;
}

}  // namespace radrecon
