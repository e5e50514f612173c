#include "io/mesh_import.h"

#include <atomic>
#include <cstdio>
#include <filesystem>

#include "core/error.h"
#include "io/assimp_import.h"
#include "io/json_reader.h"
#include "io/plugin.h"

namespace radrecon {

namespace {

std::atomic<MeshImporter> g_importer{nullptr};

}  // namespace

void set_mesh_importer(MeshImporter importer) { g_importer = importer; }

MeshImport import_mesh(const std::string& path, const MeshPlacement& placement) {
  // What needs no reader, before loading it.
  if (!mesh_format(path)) throw UserError(path, "unknown mesh format (expected .obj, .gltf, .glb or .ply)");
  require_regular_file(path, "mesh file");
  if (const MeshImporter importer = g_importer.load()) return importer(path, placement);
  static const PluginSpec kPlugin{"libradrecon_assimp.so", kAssimpPluginEntry, "RADRECON_ASSIMP_PLUGIN",
                                  "the model reader (assimp)"};
  return static_cast<const AssimpFunctions*>(plugin_table(kPlugin, path))->import_mesh(path, placement);
}

void print_warnings(const std::vector<std::string>& warnings, size_t limit) {
  for (size_t i = 0; i < warnings.size() && i < limit; ++i) warn(warnings[i]);
  if (warnings.size() > limit) warn("... and " + std::to_string(warnings.size() - limit) + " more warnings");
}

}  // namespace radrecon
