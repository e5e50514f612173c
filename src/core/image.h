#pragma once
// A linear floating-point RGB image and its writers. Row 0 is the top row of the picture.

#include <filesystem>
#include <vector>

#include "core/vec.h"

namespace radrecon {

class Image {
 public:
  Image(int width, int height);
  int width() const { return width_; }
  int height() const { return height_; }
  Rgb& at(int x, int y) { return pixels_[static_cast<size_t>(y) * width_ + x]; }
  const Rgb& at(int x, int y) const { return pixels_[static_cast<size_t>(y) * width_ + x]; }

 private:
  int width_, height_;
  std::vector<Rgb> pixels_;
};

/// The sRGB transfer curve: a linear display value in [0,1] to its encoded value.
double srgb_encode(double linear);

/// Writes display values in [0,1] (clamped) as an 8-bit RGB PNG. With `srgb_encode` the values
/// are taken as linear and encoded with the sRGB transfer curve; without, written as they are.
void write_png(const std::filesystem::path& path, const Image& image, bool srgb_encode);

/// Writes the linear values as a colour PFM (32-bit floats, bottom row first as PFM requires).
void write_pfm(const std::filesystem::path& path, const Image& image);

/// Writes the linear values as an OpenEXR image (RGB, 16-bit half floats).
void write_exr(const std::filesystem::path& path, const Image& image);

}  // namespace radrecon
