#pragma once
// PNG files decoded by libpng's simplified API for tests: an independent reader of what
// radrecon writes (8-bit RGB, row 0 the top row).

#include <gtest/gtest.h>
#include <png.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <vector>

namespace radrecon::testing_support {

struct Png {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  ///< row 0 = top
  std::array<int, 3> at(int x, int y) const {
    const size_t k = (static_cast<size_t>(y) * width + x) * 3;
    return {rgb[k], rgb[k + 1], rgb[k + 2]};
  }
};

/// Decodes a PNG begun by png_image_begin_read_from_file or _from_memory (`begun`: whether that
/// succeeded); failures are test failures.
inline Png finish_png(png_image& image, bool begun) {
  EXPECT_TRUE(begun) << image.message;
  Png out;
  if (!begun) return out;
  image.format = PNG_FORMAT_RGB;
  out.width = static_cast<int>(image.width);
  out.height = static_cast<int>(image.height);
  out.rgb.resize(PNG_IMAGE_SIZE(image));
  EXPECT_TRUE(png_image_finish_read(&image, nullptr, out.rgb.data(), 0, nullptr)) << image.message;
  return out;
}

inline Png read_png(const std::filesystem::path& path) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  const bool begun = png_image_begin_read_from_file(&image, path.c_str()) != 0;
  return finish_png(image, begun);
}

inline Png decode_png(const std::uint8_t* data, size_t size) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  const bool begun = png_image_begin_read_from_memory(&image, data, size) != 0;
  return finish_png(image, begun);
}

}  // namespace radrecon::testing_support
