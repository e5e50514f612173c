// Scene JSON (io/scene_json.h): parsed, validated and regularised as `radrecon solve` does.
#include <string>

#include "fuzz_input.h"
#include "io/scene_json.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // Named as the file in the harness's own folder: a "meshes" entry's relative path resolves
  // there, wherever the fuzzer runs.
  const std::string path = radrecon::fuzz::input_file(data, size, ".json");
  const std::string text(reinterpret_cast<const char*>(data), size);
  radrecon::fuzz::expect_success_or_refusal([&] { radrecon::parse_scene_json(text, path); });
  return 0;
}
