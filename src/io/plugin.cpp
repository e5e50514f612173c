#include "io/plugin.h"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <mutex>
#include <vector>

#include "core/error.h"
#include "core/limits.h"

namespace radrecon {

namespace {

struct Loaded {
  const void* table = nullptr;
  void (*set_limit)(int, long long) = nullptr;  ///< the plugin's own copy of the limits
  std::string failure;
};

Loaded load(const PluginSpec& plugin) {
  namespace fs = std::filesystem;
  std::vector<fs::path> candidates;
  if (const char* env = std::getenv(plugin.env); env && *env) candidates.emplace_back(env);
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    candidates.push_back(exe.parent_path() / plugin.file);
    candidates.push_back(exe.parent_path() / ".." / "lib" / "radrecon" / plugin.file);
  }
  Dl_info self{};
  if (dladdr(reinterpret_cast<const void*>(&plugin_table), &self) != 0 && self.dli_fname != nullptr) {
    const fs::path here = fs::absolute(fs::path(self.dli_fname), ec).parent_path();
    candidates.push_back(here / plugin.file);
    candidates.push_back(here / ".." / plugin.file);
  }
  Loaded out;
  for (const fs::path& c : candidates) {
    if (!fs::exists(c, ec)) continue;
    // Lazy binding: resolving every symbol of GDAL's libraries up front cost 20 ms.
    void* handle = dlopen(c.c_str(), RTLD_LAZY | RTLD_LOCAL);
    if (handle == nullptr) {
      out.failure += std::string(out.failure.empty() ? "" : "; ") + dlerror();
      continue;
    }
    using Entry = const void* (*)();
    const auto entry = reinterpret_cast<Entry>(dlsym(handle, plugin.entry));
    if (entry == nullptr) {
      out.failure += std::string(out.failure.empty() ? "" : "; ") + c.string() + " has no " + plugin.entry;
      continue;
    }
    out.table = entry();
    out.set_limit = reinterpret_cast<void (*)(int, long long)>(dlsym(handle, kPluginSetLimit));
    return out;
  }
  if (out.failure.empty())
    out.failure = std::string(plugin.file) + " is not beside the executable (build it: it comes with radrecon)";
  return out;
}

}  // namespace

const void* plugin_table(const PluginSpec& plugin, const std::string& what) {
  static std::mutex mutex;
  static std::map<std::string, Loaded> loaded;  // by file name; each tried once
  Loaded result;
  {
    const std::lock_guard<std::mutex> lock(mutex);
    auto it = loaded.find(plugin.file);
    if (it == loaded.end()) it = loaded.emplace(plugin.file, load(plugin)).first;
    result = it->second;
  }
  if (result.table == nullptr)
    throw UserError(what, std::string("needs ") + plugin.gives + ", which cannot be loaded: " + result.failure);
  if (result.set_limit != nullptr)
    for (const Limit limit : kAllLimits) result.set_limit(static_cast<int>(limit), limit_value(limit));
  return result.table;
}

}  // namespace radrecon

