#include "core/image.h"

#include <algorithm>
#include <cmath>

#include "core/check.h"

namespace radrecon {

Image::Image(int width, int height)
    : width_(width), height_(height), pixels_(static_cast<size_t>(width) * height, Rgb::Zero()) {
  RR_CHECK_GT(width, 0, "image width must be positive");
  RR_CHECK_GT(height, 0, "image height must be positive");
}

double srgb_encode(double linear) {
  return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

double tone_map(double radiosity_w_m2, double white_w_m2) {
  return std::clamp(radiosity_w_m2 / white_w_m2, 0.0, 1.0);
}

Image tone_mapped(const Image& linear, double white_w_m2) {
  Image display(linear.width(), linear.height());
  for (int y = 0; y < linear.height(); ++y)
    for (int x = 0; x < linear.width(); ++x)
      for (int c = 0; c < 3; ++c) display.at(x, y)[c] = tone_map(linear.at(x, y)[c], white_w_m2);
  return display;
}

}  // namespace radrecon
