// The assimp plugin's entry point (io/assimp_import.h).

#include "io/assimp_import.h"

extern "C" __attribute__((visibility("default"))) const void* radrecon_assimp_functions() {
  static const radrecon::AssimpFunctions functions{radrecon::import_mesh_assimp};
  return &functions;
}
