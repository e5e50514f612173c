// Query CSV (io/samples_csv.h), as `radrecon interpolate --queries` reads it.
#include "fuzz_input.h"
#include "io/samples_csv.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = radrecon::fuzz::input_file(data, size, ".csv");
  radrecon::fuzz::expect_success_or_refusal([&] { radrecon::read_queries_csv(path); });
  return 0;
}
