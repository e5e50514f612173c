#include "core/image.h"

#include <OpenEXR/ImfRgbaFile.h>
#include <png.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>

#include "core/atomic_file.h"
#include "core/check.h"
#include "core/error.h"

namespace radrecon {

Image::Image(int width, int height)
    : width_(width), height_(height),
      pixels_(static_cast<size_t>(width) * height, Rgb::Zero()) {
  RR_CHECK(width > 0 && height > 0, "image size must be positive");
}

double srgb_encode(double linear) {
  return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

void write_png(const std::filesystem::path& path, const Image& image, bool srgb_encode_values) {
  std::vector<std::uint8_t> bytes(static_cast<size_t>(image.width()) * image.height() * 3);
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x)
      for (int c = 0; c < 3; ++c) {
        double v = std::clamp(image.at(x, y)[c], 0.0, 1.0);
        if (std::isnan(v)) v = 0.0;
        if (srgb_encode_values) v = srgb_encode(v);
        bytes[(static_cast<size_t>(y) * image.width() + x) * 3 + c] =
            static_cast<std::uint8_t>(std::lround(v * 255.0));
      }
  write_file_atomically(path, [&](const std::filesystem::path& tmp) {
    png_image png{};
    png.version = PNG_IMAGE_VERSION;
    png.width = static_cast<png_uint_32>(image.width());
    png.height = static_cast<png_uint_32>(image.height());
    png.format = PNG_FORMAT_RGB;
    if (!png_image_write_to_file(&png, tmp.c_str(), 0, bytes.data(), 0, nullptr)) {
      std::string message = png.message;
      png_image_free(&png);
      throw UserError(path.string(), "cannot write PNG: " + message);
    }
  });
}

void write_pfm(const std::filesystem::path& path, const Image& image) {
  write_file_atomically(path, [&](const std::filesystem::path& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    out << "PF\n" << image.width() << " " << image.height() << "\n-1.0\n";  // little endian
    std::vector<float> row(static_cast<size_t>(image.width()) * 3);
    for (int y = image.height() - 1; y >= 0; --y) {
      for (int x = 0; x < image.width(); ++x)
        for (int c = 0; c < 3; ++c) row[static_cast<size_t>(x) * 3 + c] = static_cast<float>(image.at(x, y)[c]);
      out.write(reinterpret_cast<const char*>(row.data()), static_cast<std::streamsize>(row.size() * sizeof(float)));
    }
    out.close();
    if (!out) throw UserError(path.string(), "cannot write PFM");
  });
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
    } catch (const std::exception& e) {
      throw UserError(path.string(), std::string("cannot write OpenEXR: ") + e.what());
    }
  });
}

}  // namespace radrecon
