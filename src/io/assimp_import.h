#pragma once
// The mesh reader behind import_mesh() (io/mesh_import.h), and the plugin libradrecon_assimp.so
// that holds it (io/plugin.h): assimp and the libraries it pulls in are loaded only by a command
// that imports a model.

#include "io/mesh_import.h"

namespace radrecon {

/// import_mesh() as the plugin carries it out (its documentation there), for a path import_mesh()
/// has checked names a model file (mesh_format()).
MeshImport import_mesh_assimp(const std::string& path, const MeshPlacement& placement);

/// The plugin's table of functions.
struct AssimpFunctions {
  MeshImport (*import_mesh)(const std::string& path, const MeshPlacement& placement);
};

/// The name of the symbol the plugin exports: `const void* ()`, the address of its AssimpFunctions.
inline constexpr const char* kAssimpPluginEntry = "radrecon_assimp_functions";

}  // namespace radrecon
