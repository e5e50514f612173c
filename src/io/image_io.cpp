#include "io/image_io.h"

#include <OpenEXR/ImfRgbaFile.h>
#include <png.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <vector>

#include "core/check.h"
#include "core/error.h"
#include "core/parse.h"
#include "io/atomic_file.h"

namespace radrecon {

std::string extension_of(FileFormat format) {
  switch (format) {
    case FileFormat::csv: return ".csv";
    case FileFormat::pfm: return ".pfm";
    case FileFormat::png: return ".png";
    case FileFormat::exr: return ".exr";
  }
  return "";
}

FileFormat file_format(const std::string& path, std::initializer_list<FileFormat> allowed, const std::string& where) {
  const std::string ext = lower_extension(path);
  std::string names;
  for (FileFormat f : allowed) {
    if (ext == extension_of(f)) return f;
    names += (names.empty() ? "" : ", ") + extension_of(f);
  }
  throw UserError(where, (ext.empty() ? std::string("no file extension") : "unknown file extension " + in_quotes(ext)) +
                             " in '" + path + "'; expected " + names);
}

namespace {

/// Display values as 8-bit RGB, row by row (write_png()'s conversion).
std::vector<std::uint8_t> png_bytes(const Image& image, bool srgb_encode_values) {
  std::vector<std::uint8_t> bytes(static_cast<size_t>(image.width()) * image.height() * 3);
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x)
      for (int c = 0; c < 3; ++c) {
        double v = std::clamp(image.at(x, y)[c], 0.0, 1.0);
        if (std::isnan(v)) v = 0.0;
        if (srgb_encode_values) v = srgb_encode(v);
        bytes[(static_cast<size_t>(y) * image.width() + x) * 3 + c] = static_cast<std::uint8_t>(std::lround(v * 255.0));
      }
  return bytes;
}

png_image png_header(const Image& image) {
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  png.width = static_cast<png_uint_32>(image.width());
  png.height = static_cast<png_uint_32>(image.height());
  png.format = PNG_FORMAT_RGB;
  return png;
}

}  // namespace

void write_png(const std::filesystem::path& path, const Image& image, bool srgb_encode_values) {
  const std::vector<std::uint8_t> bytes = png_bytes(image, srgb_encode_values);
  write_file_atomically(path, [&](const std::filesystem::path& tmp) {
    png_image png = png_header(image);
    if (!png_image_write_to_file(&png, tmp.c_str(), 0, bytes.data(), 0, nullptr)) {
      std::string message = png.message;
      png_image_free(&png);
      throw UserError(path.string(), "cannot write PNG: " + message);
    }
  });
}

std::vector<std::uint8_t> encode_png(const Image& image, bool srgb_encode_values) {
  const std::vector<std::uint8_t> bytes = png_bytes(image, srgb_encode_values);
  png_image png = png_header(image);
  png_alloc_size_t size = 0;
  if (!png_image_write_to_memory(&png, nullptr, &size, 0, bytes.data(), 0, nullptr))
    throw UserError("PNG", std::string("cannot encode: ") + png.message);
  std::vector<std::uint8_t> encoded(size);
  if (!png_image_write_to_memory(&png, encoded.data(), &size, 0, bytes.data(), 0, nullptr))
    throw UserError("PNG", std::string("cannot encode: ") + png.message);
  encoded.resize(size);
  return encoded;
}

void write_pfm(const std::filesystem::path& path, int width, int height, int channels,
               std::span<const double> values) {
  RR_CHECK(channels == 1 || channels == 3, "PFM holds 1 or 3 channels");
  RR_CHECK_EQ(values.size(), static_cast<size_t>(width) * height * channels, "PFM values do not match the size");
  for (const double v : values)
    if (std::isfinite(v) && std::abs(v) > std::numeric_limits<float>::max())
      throw UserError(path.string(), "a value, " + format_number(v) +
                                         ", is beyond the range of PFM's 32-bit floats (3.4e38); write .csv instead");
  write_file_atomically(path, [&](const std::filesystem::path& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    // The scale -1.0 declares little-endian floats; they are swapped on a big-endian machine.
    out << (channels == 1 ? "Pf" : "PF") << "\n" << width << " " << height << "\n-1.0\n";
    const size_t row_len = static_cast<size_t>(width) * channels;
    std::vector<std::uint32_t> row(row_len);
    for (int j = 0; j < height; ++j) {
      for (size_t k = 0; k < row_len; ++k) {
        std::uint32_t bits = std::bit_cast<std::uint32_t>(static_cast<float>(values[j * row_len + k]));
        if constexpr (std::endian::native == std::endian::big)
          bits = (bits >> 24) | ((bits >> 8) & 0xff00u) | ((bits << 8) & 0xff0000u) | (bits << 24);
        row[k] = bits;
      }
      out.write(reinterpret_cast<const char*>(row.data()), static_cast<std::streamsize>(row_len * sizeof(std::uint32_t)));
    }
    out.close();
    if (!out) throw UserError(path.string(), "cannot write PFM");
  });
}

void write_pfm(const std::filesystem::path& path, const Image& image) {
  const int W = image.width(), H = image.height();
  std::vector<double> values(static_cast<size_t>(W) * H * 3);
  for (int j = 0; j < H; ++j)  // PFM's row j is the picture's row H - 1 - j
    for (int x = 0; x < W; ++x)
      for (int c = 0; c < 3; ++c) values[(static_cast<size_t>(j) * W + x) * 3 + c] = image.at(x, H - 1 - j)[c];
  write_pfm(path, W, H, 3, values);
}

void write_exr(const std::filesystem::path& path, const Image& image) {
  std::vector<Imf::Rgba> pixels(static_cast<size_t>(image.width()) * image.height());
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) {
      const Rgb& c = image.at(x, y);
      pixels[static_cast<size_t>(y) * image.width() + x] =
          Imf::Rgba(static_cast<float>(c[0]), static_cast<float>(c[1]), static_cast<float>(c[2]), 1.0f);
    }
  write_file_atomically(path, [&](const std::filesystem::path& tmp) {
    try {
      Imf::RgbaOutputFile file(tmp.c_str(), image.width(), image.height(), Imf::WRITE_RGB);
      file.setFrameBuffer(pixels.data(), 1, static_cast<size_t>(image.width()));
      file.writePixels(image.height());
    } catch (const std::bad_alloc&) {
      throw;  // out of memory, not a file problem
    } catch (const std::exception& e) {
      throw UserError(path.string(), std::string("cannot write OpenEXR: ") + e.what());
    }
  });
}

}  // namespace radrecon
