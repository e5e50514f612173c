// The image writers checked for content, read back with libpng and by hand (PFM): orientation,
// the min/max mapping of rasters, NaN, byte order.

#include <gtest/gtest.h>
#include <png.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/image.h"
#include "io/image_io.h"
#include "io/raster.h"
#include "support/temp_dir.h"
#include "support/png_decode.h"

namespace radrecon {
namespace image_io_test {

namespace fs = std::filesystem;

/// Every test's files, removed at the end of the run.
const testing_support::TempDir& files() {
  static const testing_support::TempDir dir("radrecon_image_io_test");
  return dir;
}

fs::path temp_file(const std::string& name) { return files() / name; }

using testing_support::Png;
using testing_support::read_png;

TEST(Png, WritesImageRowsTopFirstWithSrgbOrLinearValues) {
  Image img(3, 2);
  img.at(0, 0) = Rgb(1, 0, 0);    // top left: red
  img.at(2, 1) = Rgb(0, 0, 1);    // bottom right: blue
  img.at(1, 0) = Rgb(0.5, 0.5, 0.5);
  img.at(1, 1) = Rgb(std::numeric_limits<double>::quiet_NaN(), 2.0, -1.0);  // NaN black, clamped
  const fs::path linear = temp_file("linear.png"), srgb = temp_file("srgb.png");
  write_png(linear, img, false);
  write_png(srgb, img, true);
  const Png a = read_png(linear), b = read_png(srgb);
  ASSERT_EQ(a.width, 3);
  ASSERT_EQ(a.height, 2);
  EXPECT_EQ(a.at(0, 0), (std::array<int, 3>{255, 0, 0}));
  EXPECT_EQ(a.at(2, 1), (std::array<int, 3>{0, 0, 255}));
  EXPECT_EQ(a.at(1, 0), (std::array<int, 3>{128, 128, 128}));  // round(0.5 * 255)
  EXPECT_EQ(a.at(1, 1), (std::array<int, 3>{0, 255, 0}));
  // sRGB of 0.5 is 0.7354: 188 (IEC 61966-2-1).
  EXPECT_EQ(b.at(1, 0), (std::array<int, 3>{188, 188, 188}));
}

TEST(Png, SrgbCodesAreTheTransferCurveRounded) {
  // 120,000 values over [0, 1], finer near 0 where the curve is steep, and the codes' borders
  // from either side: each byte against lround(255 srgb_encode(v)) (IEC 61966-2-1's curve).
  std::vector<double> values;
  for (int k = 0; k < 100000; ++k) values.push_back(k / 99999.0);
  for (int k = 0; k < 20000; ++k) values.push_back(std::pow(k / 19999.0, 4.0));
  for (int code = 1; code < 256; ++code) {
    double lo = 0, hi = 1;  // the border of `code`, by bisection on the formula
    while (std::nextafter(lo, 1.0) < hi) {
      const double mid = 0.5 * (lo + hi);
      (std::lround(255.0 * srgb_encode(mid)) >= code ? hi : lo) = mid;
    }
    values.push_back(lo);
    values.push_back(hi);
  }
  const int width = 1000, height = static_cast<int>((values.size() + width - 1) / width);
  Image img(width, height);
  for (size_t k = 0; k < values.size(); ++k) img.at(static_cast<int>(k % width), static_cast<int>(k / width)) = Rgb::Constant(values[k]);
  const fs::path path = temp_file("srgb_codes.png");
  write_png(path, img, true);
  const Png png = read_png(path);
  int wrong = 0;
  for (size_t k = 0; k < values.size(); ++k) {
    const int expected = static_cast<int>(std::lround(255.0 * srgb_encode(values[k])));
    wrong += png.at(static_cast<int>(k % width), static_cast<int>(k / width))[1] != expected ? 1 : 0;
  }
  EXPECT_EQ(wrong, 0);
}

TEST(RasterPng, ShowsYUpwardAndMapsMinToBlackMaxToWhiteNanBlack) {
  // A 2 x 2 raster over [0,2]^2, one channel: row y0 (bottom) = {0, 1}, row y1 (top) = {NaN, 4}.
  Raster r;
  r.width = 2;
  r.height = 2;
  r.domain = {0, 0, 2, 2};
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<double> values = {0, 1, nan, 4};
  const fs::path path = temp_file("raster.png");
  write_raster_png(path.string(), r, values, 1);
  const Png p = read_png(path);
  EXPECT_EQ(p.at(0, 1), (std::array<int, 3>{0, 0, 0}));        // min, bottom left
  EXPECT_EQ(p.at(1, 0), (std::array<int, 3>{255, 255, 255}));  // max, top right
  EXPECT_EQ(p.at(0, 0), (std::array<int, 3>{0, 0, 0}));        // NaN
  // 1 of [0, 4]: linear 0.25, sRGB-encoded 0.5371 -> 137.
  EXPECT_EQ(p.at(1, 1), (std::array<int, 3>{137, 137, 137}));
}

TEST(RasterPng, ValuesThatDifferByRoundingOnlyAreShownFlat) {
  // An interpolant of constant data rounds to within a few units in the last place of it: one
  // grey (display 0.5, sRGB 188), not black-and-white speckle; a difference of 1e-6 of the
  // values is still stretched from black to white.
  Raster r;
  r.width = 3;
  r.height = 1;
  r.domain = {0, 0, 3, 1};
  const fs::path path = temp_file("flat.png");
  write_raster_png(path.string(), r, std::vector<double>{5, std::nextafter(5.0, 0.0), std::nextafter(5.0, 6.0)}, 1);
  const Png flat = read_png(path);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(flat.at(i, 0), (std::array<int, 3>{188, 188, 188})) << "pixel " << i;
  write_raster_png(path.string(), r, std::vector<double>{5, 5 * (1 - 1e-6), 5 * (1 + 1e-6)}, 1);
  const Png varied = read_png(path);
  EXPECT_EQ(varied.at(1, 0), (std::array<int, 3>{0, 0, 0}));
  EXPECT_EQ(varied.at(2, 0), (std::array<int, 3>{255, 255, 255}));
}

/// The floats of a little-endian PFM after its header (checked: magic, size, scale), decoded by
/// hand.
std::vector<float> pfm_floats(const fs::path& path, const std::string& magic_expected, int width, int height) {
  std::ifstream in(path, std::ios::binary);
  std::string magic, scale;
  int w = 0, h = 0;
  in >> magic >> w >> h >> scale;
  in.get();
  EXPECT_EQ(magic, magic_expected);
  EXPECT_EQ(w, width);
  EXPECT_EQ(h, height);
  EXPECT_EQ(scale, "-1.0");
  std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::vector<float> floats(bytes.size() / 4);
  for (size_t k = 0; k < floats.size(); ++k) {
    const std::uint32_t bits = std::uint32_t(bytes[k * 4]) | std::uint32_t(bytes[k * 4 + 1]) << 8 |
                               std::uint32_t(bytes[k * 4 + 2]) << 16 | std::uint32_t(bytes[k * 4 + 3]) << 24;
    std::memcpy(&floats[k], &bits, 4);
  }
  return floats;
}

TEST(Pfm, WritesLittleEndianFloatsBottomRowFirst) {
  Image img(2, 2);
  img.at(0, 0) = Rgb(1, 2, 3);  // top row
  img.at(1, 1) = Rgb(-0.5, 0.25, 8);  // bottom row
  const fs::path path = temp_file("image.pfm");
  write_pfm(path, img);
  const std::vector<float> floats = pfm_floats(path, "PF", 2, 2);  // scale -1.0: little endian
  ASSERT_EQ(floats.size(), 2u * 2 * 3);
  // First stored row = bottom row of the picture: pixel (0, 1) then (1, 1).
  EXPECT_EQ(floats[3], -0.5f);
  EXPECT_EQ(floats[4], 0.25f);
  EXPECT_EQ(floats[5], 8.0f);
  // Second stored row = top row: pixel (0, 0).
  EXPECT_EQ(floats[6], 1.0f);
  EXPECT_EQ(floats[8], 3.0f);
}

TEST(Pfm, StreamedValuesComeInOrderWhateverTheBatch) {
  // 7 x 5 x 3 = 105 values, value k = k / 8 (exact in floats), asked for in batches of 1, 16
  // (not dividing 105), 105 and more: every value once, in order.
  for (const size_t batch : {size_t{1}, size_t{16}, size_t{105}, size_t{1000}}) {
    const fs::path path = temp_file("streamed.pfm");
    std::vector<size_t> firsts;
    write_pfm(path, 7, 5, 3, batch, [&](size_t first, std::span<double> out) {
      firsts.push_back(first);
      EXPECT_LE(out.size(), batch);
      for (size_t k = 0; k < out.size(); ++k) out[k] = static_cast<double>(first + k) / 8;
    });
    const std::vector<float> floats = pfm_floats(path, "PF", 7, 5);
    ASSERT_EQ(floats.size(), 105u) << "batch " << batch;
    for (size_t k = 0; k < floats.size(); ++k) EXPECT_EQ(floats[k], static_cast<float>(k) / 8) << "value " << k;
    EXPECT_EQ(firsts.size(), (105 + batch - 1) / batch);
  }
}

TEST(Pfm, AFailedOrOutOfRangeBatchLeavesNoFile) {
  const fs::path path = temp_file("failed.pfm");
  fs::remove(path);
  // Ones, but the batch starting at value `at` throws (`fail`) or holds `bad` first.
  const auto ones_but = [](size_t at, bool fail, double bad) {
    return [=](size_t first, std::span<double> out) {
      for (double& v : out) v = 1;
      if (first != at) return;
      if (fail) throw UserError("test", "a failed batch");
      out[0] = bad;
    };
  };
  EXPECT_THROW(write_pfm(path, 4, 4, 1, 4, ones_but(8, true, 0)), UserError);
  EXPECT_FALSE(fs::exists(path));
  EXPECT_THROW(write_pfm(path, 4, 4, 1, 4, ones_but(12, false, 1e39)), UserError);  // beyond float's range
  EXPECT_FALSE(fs::exists(path));
  for (const fs::directory_entry& e : fs::directory_iterator(files().path()))
    EXPECT_EQ(e.path().filename().string().find("failed.pfm.tmp"), std::string::npos) << e.path();
}

TEST(Pfm, AnImageOfSeveralBatchesIsWrittenBottomRowFirst) {
  // 200 x 120 x 3 = 72,000 values: more than one of the writer's batches (65,536).
  Image img(200, 120);
  for (int y = 0; y < 120; ++y)
    for (int x = 0; x < 200; ++x) img.at(x, y) = Rgb(x, y, 0.5 * (x + y));  // exact in floats
  const fs::path path = temp_file("big_image.pfm");
  write_pfm(path, img);
  const std::vector<float> floats = pfm_floats(path, "PF", 200, 120);
  ASSERT_EQ(floats.size(), 72000u);
  for (int j = 0; j < 120; ++j)  // stored row j is the picture's row 119 - j
    for (int x = 0; x < 200; ++x) {
      const size_t k = (static_cast<size_t>(j) * 200 + x) * 3;
      ASSERT_EQ(floats[k], static_cast<float>(x));
      ASSERT_EQ(floats[k + 1], static_cast<float>(119 - j));
      ASSERT_EQ(floats[k + 2], static_cast<float>(0.5 * (x + 119 - j)));
    }
}

TEST(FileFormat, ChoosesByExtensionInAnyCaseAndRefusesOthers) {
  EXPECT_EQ(file_format("a/b.PNG", {FileFormat::png, FileFormat::exr}, "--out"), FileFormat::png);
  EXPECT_EQ(file_format("x.exr", {FileFormat::png, FileFormat::exr}, "--out"), FileFormat::exr);
  try {
    file_format("x.tif", {FileFormat::png, FileFormat::pfm}, "--out");
    FAIL() << "accepted .tif";
  } catch (const UserError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("--out"), std::string::npos) << what;
    EXPECT_NE(what.find(".png, .pfm"), std::string::npos) << what;
  }
  EXPECT_THROW(file_format("noext", {FileFormat::csv}, "--out"), UserError);
}

}  // namespace image_io_test
}  // namespace radrecon
