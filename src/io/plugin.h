#pragma once
// Optional libraries as plugins loaded on first use. GDAL (and the hundred libraries it pulls
// in), assimp and OpenEXR would cost every radrecon command their start-up (GDAL ~40 ms, assimp
// ~8 ms, OpenEXR ~5 ms on the 2-core machine) though most commands never touch them, so the code
// that calls them is built into modules beside the executable (libradrecon_gdal.so,
// libradrecon_assimp.so, libradrecon_openexr.so) and loaded by the first call that needs one.

#include <string>

namespace radrecon {

/// A plugin: its file name, the symbol it exports (a function `const void* ()` returning the
/// address of its table of functions, plain C++ signatures: the same compiler and library as
/// the program), the
/// environment variable that may name its path, and what it gives, for messages.
struct PluginSpec {
  const char* file;
  const char* entry;
  const char* env;
  const char* gives;
};

/// The symbols every plugin exports besides its entry (io/plugin_limits.cpp, built into each):
/// - kPluginSetLimit, `void (int, long long)`, takes the program's resource limits (core/limits.h):
///   the plugin links its own copy of that process-wide table, which plugin_table() brings up to
///   date with the program's on every call;
/// - kPluginAbiEntry, `int ()`, returns the kPluginAbi it was built with: a plugin of another
///   interface is refused, not called.
inline constexpr const char* kPluginSetLimit = "radrecon_plugin_set_limit";
inline constexpr const char* kPluginAbiEntry = "radrecon_plugin_abi";
/// The plugins' interface version: raise it whenever a table of functions, or a type they pass
/// (MeshImport, PictureValues, ScatteredSamples, ...), changes.
inline constexpr int kPluginAbi = 8;

/// The plugin's table of functions, loaded on the first call: from $env if set, else `file`
/// in the executable's folder, else in ../lib/radrecon/ from it, else beside (or one folder
/// above) the shared object this code is in (the Python module); the first that loads and has
/// this program's interface. UserError naming `what` (the option or file that needs it), and
/// why each candidate failed, when none does.
const void* plugin_table(const PluginSpec& plugin, const std::string& what);

}  // namespace radrecon
