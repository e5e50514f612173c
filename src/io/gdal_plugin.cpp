#include "io/gdal_plugin.h"

#include <dlfcn.h>

#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <mutex>

#include "core/error.h"
#include "core/parse.h"

namespace radrecon {

const GdalFunctions& gdal_functions(const std::string& what) {
  static std::once_flag once;
  static const GdalFunctions* functions = nullptr;
  static std::string failure;
  std::call_once(once, [] {
    namespace fs = std::filesystem;
    std::vector<fs::path> candidates;
    if (const char* env = std::getenv("RADRECON_GDAL_PLUGIN"); env && *env) candidates.emplace_back(env);
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (!ec) {
      candidates.push_back(exe.parent_path() / "libradrecon_gdal.so");
      candidates.push_back(exe.parent_path() / ".." / "lib" / "radrecon" / "libradrecon_gdal.so");
    }
    // Beside (or one folder above) the shared object this code is in: the Python module in
    // build/python, or installed beside the plugin.
    Dl_info self{};
    if (dladdr(reinterpret_cast<const void*>(&gdal_functions), &self) != 0 && self.dli_fname != nullptr) {
      const fs::path here = fs::absolute(fs::path(self.dli_fname), ec).parent_path();
      candidates.push_back(here / "libradrecon_gdal.so");
      candidates.push_back(here / ".." / "libradrecon_gdal.so");
    }
    for (const fs::path& c : candidates) {
      if (!fs::exists(c, ec)) continue;
      void* handle = dlopen(c.c_str(), RTLD_NOW | RTLD_LOCAL);
      if (handle == nullptr) {
        failure += std::string(failure.empty() ? "" : "; ") + dlerror();
        continue;
      }
      using Entry = const GdalFunctions* (*)();
      const auto entry = reinterpret_cast<Entry>(dlsym(handle, kGdalPluginEntry));
      if (entry == nullptr) {
        failure += "; " + c.string() + " has no " + kGdalPluginEntry;
        continue;
      }
      functions = entry();
      return;
    }
    if (failure.empty()) failure = "libradrecon_gdal.so is not beside the executable (build it: it comes with radrecon)";
  });
  if (functions == nullptr) throw UserError(what, "needs GDAL support, which cannot be loaded: " + failure);
  return *functions;
}

bool is_ogr_vector_path(const std::string& path) {
  const std::string ext = lower_extension(path);
  return !(ext.empty() || ext == ".csv" || ext == ".txt" || ext == ".xyz" || ext == ".dat" || ext == ".tsv");
}

}  // namespace radrecon
