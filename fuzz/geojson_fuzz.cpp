// GeoJSON barriers (io/geojson.h), and the barrier set built from them as `--barriers` does.
#include "fuzz_input.h"
#include "io/geojson.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = radrecon::fuzz::input_file(data, size, ".geojson");
  radrecon::fuzz::expect_success_or_refusal([&] { radrecon::read_barriers_file(path, "--barriers"); });
  return 0;
}
