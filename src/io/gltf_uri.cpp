#include "io/gltf_uri.h"

#include <filesystem>

namespace radrecon {

std::string percent_decoded(std::string_view uri) {
  const auto hex = [](char c) {
    return c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : c >= 'A' && c <= 'F' ? c - 'A' + 10 : -1;
  };
  std::string out;
  out.reserve(uri.size());
  for (size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size() && hex(uri[i + 1]) >= 0 && hex(uri[i + 2]) >= 0) {
      out += static_cast<char>(16 * hex(uri[i + 1]) + hex(uri[i + 2]));
      i += 2;
    } else {
      out += uri[i];
    }
  }
  return out;
}

std::string gltf_uri_file(const std::string& folder, const std::string& uri) {
  const std::filesystem::path base = folder.empty() ? std::filesystem::path() : std::filesystem::path(folder);
  const std::filesystem::path as_written = base / uri;
  const std::filesystem::path decoded = base / percent_decoded(uri);
  std::error_code ec;
  return (std::filesystem::exists(decoded, ec) || !std::filesystem::exists(as_written, ec) ? decoded : as_written).string();
}

}  // namespace radrecon
