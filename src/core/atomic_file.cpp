#include "core/atomic_file.h"

#include <fstream>
#include <system_error>
#include <unistd.h>

#include "core/error.h"

namespace radrecon {

void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(const std::filesystem::path&)>& write) {
  namespace fs = std::filesystem;
  std::error_code ec;
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
  write_file_atomically(path, [&](const std::filesystem::path& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    out << text;
    out.close();
    if (!out) throw UserError(path.string(), "cannot write");
  });
}

}  // namespace radrecon
