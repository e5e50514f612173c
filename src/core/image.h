#pragma once
// A linear floating-point RGB image, and the one tone mapping of radrecon's pictures. Row 0 is
// the top row of the picture. Files are written by io/image_io.h.

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

/// The one tone mapping of radrecon's pictures: display = clamp(B / white_w_m2, 0, 1) (encode
/// with the sRGB curve when writing). `white_w_m2` (> 0) is the radiosity shown as white.
double tone_map(double radiosity_w_m2, double white_w_m2);

/// Every channel of every pixel through tone_map(): display values in [0,1], still linear.
Image tone_mapped(const Image& linear_w_m2, double white_w_m2);

}  // namespace radrecon
