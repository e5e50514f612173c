// A picture as `radrecon compare` reads it (io/image_read.h: read_picture): PFM by our own
// parser, PNG through libpng and its error jumps. One harness per format, this source compiled
// with RADRECON_FUZZ_EXTENSION set to ".pfm" or ".png" (fuzz/CMakeLists.txt): the extension
// chooses the reader. (OpenEXR files are read by OpenEXR's own library, in a plugin.)
#include "fuzz_input.h"
#include "io/image_read.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = radrecon::fuzz::input_file(data, size, RADRECON_FUZZ_EXTENSION);
  radrecon::fuzz::expect_success_or_refusal([&] { radrecon::read_picture(path, "fuzz"); });
  return 0;
}
