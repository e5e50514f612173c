// A model file as a whole scene (io/scene_json.h: load_mesh_scene, through assimp), as
// `radrecon solve model.EXT` reads it: import, validation, regularisation. One harness per
// format, this source compiled with RADRECON_FUZZ_EXTENSION set to ".obj", ".gltf", ".glb" or
// ".ply" (fuzz/CMakeLists.txt): the extension chooses the reader.
#include "fuzz_input.h"
#include "io/assimp_import.h"
#include "io/scene_json.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  radrecon::set_mesh_importer(radrecon::import_mesh_assimp);  // the reader linked in, instrumented
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = radrecon::fuzz::input_file(data, size, RADRECON_FUZZ_EXTENSION);
  radrecon::fuzz::expect_success_or_refusal([&] { radrecon::load_mesh_scene(path); });
  return 0;
}
