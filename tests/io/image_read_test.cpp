// Reading pictures: round trips through the writers (image_io.h) and libpng/OpenEXR directly,
// a big-endian PFM made by hand, and broken files refused with the file named.

#include <gtest/gtest.h>
#include <png.h>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "io/image_io.h"
#include "io/image_read.h"
#include "support/temp_dir.h"

namespace radrecon {
namespace image_read_test {

namespace fs = std::filesystem;
using testing_support::user_error_message;

const testing_support::TempDir& files() {
  static const testing_support::TempDir dir("radrecon_image_read_test");
  return dir;
}

/// A 3 x 2 picture with distinct values, exact in half floats (for OpenEXR) and in 8 bits.
Image test_image() {
  Image img(3, 2);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x) img.at(x, y) = Rgb((x + 3 * y) / 255.0 * 16, 0.25 * x, 1.0 - 0.5 * y);
  return img;
}

void expect_same_as(const PictureValues& p, const Image& img, double tol) {
  ASSERT_EQ(p.width, img.width());
  ASSERT_EQ(p.height, img.height());
  ASSERT_EQ(p.channels, 3);
  ASSERT_EQ(p.values.size(), 3u * img.width() * img.height());
  for (int y = 0; y < img.height(); ++y)
    for (int x = 0; x < img.width(); ++x)
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(p.values[(static_cast<size_t>(y) * img.width() + x) * 3 + c], img.at(x, y)[c], tol)
            << "pixel " << x << "," << y << " channel " << c;
}

TEST(ReadPicture, PfmRoundTripKeepsTheTopRowFirst) {
  const Image img = test_image();
  const fs::path path = files() / "rgb.pfm";
  write_pfm(path, img);
  const PictureValues p = read_picture(path, "A");
  EXPECT_EQ(p.format, FileFormat::pfm);
  expect_same_as(p, img, 1e-7);  // 32-bit floats
}

TEST(ReadPicture, GreyPfmRowsComeBottomUpInTheFile) {
  // Stored rows (bottom first): {1, 2}, {3, 4}: the picture's top row is {3, 4}.
  const fs::path path = files() / "grey.pfm";
  write_pfm(path, 2, 2, 1, std::vector<double>{1, 2, 3, 4});
  const PictureValues p = read_picture(path, "A");
  EXPECT_EQ(p.channels, 1);
  EXPECT_EQ(p.values, (std::vector<double>{3, 4, 1, 2}));
}

TEST(ReadPicture, BigEndianPfmByTheSignOfTheScale) {
  // "Pf", 2 x 1, scale +2.0 (big endian; the magnitude does not matter): floats 1.5 and -0.25.
  const fs::path path = files() / "big.pfm";
  {
    std::ofstream out(path, std::ios::binary);
    out << "Pf\n2 1\n2.0\n";
    for (const float f : {1.5f, -0.25f}) {
      std::uint32_t bits;
      std::memcpy(&bits, &f, 4);
      const unsigned char b[4] = {static_cast<unsigned char>(bits >> 24), static_cast<unsigned char>(bits >> 16),
                                  static_cast<unsigned char>(bits >> 8), static_cast<unsigned char>(bits)};
      out.write(reinterpret_cast<const char*>(b), 4);
    }
  }
  const PictureValues p = read_picture(path, "A");
  EXPECT_EQ(p.width, 2);
  EXPECT_EQ(p.height, 1);
  EXPECT_EQ(p.values, (std::vector<double>{1.5, -0.25}));
}

TEST(ReadPicture, PngRoundTripGivesTheStoredValuesOver255) {
  const Image img = test_image();
  const fs::path path = files() / "rgb.png";
  write_png(path, img, false);  // no sRGB curve: the stored bytes are round(255 v)
  const PictureValues p = read_picture(path, "A");
  EXPECT_EQ(p.format, FileFormat::png);
  expect_same_as(p, img, 0.5 / 255 + 1e-12);
}

/// Writes a PNG with libpng's simplified API.
void write_simple_png(const fs::path& path, int width, int height, png_uint_32 format, const void* data) {
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  png.width = width;
  png.height = height;
  png.format = format;
  ASSERT_TRUE(png_image_write_to_file(&png, path.c_str(), 0, data, 0, nullptr)) << png.message;
}

TEST(ReadPicture, SixteenBitGreyAndRgbaPngs) {
  const fs::path grey = files() / "grey16.png", rgba = files() / "rgba.png";
  const std::uint16_t g[3] = {0, 1000, 65535};
  write_simple_png(grey, 3, 1, PNG_FORMAT_LINEAR_Y, g);
  const PictureValues p = read_picture(grey, "A");
  EXPECT_EQ(p.channels, 1);
  ASSERT_EQ(p.values.size(), 3u);
  EXPECT_DOUBLE_EQ(p.values[0], 0.0);
  EXPECT_DOUBLE_EQ(p.values[1], 1000.0 / 65535);
  EXPECT_DOUBLE_EQ(p.values[2], 1.0);
  // RGBA: alpha dropped, colours as stored (not multiplied by alpha).
  const std::uint8_t c[8] = {10, 20, 30, 255, 40, 50, 60, 128};
  write_simple_png(rgba, 2, 1, PNG_FORMAT_RGBA, c);
  const PictureValues q = read_picture(rgba, "A");
  EXPECT_EQ(q.channels, 3);
  EXPECT_EQ(q.values, (std::vector<double>{10 / 255.0, 20 / 255.0, 30 / 255.0, 40 / 255.0, 50 / 255.0, 60 / 255.0}));
}

TEST(ReadPicture, ExrRoundTripOfFloatsKeepsWhatHalfFloatsLose) {
  // 32-bit floats, as PFM: half floats made a lamp of 1e5 W/m^2 infinity (exit 0; a review) and
  // 1e-9 zero. Every value comes back as its float.
  Image img = test_image();
  img.at(0, 0) = Rgb(1e5, 2.5e30, 3);
  img.at(1, 0) = Rgb(1e-9, 65504.0 * 1.5, -7.25);
  const fs::path path = files() / "rgb.exr";
  write_exr(path, img);
  const PictureValues p = read_picture(path, "A");
  EXPECT_EQ(p.format, FileFormat::exr);
  ASSERT_EQ(p.values.size(), static_cast<size_t>(img.width()) * img.height() * 3);
  for (int y = 0; y < img.height(); ++y)
    for (int x = 0; x < img.width(); ++x)
      for (int c = 0; c < 3; ++c)
        EXPECT_EQ(p.values[(static_cast<size_t>(y) * img.width() + x) * 3 + c], static_cast<float>(img.at(x, y)[c]))
            << x << ", " << y << ", channel " << c;
  // Beyond a float's range: refused, naming the file, nothing written.
  img.at(0, 0) = Rgb(1e39, 0, 0);
  const fs::path huge = files() / "huge.exr";
  try {
    write_exr(huge, img);
    ADD_FAILURE() << "1e39 written";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("beyond the range of OpenEXR's 32-bit floats"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(huge));
}

TEST(ReadPicture, ExrWithALuminanceChannelOnly) {
  const fs::path path = files() / "y.exr";
  const float y[4] = {0.5f, 1.0f, 2.0f, 4.0f};  // 2 x 2, top row first
  {
    Imf::Header header(2, 2);
    header.channels().insert("Y", Imf::Channel(Imf::FLOAT));
    Imf::OutputFile out(path.c_str(), header);
    Imf::FrameBuffer frame;
    frame.insert("Y", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(const_cast<float*>(y)), sizeof(float), 2 * sizeof(float)));
    out.setFrameBuffer(frame);
    out.writePixels(2);
  }
  const PictureValues p = read_picture(path, "A");
  EXPECT_EQ(p.channels, 1);
  EXPECT_EQ(p.values, (std::vector<double>{0.5, 1, 2, 4}));
}

void write_bytes(const fs::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out << bytes;
}

std::string file_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

TEST(ReadPicture, RefusesBrokenFilesNamingThem) {
  const Image img = test_image();
  write_pfm(files() / "good.pfm", img);
  write_png(files() / "good.png", img, false);
  write_exr(files() / "good.exr", img);
  const std::string pfm = file_bytes(files() / "good.pfm"), png = file_bytes(files() / "good.png"),
                    exr = file_bytes(files() / "good.exr");
  struct Case {
    std::string name, bytes, expect;
  };
  const std::vector<Case> cases = {
      {"short.pfm", pfm.substr(0, pfm.size() - 5), "truncated"},
      {"long.pfm", pfm + "xx", "extra data"},
      {"text.pfm", "hello world\n", "not a PFM file"},
      {"size.pfm", "PF\n-3 2\n-1.0\n", "at least 1"},
      {"scale.pfm", "PF\n3 2\nabc\n", "scale"},
      {"empty.pfm", "", "not a PFM file"},
      {"short.png", png.substr(0, png.size() / 2), "cannot read PNG"},
      {"text.png", "hello world, not a png", "not a PNG file"},
      {"short.exr", exr.substr(0, exr.size() / 2), "OpenEXR"},
      {"text.exr", "hello world, not an exr", "cannot read OpenEXR"},
  };
  for (const Case& c : cases) {
    const fs::path path = files() / c.name;
    write_bytes(path, c.bytes);
    const std::string message = user_error_message([&] { read_picture(path, "A"); });
    EXPECT_NE(message.find(path.string()), std::string::npos) << c.name << ": " << message;
    EXPECT_NE(message.find(c.expect), std::string::npos) << c.name << ": " << message;
  }
  EXPECT_NE(user_error_message([&] { read_picture(files() / "missing.pfm", "A"); }).find("cannot open"), std::string::npos);
  EXPECT_NE(user_error_message([&] { read_picture(files() / "x.tif", "A"); }).find(".pfm"), std::string::npos);
}

}  // namespace image_read_test
}  // namespace radrecon
