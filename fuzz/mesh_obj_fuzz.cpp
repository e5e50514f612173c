// A .obj model as a whole scene (io/scene_json.h: load_mesh_scene, through assimp), as
// `radrecon solve model.obj` reads it: import, validation, regularisation.
#include "fuzz_input.h"
#include "io/scene_json.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = radrecon::fuzz::input_file(data, size, ".obj");
  radrecon::fuzz::expect_success_or_refusal([&] { radrecon::load_mesh_scene(path); });
  return 0;
}
