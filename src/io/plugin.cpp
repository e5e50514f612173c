#include "io/plugin.h"

#include <dlfcn.h>

#include <algorithm>
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
  void (*set_limit)(int, long long) = nullptr;  ///< into the plugin's own copy of the limits
  std::string failure;
};

Loaded load(const PluginSpec& plugin) {
  namespace fs = std::filesystem;
  Loaded out;
  const auto fail = [&](const std::string& why) { out.failure += (out.failure.empty() ? "" : "; ") + why; };
  std::vector<fs::path> candidates;
  std::error_code ec;
  if (const char* env = std::getenv(plugin.env); env && *env) {
    if (fs::exists(env, ec)) candidates.emplace_back(env);
    else fail(std::string("$") + plugin.env + " names " + env + ", which does not exist");
  }
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
  std::vector<fs::path> tried;  // the executable's folder is also the code's, outside Python
  for (const fs::path& c : candidates) {
    if (!fs::exists(c, ec)) continue;
    const fs::path canonical = fs::weakly_canonical(c, ec);
    if (std::find(tried.begin(), tried.end(), canonical) != tried.end()) continue;
    tried.push_back(canonical);
    // Lazy binding: resolving every symbol of GDAL's libraries up front cost 20 ms.
    void* handle = dlopen(c.c_str(), RTLD_LAZY | RTLD_LOCAL);
    if (handle == nullptr) {
      fail(dlerror());
      continue;
    }
    // A plugin of another build (an installed one, a stale one) passes other types: refused.
    using Abi = int (*)();
    using Entry = const void* (*)();
    const auto abi = reinterpret_cast<Abi>(dlsym(handle, kPluginAbiEntry));
    const auto entry = reinterpret_cast<Entry>(dlsym(handle, plugin.entry));
    const auto set_limit = reinterpret_cast<void (*)(int, long long)>(dlsym(handle, kPluginSetLimit));
    if (abi == nullptr || entry == nullptr || set_limit == nullptr || abi() != kPluginAbi) {
      fail(c.string() + (abi != nullptr && entry != nullptr && set_limit != nullptr
                             ? " is of another radrecon version (interface " + std::to_string(abi()) + ", this is " +
                                   std::to_string(kPluginAbi) + ")"
                             : std::string(" is no radrecon plugin (it lacks ") + plugin.entry + ", " +
                                   kPluginAbiEntry + " or " + kPluginSetLimit + ")"));
      dlclose(handle);
      continue;
    }
    out.table = entry();
    out.set_limit = set_limit;
    return out;
  }
  if (out.failure.empty())
    fail(std::string(plugin.file) +
         " is neither beside the executable (or in ../lib/radrecon) nor beside the Python module; it is built "
         "with radrecon");
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
  for (const Limit limit : kAllLimits) result.set_limit(static_cast<int>(limit), limit_value(limit));
  return result.table;
}

}  // namespace radrecon

