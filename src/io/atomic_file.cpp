#include "io/atomic_file.h"

#include <fstream>
#include <system_error>
#include <unistd.h>

#include "core/error.h"

namespace radrecon {

void write_file_atomically(const std::filesystem::path& requested,
                           const std::function<void(const std::filesystem::path&)>& write) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::path path = requested;
  // Replace only regular files: never a folder, device or pipe; through a symlink, its target.
  for (int hops = 0; fs::is_symlink(path, ec); ++hops) {
    if (hops == 40) throw UserError(requested.string(), "too many levels of symbolic links");
    const fs::path target = fs::read_symlink(path, ec);
    if (ec) throw UserError(requested.string(), "cannot read the symbolic link: " + ec.message());
    path = target.is_absolute() ? target : path.parent_path() / target;
  }
  const fs::file_status status = fs::status(path, ec);
  if (fs::exists(status) && !fs::is_regular_file(status))
    throw UserError(requested.string(), fs::is_directory(status) ? "is a folder, not a file"
                                                                  : "is not a regular file; refusing to replace it");
  if (path.has_parent_path()) {
    fs::create_directories(path.parent_path(), ec);
    if (ec) throw UserError(path.parent_path().string(), "cannot create folder: " + ec.message());
  }
  fs::path tmp = path;
  tmp += ".tmp" + std::to_string(::getpid());
  try {
    write(tmp);
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw UserError(path.string(), "cannot write: " + ec.message());
  }
}

void write_text_file(const std::filesystem::path& path, const std::string& text) {
  write_binary_file(path, {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()});
}

void write_binary_file(const std::filesystem::path& path, std::span<const std::uint8_t> bytes) {
  write_file_atomically(path, [&](const std::filesystem::path& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    out.close();  // the last bytes are flushed here: a full disk shows now
    if (!out) throw UserError(path.string(), "cannot write");
  });
}

}  // namespace radrecon
