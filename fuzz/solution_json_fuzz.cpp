// Solution JSON (io/solution_json.h), as `radrecon render`, `compare` and `export` read it.
#include "fuzz_input.h"
#include "io/solution_json.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = radrecon::fuzz::input_file(data, size, ".json");
  radrecon::fuzz::expect_success_or_refusal([&] { radrecon::read_solution_json(path); });
  return 0;
}
