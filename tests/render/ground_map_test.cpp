// The pictures: tone mappings by their definitions, the orientation of the maps, and the PNG
// and PFM writers read back byte by byte.

#include <gtest/gtest.h>

#include <png.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "core/image.h"
#include "io/image_io.h"
#include "render/ground_map.h"

namespace radrecon {
namespace ground_map_test {

namespace fs = std::filesystem;

// The mappings are one division and one addition: exact to an ulp or two.
constexpr double kExact = 1e-15;

class RenderFiles : public testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("radrecon_render_test_" + std::to_string(::getpid()) + "_" +
            testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  fs::path dir_;
};

/// Reads a PNG as 8-bit RGB with libpng's simplified API.
std::vector<std::uint8_t> ReadPngRgb(const fs::path& path, int& width, int& height) {
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&image, path.c_str())) {
    ADD_FAILURE() << "cannot read " << path << ": " << image.message;
    return {};
  }
  image.format = PNG_FORMAT_RGB;
  std::vector<std::uint8_t> bytes(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, bytes.data(), 0, nullptr)) {
    ADD_FAILURE() << "cannot decode " << path << ": " << image.message;
    png_image_free(&image);
    return {};
  }
  width = static_cast<int>(image.width);
  height = static_cast<int>(image.height);
  return bytes;
}

TEST(ToneMapping, DifferenceToneByDefinition) {
  const double white = 8.0;
  EXPECT_NEAR(difference_tone(0.0, white), 0.5, kExact);           // zero error is mid-grey
  EXPECT_NEAR(difference_tone(white / 4, white), 1.0, kExact);     // +white/4 reaches white
  EXPECT_NEAR(difference_tone(-white / 4, white), 0.0, kExact);    // -white/4 reaches black
  EXPECT_NEAR(difference_tone(white / 8, white), 0.75, kExact);    // linear in between
  EXPECT_NEAR(difference_tone(-white / 16, white), 0.375, kExact);
  EXPECT_EQ(difference_tone(10 * white, white), 1.0);              // clamped
  EXPECT_EQ(difference_tone(-10 * white, white), 0.0);
}

TEST(ToneMapping, RadiosityToneByDefinition) {
  const double white = 12.5;
  EXPECT_NEAR(tone_map(white, white), 1.0, kExact);
  EXPECT_NEAR(tone_map(0.0, white), 0.0, kExact);
  EXPECT_NEAR(tone_map(white / 4, white), 0.25, kExact);
  EXPECT_EQ(tone_map(3 * white, white), 1.0);  // clamped above
  EXPECT_EQ(tone_map(-1.0, white), 0.0);       // and below
}

TEST(GroundMap, RowZeroIsTheBottomImageRow) {
  // 2 x 3 samples; sample (i, j) has value 1 + i + 2 j in every channel, white = 10.
  const int w = 2, h = 3;
  const double white = 10.0;
  std::vector<double> values;
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i)
      for (int c = 0; c < 3; ++c) values.push_back(1.0 + i + 2 * j + 0.1 * c);
  const Image img = radiosity_map(values, w, h, white);
  ASSERT_EQ(img.width(), w);
  ASSERT_EQ(img.height(), h);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i)
      for (int c = 0; c < 3; ++c)
        // v = 0 (j = 0) at the bottom image row (y = h - 1); u to the right.
        EXPECT_NEAR(img.at(i, h - 1 - j)[c], (1.0 + i + 2 * j + 0.1 * c) / white, kExact)
            << "sample " << i << "," << j << " channel " << c;
}

TEST(GroundMap, DifferenceMapRowOrderAndValues) {
  const int w = 1, h = 2;
  const double white = 4.0;
  // Sample row 0 (v = 0): error +0.5 -> 0.5 + 2 * 0.5 / 4 = 0.75; row 1: error -1 -> 0.
  const std::vector<double> approx = {1.5, 1.5, 1.5, 0, 0, 0}, reference = {1, 1, 1, 1, 1, 1};
  const Image img = difference_map(approx, reference, w, h, white);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(img.at(0, 1)[c], 0.75, kExact);  // bottom row: v = 0
    EXPECT_NEAR(img.at(0, 0)[c], 0.0, kExact);   // top row: v = 1
  }
}

TEST_F(RenderFiles, ZeroDifferenceIsByte128InThePng) {
  const int w = 3, h = 2;
  const std::vector<double> v(static_cast<size_t>(w) * h * 3, 7.0);
  const Image img = difference_map(v, v, w, h, 5.0);
  const fs::path path = dir_ / "diff.png";
  write_png(path, img, /*srgb_encode=*/false);
  int rw = 0, rh = 0;
  const std::vector<std::uint8_t> bytes = ReadPngRgb(path, rw, rh);
  ASSERT_EQ(rw, w);
  ASSERT_EQ(rh, h);
  ASSERT_EQ(bytes.size(), static_cast<size_t>(w) * h * 3);
  for (std::uint8_t b : bytes) EXPECT_EQ(b, 128);  // round(0.5 * 255) = round(127.5) = 128
}

}  // namespace ground_map_test
}  // namespace radrecon
